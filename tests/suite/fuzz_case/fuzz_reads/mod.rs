//! The read fuzzer of `tests/fuzz_case.rs`: it mutates the sections of a case that name files
//! (`[[stored_results]]` `file`, a check's reference `file`) and the texts a case shows
//! (description, reason, names), in a project folder that holds what a hostile case reaches for:
//! files beside the project holding a secret, links that lead out and in, a FIFO, a sparse 5 GiB
//! file, a folder, `/dev/zero`, `/proc/self/environ`, names with `..`, absolute names and control
//! characters.
//!
//! Every input is loaded in the process (no panic; a case or an error; a case reads no file outside
//! its tree, each name resolved here on its own) and, when it loads, verified
//! with its solvers (hertz and the stored results); every text a user would see (the error, the
//! `verify` rows, the summary, JUnit, one in ten times the compare report) must hold neither the
//! secret nor a raw control character. One input in 50 is also run through the command line
//! (`verify`, the secret also in its environment): exit code 0, 1 or 2 only, and the same two
//! promises on its output. A failing input is written to `target/fuzz-crashers/`.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};

use super::common::reads::{raw_controls, spherecontact_guarded, symlink, text, Project, SECRET};
use super::Rng;
use spherecontact::case::{Case, CaseSolver, ReadRoots};
use spherecontact::check::Reference;
use spherecontact::report::{compare, junit, summary};
use spherecontact::verify;
use spherecontact::verify::table;

/// Names a hostile case gives its files (relative to `project/cases/`); `@ABS@` stands for the
/// temporary folder that holds the project and the secrets.
const NAMES: &[&str] = &[
    "data/good.csv",
    "data/link-in.csv",
    "data/link-out.csv",
    "data/fifo.csv",
    "data/sparse.csv",
    "data/zero",
    "data/folder",
    "data/../data/good.csv",
    "./data/good.csv",
    "../../secret.csv",
    "../../secret.toml",
    "../../outside.csv",
    "@ABS@/outside.csv",
    "data/link-outside.csv",
    "@ABS@/secret.csv",
    "@ABS@/secret.toml",
    "@ABS@/project/cases/data/good.csv",
    "@ABS@/project/reference/values.toml",
    "../reference/values.toml",
    "../reference/link.toml",
    "../reference/../../secret.toml",
    "/proc/self/environ",
    "/proc/self/cmdline",
    "/dev/zero",
    "/dev/stdin",
    "/etc/passwd",
    "/",
    "",
    ".",
    "..",
    "data",
    "data/good.csv\u{0}",
    "data/\u{1b}[2Kgood.csv",
    "data/good.csv\n[[checks]]",
];

/// Texts that try to redraw the terminal or hide in a report.
const CONTROLS: &[&str] = &[
    "\u{1b}[2K\rOK    forged",
    "\u{1b}[1A",
    "\r",
    "\u{8}\u{8}\u{8}",
    "\u{7f}",
    "\u{85}",
    "\u{202e}",
    "\u{feff}",
    "\n",
    "\t",
    "\u{0}",
    "\u{1b}]0;title\u{7}",
];

/// The project folder with its hostile files.
fn hostile_project() -> Project {
    let p = Project::new();
    let data = p.cases().join("data");
    symlink(&data.join("good.csv"), &data.join("link-in.csv"));
    symlink(&p.dir.path().join("secret.csv"), &data.join("link-out.csv"));
    symlink(&p.dir.path().join("outside.csv"), &data.join("link-outside.csv"));
    symlink(Path::new("/dev/zero"), &data.join("zero"));
    symlink(
        &p.dir.path().join("secret.toml"),
        &p.project().join("reference/link.toml"),
    );
    std::fs::create_dir(data.join("folder")).unwrap();
    let made = std::process::Command::new("mkfifo")
        .arg(data.join("fifo.csv"))
        .status()
        .unwrap();
    assert!(made.success());
    std::fs::File::create(data.join("sparse.csv"))
        .unwrap()
        .set_len(5 << 30)
        .unwrap();
    p
}

/// A name from [`NAMES`], sometimes behind a run of `../` or with a control character.
fn name(rng: &mut Rng, abs: &str) -> String {
    let mut name = rng.pick(NAMES).replace("@ABS@", abs);
    match rng.below(6) {
        0 => name = format!("{}{name}", "../".repeat(rng.below(12))),
        1 => name.push_str(*rng.pick(CONTROLS)),
        _ => {}
    }
    name
}

