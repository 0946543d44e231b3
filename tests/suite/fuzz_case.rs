//! A seeded, structure-aware mutation fuzzer for the case parser and validator (stable Rust: no
//! libFuzzer). The corpus is every shipped case and every hostile test case; each iteration takes
//! one, mutates it a few times — as TOML (replace, drop, add or swap values, grow or cut arrays)
//! or as text (flip, cut, splice, insert tokens) — and feeds it to `Case::parse`.
//!
//! Every input must give a case or a `CaseError`, never a panic. A case it accepts must keep the
//! promises of validation (finite values within their ranges, bounded increments and fields, a
//! plain name), and the cheap in-crate solvers (closed forms, DEM laws, MDR on a coarse bed) must
//! solve it without a panic or a non-finite value. A failing input is written to
//! `target/fuzz-crashers/` and fails the test; it then becomes a regular test.
//!
//! The read fuzzer ([`fuzz_reads`], `tests/suite/fuzz_case/fuzz_reads/mod.rs`) mutates the sections that name
//! files (stored results, reference values) and the texts a case shows, in a project folder with
//! secrets beside it, links, a FIFO and a sparse file: no panic, exit code 0/1/2 only, nothing of a
//! file outside the case's tree and no raw control character in any output (docs/security.md).
//!
//! The foreign-input fuzzer ([`fuzz_foreign`]) mutates a baseline, a run file and a deck's table,
//! the secret planted in them: no panic, no leak, nothing accepted that does not fit its case.
//!
//! In CI (`cargo test`): 60 000 iterations from seeds 1 and 24 302, in two halves run in parallel
//! (about 40 s on two cores in the dev profile). By hand, longer, with another seed:
//!
//! ```sh
//! FUZZ_ITERATIONS=2000000 FUZZ_SEED=7 cargo test --release --test suite fuzz_case:: -- --nocapture
//! FUZZ_SECONDS=3600 FUZZ_SEED=8 cargo test --release --test suite fuzz_case:: -- --nocapture
//! ```

use crate::common;
mod fuzz_commands;
mod fuzz_foreign;
mod fuzz_reads;

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use spherecontact::analytic::mdr::Mdr;
use spherecontact::case::limits::{self, MAX_FIELD_POSITIONS, MAX_INCREMENTS};
use spherecontact::case::Case;
use spherecontact::registry;
use spherecontact::scene::FieldPositions;
use spherecontact::solver::{self, SolveError, Solver};

/// SplitMix64: a small, good, seedable generator (Steele, Lea & Flood 2014).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// A number in 0..n (n ≥ 1).
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

/// Values that probe the validator's edges.
const FLOATS: &[f64] = &[
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.5,
    -0.5,
    0.499_999_999_999_999_94,
    -0.999_999_999_999_999_9,
    10.0,
    10.000_000_000_000_002,
    5e-324,
    1e-308,
    2.2e-308,
    1e-300,
    1e-13,
    1e-9,
    1e3,
    1e13,
    1.000_000_000_000_000_2e13,
    1.7e308,
    -1.7e308,
    f64::MAX,
    f64::MIN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::NAN,
    1e-6,
    17.0,
    0.1,
    100_000.0,
    1e5 + 1.0,
];
const INTEGERS: &[i64] = &[
    0,
    1,
    -1,
    2,
    3,
    16,
    17,
    1_000_000,
    1_000_001,
    i64::MAX,
    i64::MIN,
    4_000_000_000,
];
const STRINGS: &[&str] = &[
    "",
    "um",
    "µm",
    "μm",
    "mm",
    "m",
    "inch",
    "../../../escaped",
    "x/..",
    "..",
    ".",
    "a\nb",
    "-rf",
    "every-position",
    "every-step",
    "focus",
    "hertz",
    "mdr",
    "bem",
    "fem-axisym",
    "normal_force",
    "stick_radius",
    "relative",
    "absolute",
    "../reference/hertz.toml",
    "/dev/zero",
    "/etc",
    "\u{0}",
    "ü",
    "🦀",
];
const TOKENS: &[&str] = &[
    "nan",
    "inf",
    "-inf",
    "1e308",
    "5e-324",
    "-0.0",
    "[",
    "]",
    "{",
    "}",
    "\"",
    "'",
    "=",
    ",",
    "\n",
    "\n[[checks]]\n",
    "\n[body2]\n",
    "[path]",
    "#",
    "\"\"\"",
    "99999999999999999999",
    "1_000_000",
    "0x10",
    "μ",
    "\u{feff}",
    "\r\n",
    "\t",
    "true",
    "1979-05-27T07:32:00Z",
];

