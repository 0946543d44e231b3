//! The foreign-input fuzzer of `tests/fuzz_case.rs` (issue 42): it mutates the files from
//! elsewhere that the harness reads — a baseline and a run file, each first written by the harness
//! itself for a small case, and a deck folder's `steps.csv` — as text (the parent's mutations) and as data (a leaf replaced by an
//! edge value, an array cut or doubled), and plants the secret of `common::reads` in them as keys,
//! values and raw text.
//!
//! Every mutant is loaded in the process ([`Baseline::load`], [`merge::merge`], the deck's table
//! through [`readback::read_output`] and [`readback::parse_steps`]): no panic; an
//! error that holds neither the secret nor a raw control character; a baseline it accepts keeps
//! the promises of its check (finite values, steps and indices of the case), a run file it accepts
//! holds only histories on the case's path. One mutant in 100 also goes through the command line
//! (`verify --baselines`, `merge`, the secret also in the environment): exit code 0, 1 or 2 only,
//! the same two promises on its output. A failing input is written to `target/fuzz-crashers/`.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;

use super::common::reads::{raw_controls, spherecontact_guarded, text, SECRET};
use super::{mutate_text, Rng};
use spherecontact::baseline::{self, Baseline, Shape};
use spherecontact::case::ReadRoots;
use spherecontact::external::deck::ComputedStep;
use spherecontact::external::readback;
use spherecontact::merge;
use spherecontact::plan::{CaseOptions, Member};

/// The case: hertz and mdr on a short path, one check.
const CASE: &str = r#"
name = "fuzzed"
friction = 0.2
solvers = ["hertz", "mdr"]

[body1]
radius = 0.1
young = 70e9
poisson = 0.3

[path]
unit = "um"
delta_n = [0, 10, 10]
delta_t = [0, 0, 1]
substeps = 3

[[checks]]
solver = "mdr"
quantity = "normal_force"
at = "every-step"
reference = { solver = "hertz" }
tolerance = 1e-4
reason = "the bed's midpoint rule, about 1e-6"
"#;

/// A folder holding the case, its baseline (`b/fuzzed.toml`), its run (`out/run.json`) and, beside
/// them, a file of secrets.
struct Workspace {
    dir: tempfile::TempDir,
    case: Member,
    baseline: String,
    run_file: String,
}

impl Workspace {
    fn new() -> Self {
        let dir = tempfile::tempdir().unwrap();
        let at = |name: &str| dir.path().join(name);
        std::fs::write(at("case.toml"), CASE).unwrap();
        std::fs::write(at("secret.toml"), format!("token = \"{SECRET}\"\n{SECRET}\n")).unwrap();
        std::fs::create_dir(at("none")).unwrap();
        for args in [
            &["baseline", "update", "case.toml", "--baselines", "b"][..],
            &["verify", "case.toml", "--out", "out", "--baselines", "none"],
        ] {
            let output = super::common::spherecontact(args, dir.path());
            assert_eq!(output.status.code(), Some(0), "{}", text(&output));
        }
        let case = CaseOptions::default().load_member(&at("case.toml")).unwrap();
        Workspace {
            baseline: super::common::text(&at("b/fuzzed.toml")),
            run_file: super::common::text(&at("out/run.json")),
            dir,
            case,
        }
    }

    fn path(&self, name: &str) -> std::path::PathBuf {
        self.dir.path().join(name)
    }
}

/// Values that probe a baseline's or a run file's reader, the secret among them.
fn edge_value(rng: &mut Rng) -> serde_json::Value {
    let values = [
        serde_json::json!(SECRET),
        serde_json::json!(format!("../{SECRET}")),
        serde_json::json!("/proc/self/environ"),
        serde_json::json!("../secret.toml"),
        serde_json::json!(-1),
        serde_json::json!(0),
        serde_json::json!(1e300),
        serde_json::json!(-1e-300),
        serde_json::json!(u64::MAX),
        serde_json::json!(null),
        serde_json::json!(true),
        serde_json::json!([]),
        serde_json::json!({}),
        serde_json::json!("\u{1b}[2J\u{0}"),
    ];
    rng.pick(&values).clone()
}