/// `table[key]`, when the document has that table.
fn entry<'a>(doc: &'a mut toml::Value, path: &[&str]) -> Option<&'a mut toml::Value> {
    path.iter()
        .try_fold(doc, |v, key| match (v, key.parse::<usize>()) {
            (toml::Value::Array(a), Ok(i)) => a.get_mut(i),
            (toml::Value::Table(t), _) => t.get_mut(*key),
            _ => None,
        })
}

/// A mutant of the base case: 1 to 3 changes to its file names and texts, then, one time in four,
/// the general mutations of the case fuzzer on top.
fn mutant(base: &toml::Value, abs: &str, rng: &mut Rng, corpus: &[String]) -> String {
    let mut doc = base.clone();
    for _ in 0..1 + rng.below(3) {
        let (path, value): (&[&str], String) = match rng.below(6) {
            0 | 1 => (&["stored_results", "0", "file"], name(rng, abs)),
            2 => (&["checks", "1", "reference", "file"], name(rng, abs)),
            3 => (&["description"], format!("case{}", rng.pick(CONTROLS))),
            4 => (
                &["checks", "0", "reason"],
                format!("reason{}NOOK", rng.pick(CONTROLS)),
            ),
            _ => (
                &["stored_results", "0", "description"],
                rng.pick(CONTROLS).to_string(),
            ),
        };
        if let Some(v) = entry(&mut doc, path) {
            *v = toml::Value::String(value);
        } else if let Some(toml::Value::Table(t)) = entry(&mut doc, &path[..path.len() - 1]) {
            t.insert(path[path.len() - 1].to_owned(), toml::Value::String(value));
        }
    }
    let text = toml::to_string(&doc).expect("a TOML document");
    if rng.below(4) == 0 {
        super::mutant(&text, corpus, rng)
    } else {
        text
    }
}

/// What is wrong with the texts a user would see, if anything.
fn leaks(what: &str, shown: &str) -> Option<String> {
    if shown.contains(SECRET) {
        return Some(format!("{what}: the secret is shown"));
    }
    let raw = raw_controls(shown);
    (!raw.is_empty()).then(|| format!("{what}: raw control characters {raw:?}"))
}

/// The solvers a loaded input may run here: closed forms, DEM laws and stored results (a mutant
/// that names a costly or external solver, a command, or a long path is judged on its loading).
const CHEAP: &[&str] = &[
    "hertz",
    "cattaneo-mindlin",
    "hertz-mindlin-spring",
    "thornton",
    "walton-braun",
];

fn cheap(case: &Case) -> bool {
    let stored = |name: &str| {
        case.own_solvers
            .iter()
            .any(|s| s.name() == name && matches!(s, CaseSolver::Stored(_)))
    };
    case.scene.path.substeps().iter().sum::<usize>() <= 2_000
        && case
            .required_solvers()
            .iter()
            .all(|name| CHEAP.contains(&name.as_str()) || stored(name))
}

/// How the inputs fared.
#[derive(Default)]
struct Tally {
    refused: u64,
    verified: u64,
    loaded_only: u64,
    commands: u64,
}

/// The file a loaded case reads from outside its tree (`project/cases/`, `project/reference/`),
/// if any: its stored results and its reference files, resolved here on their own.
fn read_outside(case: &Case, project: &Path) -> Option<String> {
    let inside = |file: &Path| {
        file.canonicalize()
            .is_ok_and(|f| f.starts_with(project.join("cases")) || f.starts_with(project.join("reference")))
    };
    let stored = case.own_solvers.iter().filter_map(|s| match s {
        CaseSolver::Stored(s) => Some(s.file.clone()),
        CaseSolver::Command(_) => None,
    });
    let references = case.checks.iter().filter_map(|c| match &c.reference {
        Reference::Value { key, .. } => Some(project.join("cases").join(key.rsplit_once('#')?.0)),
        Reference::Solver(_) => None,
    });
    let mut files = stored.chain(references);
    files
        .find(|f| !inside(f))
        .map(|f| format!("read {} outside the tree", f.display()))
}