/// A random leaf value.
fn interesting_value(rng: &mut Rng) -> toml::Value {
    match rng.below(6) {
        0 | 1 => toml::Value::Float(*rng.pick(FLOATS)),
        2 => toml::Value::Integer(*rng.pick(INTEGERS)),
        3 => toml::Value::String((*rng.pick(STRINGS)).to_owned()),
        4 => toml::Value::Boolean(rng.below(2) == 0),
        _ => {
            let n = rng.below(40);
            let item = toml::Value::Float(*rng.pick(FLOATS));
            toml::Value::Array(vec![item; n])
        }
    }
}

/// Every path to a value of `value` (keys and array indices), depth first.
fn leaf_paths(value: &toml::Value, prefix: &mut Vec<String>, out: &mut Vec<Vec<String>>) {
    match value {
        toml::Value::Table(t) => {
            for (k, v) in t {
                prefix.push(k.clone());
                out.push(prefix.clone());
                leaf_paths(v, prefix, out);
                prefix.pop();
            }
        }
        toml::Value::Array(a) => {
            for (i, v) in a.iter().enumerate().take(8) {
                prefix.push(format!("#{i}"));
                out.push(prefix.clone());
                leaf_paths(v, prefix, out);
                prefix.pop();
            }
        }
        _ => {}
    }
}

fn at_path<'a>(value: &'a mut toml::Value, path: &[String]) -> Option<&'a mut toml::Value> {
    path.iter()
        .try_fold(value, |v, key| match (v, key.strip_prefix('#')) {
            (toml::Value::Array(a), Some(i)) => a.get_mut(i.parse::<usize>().ok()?),
            (toml::Value::Table(t), None) => t.get_mut(key),
            _ => None,
        })
}

/// One structural mutation of a parsed document.
fn mutate_structure(doc: &mut toml::Value, rng: &mut Rng) {
    let mut paths = Vec::new();
    leaf_paths(doc, &mut Vec::new(), &mut paths);
    if paths.is_empty() {
        return;
    }
    let path = rng.pick(&paths).clone();
    match rng.below(6) {
        0 | 1 => {
            if let Some(v) = at_path(doc, &path) {
                *v = interesting_value(rng);
            }
        }
        2 => {
            // Drop the key or element.
            let (last, parent) = path.split_last().unwrap();
            match (at_path(doc, parent), last.strip_prefix('#')) {
                (Some(toml::Value::Table(t)), None) => {
                    t.remove(last);
                }
                (Some(toml::Value::Array(a)), Some(i)) => {
                    a.remove(i.parse().unwrap());
                }
                _ => {}
            }
        }
        3 => {
            // Grow or cut an array, or add an unknown key to a table.
            match at_path(doc, &path) {
                Some(toml::Value::Array(a)) if !a.is_empty() && rng.below(2) == 0 => {
                    let n = rng.below(a.len() * 3 + 1);
                    let copy = a[rng.below(a.len())].clone();
                    a.resize(n, copy);
                }
                Some(toml::Value::Table(t)) => {
                    t.insert((*rng.pick(STRINGS)).to_owned(), interesting_value(rng));
                }
                _ => {}
            }
        }
        4 => {
            // Swap two values.
            let other = rng.pick(&paths).clone();
            let a = at_path(doc, &path).cloned();
            let b = at_path(doc, &other).cloned();
            if let (Some(a), Some(b)) = (a, b) {
                if let Some(v) = at_path(doc, &path) {
                    *v = b;
                }
                if let Some(v) = at_path(doc, &other) {
                    *v = a;
                }
            }
        }
        _ => {
            // A numeric value nudged by a factor.
            if let Some(toml::Value::Float(x)) = at_path(doc, &path) {
                *x *= *rng.pick(&[1e-3, 1e3, -1.0, 1.0 + f64::EPSILON, 1e300, 1e-300]);
            }
        }
    }
}