/// Every leaf of `value` and every array, as a JSON pointer.
fn pointers(value: &serde_json::Value, at: String, out: &mut Vec<String>) {
    match value {
        serde_json::Value::Object(map) => map
            .iter()
            .for_each(|(k, v)| pointers(v, format!("{at}/{k}"), out)),
        serde_json::Value::Array(items) => {
            out.push(at.clone());
            items
                .iter()
                .enumerate()
                .for_each(|(i, v)| pointers(v, format!("{at}/{i}"), out));
        }
        _ => out.push(at),
    }
}

/// One mutation of `doc` as data: a leaf replaced, an array cut or doubled, a key planted.
fn mutate_data(doc: &mut serde_json::Value, rng: &mut Rng) {
    let mut all = Vec::new();
    pointers(doc, String::new(), &mut all);
    if all.is_empty() {
        *doc = edge_value(rng);
        return;
    }
    let pointer = rng.pick(&all).clone();
    let Some(target) = doc.pointer_mut(&pointer) else {
        return;
    };
    match (rng.below(4), target) {
        (0, serde_json::Value::Array(items)) if !items.is_empty() => {
            let keep = rng.below(items.len());
            items.truncate(keep);
        }
        (1, serde_json::Value::Array(items)) if !items.is_empty() => {
            let copy = items.clone();
            items.extend(copy);
        }
        (2, serde_json::Value::Object(map)) => {
            map.insert(SECRET.to_owned(), serde_json::json!(1));
        }
        (_, target) => *target = edge_value(rng),
    }
}

/// A mutant of the text `seed`, structured as `json` or TOML data where it parses.
fn mutant(seed: &str, json: bool, rng: &mut Rng) -> String {
    let mut text = seed.to_owned();
    for _ in 0..1 + rng.below(3) {
        let parsed: Option<serde_json::Value> = if json {
            serde_json::from_str(&text).ok()
        } else {
            toml::from_str::<toml::Value>(&text)
                .ok()
                .and_then(|t| serde_json::to_value(t).ok())
        };
        text = match (rng.below(3), parsed) {
            (0 | 1, Some(mut doc)) => {
                mutate_data(&mut doc, rng);
                let written = if json {
                    serde_json::to_string(&doc).ok()
                } else {
                    toml::to_string(&doc).ok()
                };
                written.unwrap_or(text)
            }
            (2, _) if rng.below(2) == 0 => {
                let at = rng.below(text.len() + 1);
                let at = (0..=at).rev().find(|&i| text.is_char_boundary(i)).unwrap_or(0);
                format!("{}{SECRET} = \"{SECRET}\"\n{}", &text[..at], &text[at..])
            }
            _ => mutate_text(&text, &[seed.to_owned()], rng),
        };
    }
    text
}

/// What a user would see of `error` must hold neither the secret nor a raw control character.
fn leak(shown: &str) -> Option<String> {
    if shown.contains(SECRET) {
        return Some(format!("the secret is shown: {shown}"));
    }
    let controls = raw_controls(shown);
    (!controls.is_empty()).then(|| format!("raw control characters {controls:?} in: {shown}"))
}

/// Loads a mutated baseline; the broken promise, if any.
fn judge_baseline(work: &Workspace, shape: &Shape) -> Option<String> {
    match catch_unwind(AssertUnwindSafe(|| Baseline::load(&work.path("b"), shape))) {
        Err(_) => Some("panicked".into()),
        Ok(Err(e)) => leak(&e.to_string()),
        Ok(Ok(None)) => Some("the baseline vanished".into()),
        Ok(Ok(Some(b))) => b
            .checks
            .iter()
            .find(|c| {
                c.values.is_empty()
                    || c.values.iter().any(|v| !v.1.is_finite() || v.0 >= shape.steps)
                    || c.values.windows(2).any(|w| w[0].0 >= w[1].0)
                    || c.index >= shape.checks.len()
            })
            .map(|c| format!("accepted an entry off its case: {c:?}")),
    }
}

/// Merges a mutated run file; the broken promise, if any.
fn judge_run_file(work: &Workspace) -> Option<String> {
    let roots = ReadRoots::default();
    let merged = catch_unwind(AssertUnwindSafe(|| merge::merge(&[work.path("out")], &roots)));
    match merged {
        Err(_) => Some("panicked".into()),
        Ok(Err(e)) => leak(&e.to_string()),
        Ok(Ok(merged)) => {
            let Member::Path(case) = &merged.plan.cases[0] else {
                return Some("the case changed kind".into());
            };
            let steps = case.scene.steps();
            merged.finished.iter().find_map(|f| match &f.result {
                spherecontact::schedule::Output::Path(Ok(h)) => spherecontact::solver::validate(h, &steps)
                    .err()
                    .map(|why| format!("accepted a history off its path: {why}")),
                _ => None,
            })
        }
    }
}