/// Loads and verifies one input in the process: what is wrong with it, if anything, and whether
/// the command line may run it (it does not load, or its solvers are cheap).
fn judge(project: &Path, text: &str, report: bool, tally: &mut Tally) -> (Option<String>, bool) {
    let file = project.join("cases/fuzz.toml");
    let loaded = catch_unwind(AssertUnwindSafe(|| {
        Case::parse_with(&file, text, &ReadRoots::default())
    }));
    let case = match loaded {
        Err(_) => return (Some("Case::parse panicked".into()), false),
        Ok(Err(e)) => {
            tally.refused += 1;
            return (leaks("the error", &e.to_string()), true);
        }
        Ok(Ok(case)) if read_outside(&case, project).is_some() => {
            return (read_outside(&case, project), false);
        }
        Ok(Ok(case)) if !cheap(&case) => {
            tally.loaded_only += 1;
            return (None, false);
        }
        Ok(Ok(case)) => case,
    };
    tally.verified += 1;
    (verified(case, report), true)
}

/// What is wrong with what a user sees of the verification of `case`, if anything.
fn verified(case: Case, report: bool) -> Option<String> {
    let run = match catch_unwind(AssertUnwindSafe(|| verify::run_case(case))) {
        Err(_) => return Some("verify panicked".into()),
        Ok(run) => run,
    };
    let mut shown = vec![
        ("verify", table::case_block(&run)),
        ("the summary", summary::screen(&run)),
        ("JUnit", junit::document(&[table::suite(&run)], false)),
    ];
    if report {
        match compare::document(&run) {
            Ok(d) => shown.extend([("report.md", d.to_markdown()), ("report.html", d.to_html())]),
            Err(e) => return Some(format!("compare failed: {e}")),
        }
    }
    shown.iter().find_map(|(what, text)| leaks(what, text))
}

/// Runs one input through `verify` on the command line; what is wrong, if anything.
fn judge_command(p: &Project, file: &Path) -> Option<String> {
    let output = spherecontact_guarded(&["verify", file.to_str().unwrap()], &p.project());
    match output.status.code() {
        Some(0..=2) => leaks("the command line", &text(&output)),
        code => Some(format!("exit code {code:?}: {}", text(&output))),
    }
}

/// Runs `iterations` inputs from `seed`; writes crashers and fails on any.
pub fn fuzz(seed: u64, iterations: u64, corpus: &[String]) {
    let p = hostile_project();
    let abs = p.dir.path().to_str().unwrap().to_owned();
    let base: toml::Value = toml::from_str(
        &std::fs::read_to_string(super::common::reads::hostile("base.toml"))
            .unwrap()
            .replace("@STORED@", "data/good.csv")
            .replace("@REFERENCE@", "../reference/values.toml"),
    )
    .unwrap();
    let project = p.project().canonicalize().unwrap();
    let file = project.join("cases/fuzz.toml");
    let mut rng = Rng(seed);
    let mut crashers: Vec<PathBuf> = Vec::new();
    let mut tally = Tally::default();
    // Panics are caught and judged; the default hook would print each one on top.
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    for done in 0..iterations {
        let text = mutant(&base, &abs, &mut rng, corpus);
        let (mut problem, runnable) = judge(&project, &text, done % 10 == 0, &mut tally);
        if problem.is_none() && runnable && done % 50 == 0 {
            tally.commands += 1;
            std::fs::write(&file, &text).unwrap();
            problem = judge_command(&p, &file);
        }
        if let Some(problem) = problem {
            let dir = super::common::root().join("target/fuzz-crashers");
            std::fs::create_dir_all(&dir).unwrap();
            let crasher = dir.join(format!("reads-seed{seed}-{done}.toml"));
            let note = format!("# {}\n# project: {abs}\n", raw_free(&problem));
            std::fs::write(&crasher, format!("{note}{text}")).unwrap();
            crashers.push(crasher);
        }
    }
    std::panic::set_hook(hook);
    eprintln!(
        "fuzz reads: seed {seed}: {iterations} inputs: {} refused, {} verified, {} loaded only \
         (costly solvers), {} also run by the command line; {} crashers",
        tally.refused,
        tally.verified,
        tally.loaded_only,
        tally.commands,
        crashers.len()
    );
    assert!(crashers.is_empty(), "crashers written: {crashers:?}");
}

/// `text` on one line, for a comment.
fn raw_free(text: &str) -> String {
    text.chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect()
}