/// One textual mutation.
fn mutate_text(text: &str, corpus: &[String], rng: &mut Rng) -> String {
    let chars: Vec<char> = text.chars().collect();
    if chars.is_empty() {
        return (*rng.pick(TOKENS)).to_owned();
    }
    let at = rng.below(chars.len());
    let span = 1 + rng.below(16);
    let head: String = chars[..at].iter().collect();
    let tail: String = chars[(at + span).min(chars.len())..].iter().collect();
    match rng.below(5) {
        0 => format!(
            "{head}{}{}",
            rng.pick(TOKENS),
            chars[at..].iter().collect::<String>()
        ),
        1 => format!("{head}{tail}"),
        2 => {
            let c = char::from_u32(rng.below(0x3000) as u32).unwrap_or('\u{fffd}');
            format!("{head}{c}{tail}")
        }
        3 => {
            // Splice a line of another corpus file.
            let donor = rng.pick(corpus);
            let lines: Vec<&str> = donor.lines().collect();
            let line = lines.get(rng.below(lines.len().max(1))).copied().unwrap_or("");
            format!("{head}\n{line}\n{}", chars[at..].iter().collect::<String>())
        }
        _ => head, // truncate
    }
}

/// A mutant of `seed`: one mutation half of the time (mutants that stay valid reach the
/// solvers), else 2 to 4; structural where the text parses as TOML.
fn mutant(seed: &str, corpus: &[String], rng: &mut Rng) -> String {
    let mut text = seed.to_owned();
    let count = if rng.below(2) == 0 { 1 } else { 2 + rng.below(3) };
    for _ in 0..count {
        text = match (rng.below(3), toml::from_str::<toml::Value>(&text)) {
            (0 | 1, Ok(mut doc)) => {
                mutate_structure(&mut doc, rng);
                toml::to_string(&doc).unwrap_or(text)
            }
            _ => mutate_text(&text, corpus, rng),
        };
    }
    text
}

/// What a validated case promises; returns the broken promise, if any.
fn broken_promise(case: &Case) -> Option<String> {
    let scene = &case.scene;
    let positions = scene.path.positions();
    let increments: usize = scene.path.substeps().iter().sum();
    let r_min = scene.pair.body1.radius.min(scene.pair.body2.radius);
    let fine = |v: f64| v.is_normal() && v > 0.0;
    let pair = &scene.pair;
    if increments > MAX_INCREMENTS {
        return Some(format!("{increments} increments"));
    }
    if !limits::is_plain_name(&scene.name) {
        return Some(format!("name {:?}", scene.name));
    }
    if !(0.0..=limits::MAX_FRICTION).contains(&scene.friction) {
        return Some(format!("μ = {}", scene.friction));
    }
    if let Some(p) = positions
        .iter()
        .find(|p| !(p.delta_n.abs() <= r_min && p.delta_t.abs() <= r_min))
    {
        return Some(format!("position {p:?} beyond R_min = {r_min}"));
    }
    if ![
        pair.effective_modulus(),
        pair.effective_radius(),
        pair.mindlin_shear_modulus(),
    ]
    .into_iter()
    .all(fine)
    {
        return Some("E*, R* or G* not normal".into());
    }
    let delta = scene.path.max_approach();
    if delta > 0.0 && !fine(scene.hertz().force(delta)) {
        return Some(format!("Hertz force at δn = {delta:e} not normal"));
    }
    if case.focus >= positions.len() {
        return Some(format!("focus {}", case.focus));
    }
    let with_fields = match &scene.fields {
        FieldPositions::Every => positions.len(),
        FieldPositions::Listed(list) => list.len(),
    };
    if with_fields > MAX_FIELD_POSITIONS || !scene.records_fields_at(case.focus) {
        return Some(format!(
            "{with_fields} positions with fields, focus among them: no"
        ));
    }
    None
}