/// The command line on the mutant in place: exit code 0, 1 or 2, nothing leaked.
fn judge_command_line(work: &Workspace, run_file: bool) -> Option<String> {
    let args: &[&str] = if run_file {
        &["merge", "out", "--baselines", "none"]
    } else {
        &["verify", "case.toml", "--baselines", "b"]
    };
    // The harness reads its files from the folder it runs in.
    let output = spherecontact_guarded(args, work.dir.path());
    let shown = text(&output);
    match output.status.code() {
        Some(0..=2) => leak(&shown),
        code => Some(format!("exit {code:?}: {shown}")),
    }
}

/// A deck's `steps.csv` for two computed steps (as `readback`'s own tests write it).
const STEPS: &str = "step,d_mm,t_mm,P_contact_N,P_top_N,Q_N,iterations_normal,iterations_tangential,outcome,\
                     field_file\n4,0.0085,0,806.56,,0,3,2,1,-\n5,0.0085,0.0005,806.56,806.77,98.8,0,4,2,field_2.vtu\n";

/// The steps [`STEPS`] answers.
fn asked() -> Vec<ComputedStep> {
    let step = |step, t, position| ComputedStep {
        step,
        d: 8.5e-6,
        t,
        position,
    };
    vec![step(4, 0.0, None), step(5, 5e-7, Some(2))]
}

/// Reads a mutated `steps.csv` as `deck read` does; the broken promise, if any.
fn judge_steps(work: &Workspace) -> Option<String> {
    let read = catch_unwind(AssertUnwindSafe(|| {
        readback::read_output(&work.path("deck"), "steps.csv", 1 << 20)
            .and_then(|text| readback::parse_steps(&text, &asked()).map(|_| ()))
    }));
    match read {
        Err(_) => Some("panicked".into()),
        Ok(Err(e)) => leak(&e),
        Ok(Ok(())) => None,
    }
}

/// What a mutant is of.
#[derive(Clone, Copy)]
enum Target {
    Baseline,
    RunFile,
    Steps,
}

/// `iterations` mutants, in turn of the baseline, the run file and the deck's table, from `seed`.
pub fn fuzz(seed: u64, iterations: u64) {
    let work = Workspace::new();
    std::fs::create_dir(work.path("deck")).unwrap();
    let shape = baseline::Shape::of(&work.case);
    let mut rng = Rng(seed);
    let mut failures = Vec::new();
    for k in 0..iterations {
        let target = [Target::Baseline, Target::RunFile, Target::Steps][(k % 3) as usize];
        let (input, file) = match target {
            Target::Baseline => (mutant(&work.baseline, false, &mut rng), "b/fuzzed.toml"),
            Target::RunFile => (mutant(&work.run_file, true, &mut rng), "out/run.json"),
            Target::Steps => {
                let text = mutate_text(STEPS, &[STEPS.to_owned()], &mut rng);
                let planted = text.replacen(',', &format!(",{SECRET},"), 1 + rng.below(3));
                (if rng.below(2) == 0 { planted } else { text }, "deck/steps.csv")
            }
        };
        std::fs::write(work.path(file), &input).unwrap();
        let broken = match target {
            Target::Baseline => judge_baseline(&work, &shape),
            Target::RunFile => judge_run_file(&work),
            Target::Steps => judge_steps(&work),
        };
        let run_file = matches!(target, Target::RunFile);
        let through_command_line = !matches!(target, Target::Steps) && rng.below(100) == 0;
        let broken = broken.or_else(|| {
            through_command_line
                .then(|| judge_command_line(&work, run_file))
                .flatten()
        });
        if let Some(why) = broken {
            failures.push(keep(&input, file, &why));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {iterations} inputs broke a promise:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// Writes a failing input to `target/fuzz-crashers/` and says where.
fn keep(input: &str, file: &str, why: &str) -> String {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/fuzz-crashers");
    std::fs::create_dir_all(&dir).unwrap();
    let digest = spherecontact::runfile::digest(input.as_bytes());
    let extension = Path::new(file)
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("txt");
    let name = format!("foreign-{}.{extension}", &digest[7..23]);
    std::fs::write(dir.join(&name), input).unwrap();
    format!("{name}: {why}")
}