/// The cheap in-crate solvers: closed forms, DEM laws, and MDR on a coarse bed.
fn cheap_solvers() -> Vec<Box<dyn Solver>> {
    let mut solvers: Vec<Box<dyn Solver>> = registry::in_crate()
        .into_iter()
        .filter(|s| !["mdr", "bem", "fem-axisym", "mdr-domain"].contains(&s.name()))
        .collect();
    solvers.push(Box::new(Mdr { springs: 200 }));
    solvers
}

/// The length of a run of more than 24 digits in `message` that `input` does not hold: a
/// number printed as a long decimal (`5e-324` as 324 digits) rather than echoed from the input.
fn long_number_not_in(message: &str, input: &str) -> Option<usize> {
    message
        .split(|c: char| !c.is_ascii_digit())
        .find(|run| run.len() > 24 && !input.contains(run))
        .map(str::len)
}

/// How the inputs fared.
#[derive(Default)]
struct Tally {
    accepted: u64,
    solved: u64,
    rejected: u64,
    located: u64,
}

/// What is wrong with the outcome of one input, if anything.
fn judge(text: &str, solvers: &[Box<dyn Solver>], tally: &mut Tally) -> Option<String> {
    let file = Path::new("fuzz.toml");
    let parsed = catch_unwind(AssertUnwindSafe(|| Case::parse(file, text)));
    let case = match parsed {
        Err(_) => return Some("Case::parse panicked".into()),
        Ok(Err(e)) => {
            tally.rejected += 1;
            if e.location.is_some() {
                tally.located += 1;
            }
            let lines = text.lines().count() + 1;
            return match e.location {
                Some((line, _)) if line > lines => Some(format!("located past the end: {e}")),
                _ if e.message.is_empty() => Some("an empty message".into()),
                _ if e.to_string().len() > 2_000 => {
                    Some(format!("a message of {} bytes", e.to_string().len()))
                }
                _ => long_number_not_in(&e.message, text).map(|n| format!("{n}-digit number in: {e}")),
            };
        }
        Ok(Ok(case)) => case,
    };
    tally.accepted += 1;
    if let Some(broken) = broken_promise(&case) {
        return Some(format!("accepted, but {broken}"));
    }
    if case.scene.path.substeps().iter().sum::<usize>() > 2_000 {
        return None; // long paths: the solvers' cost, not the validator's, would dominate
    }
    for s in solvers {
        match solver::run(s.as_ref(), &case.scene) {
            Ok(_) | Err(SolveError::NotApplicable(_)) => {}
            Err(e) => return Some(format!("{}: {e}", s.name())),
        }
    }
    tally.solved += 1;
    None
}

/// The corpus: every shipped case and every hostile test case.
fn corpus() -> Vec<String> {
    let mut files = common::all_case_files();
    for folder in ["extreme", "malformed", "valid", "reads"] {
        let dir = common::root().join("tests/hostile").join(folder);
        files.extend(std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()));
    }
    files.sort();
    files
        .iter()
        .map(|f| std::fs::read_to_string(f).unwrap())
        .collect()
}

fn env_number(name: &str) -> Option<u64> {
    std::env::var(name)
        .ok()
        .map(|v| v.parse().unwrap_or_else(|_| panic!("{name}={v}")))
}

/// Runs `iterations` (or until `seconds` pass) from `seed`; writes crashers and fails on any.
fn fuzz(seed: u64, iterations: u64) {
    let deadline = env_number("FUZZ_SECONDS").map(|s| Instant::now() + Duration::from_secs(s));
    let corpus = corpus();
    let solvers = cheap_solvers();
    let mut rng = Rng(seed);
    let mut tally = Tally::default();
    let mut crashers: Vec<PathBuf> = Vec::new();
    let start = Instant::now();
    let mut done = 0;
    // Panics are caught and judged; the default hook would print each one on top.
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    while deadline.map_or(done < iterations, |d| Instant::now() < d) {
        let k = rng.below(corpus.len());
        let text = mutant(&corpus[k], &corpus, &mut rng);
        if let Some(problem) = judge(&text, &solvers, &mut tally) {
            let dir = common::root().join("target/fuzz-crashers");
            std::fs::create_dir_all(&dir).unwrap();
            let file = dir.join(format!("seed{seed}-{done}.toml"));
            std::fs::write(&file, format!("# {}\n{text}", problem.replace('\n', " "))).unwrap();
            crashers.push(file);
        }
        done += 1;
    }
    std::panic::set_hook(hook);
    eprintln!(
        "fuzz: seed {seed}: {done} inputs in {:.1} s: {} accepted ({} solved by the cheap solvers), \
         {} rejected ({} located), {} crashers",
        start.elapsed().as_secs_f64(),
        tally.accepted,
        tally.solved,
        tally.rejected,
        tally.located,
        crashers.len()
    );
    assert!(crashers.is_empty(), "crashers written: {crashers:?}");
}

/// The CI run: a fixed seed and count, split in two halves so that both cores work.
#[test]
#[ignore = "heavy: 30 000 mutated case files, 5 s on an idle core; .ci/run runs it (docs/verification-at-scale.md, \"A fast test command\")"]
fn fuzz_the_case_parser_first_half() {
    let seed = env_number("FUZZ_SEED").unwrap_or(1);
    fuzz(seed, env_number("FUZZ_ITERATIONS").unwrap_or(60_000) / 2);
}

#[test]
#[ignore = "heavy: 30 000 mutated case files, 5 s on an idle core; .ci/run runs it (docs/verification-at-scale.md, \"A fast test command\")"]
fn fuzz_the_case_parser_second_half() {
    let seed = env_number("FUZZ_SEED").unwrap_or(1).wrapping_add(0x5eed);
    fuzz(seed, env_number("FUZZ_ITERATIONS").unwrap_or(60_000) / 2);
}

/// The read fuzzer ([`fuzz_reads`]): the sections that name files and the texts a case shows.
/// `FUZZ_READ_ITERATIONS` (default 10 000) inputs.
#[test]
fn fuzz_the_files_a_case_names() {
    let seed = env_number("FUZZ_SEED").unwrap_or(1).wrapping_add(0x4ead);
    fuzz_reads::fuzz(
        seed,
        env_number("FUZZ_READ_ITERATIONS").unwrap_or(10_000),
        &corpus(),
    );
}

/// The command sections a case may hold, mutated: nothing runs without the opt-in
/// (`FUZZ_COMMAND_ITERATIONS`, default 400 inputs; one in 40 also through the command line).
#[test]
fn fuzz_the_commands_a_case_names() {
    let seed = env_number("FUZZ_SEED").unwrap_or(1).wrapping_add(0xc0de);
    fuzz_commands::fuzz(seed, env_number("FUZZ_COMMAND_ITERATIONS").unwrap_or(400));
}

/// The files from elsewhere, mutated: baselines, run files and a deck's table (`FUZZ_FOREIGN_ITERATIONS`,
/// default 1 500 inputs; one in 100 also through the command line).
#[test]
fn fuzz_the_files_from_elsewhere() {
    let seed = env_number("FUZZ_SEED").unwrap_or(1).wrapping_add(0xf0e1);
    fuzz_foreign::fuzz(seed, env_number("FUZZ_FOREIGN_ITERATIONS").unwrap_or(1_500));
}
