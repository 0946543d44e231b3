//! The command fuzzer of `fuzz_case`: it mutates the `[[command_solvers]]` section of a case (the
//! solver's name, the program and its arguments with placeholders and shell syntax, the timeout,
//! the description) and whether a check or the solver list names it. Every program it writes
//! would create the file `ran` in the case's folder if it ran.
//!
//! Every input is loaded in the process (no panic) and, when it loads, verified as `verify` does
//! without the opt-in: the file `ran` must never appear, and the rows a user sees hold no raw
//! control character. One input in 40 also goes through the command line (`verify`, no opt-in):
//! exit code 0, 1 or 2 only, no `ran`, no raw control character. The opt-in itself is checked
//! once at the start (the same program with `--allow-commands` does create `ran`), so that a
//! fuzzer whose programs could never run cannot pass for one that proves they do not.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;

use super::common::reads::{raw_controls, spherecontact_guarded, text};
use super::common::SMALL_CASE;
use super::Rng;
use spherecontact::case::Case;
use spherecontact::external::permission::CommandPermission;
use spherecontact::verify;
use spherecontact::verify::table;

/// Names a hostile case gives its program.
const NAMES: &[&str] = &[
    "mine",
    "Mine!",
    "../up",
    "",
    "hertz",
    "a\u{1b}[2Jb",
    "x y",
    "mine\n",
];

/// Programs: `@RAN@` stands for the path of the file `ran`.
const PROGRAMS: &[&str] = &[
    "sh",
    "/bin/sh",
    "touch",
    "{case_dir}/run.sh",
    "./run.sh",
    "",
    "\u{0}sh",
];

/// Arguments, alone or in a row.
const ARGUMENTS: &[&str] = &[
    "-c",
    "touch @RAN@",
    "touch @RAN@; echo {scene}",
    "{case_dir}",
    "{scene}",
    "{history}",
    "$(touch @RAN@)",
    "`touch @RAN@`",
    "{case_dir};touch @RAN@",
    "{unknown}",
    "@RAN@",
    "\u{7}\u{1b}[1A",
];

/// Timeouts as written (a number, or anything else).
const TIMEOUTS: &[&str] = &["60", "0", "-1", "1e9", "1.5", "\"x\"", "31536000", "nan"];

/// The command section and the lines that name it, drawn from the lists above.
fn command_case(rng: &mut Rng, ran: &Path) -> String {
    // Half the draws keep each field valid, so that many inputs load and their programs would run.
    let half = |rng: &mut Rng, valid: &'static str, others: &[&'static str]| {
        if rng.below(2) == 0 {
            valid
        } else {
            *rng.pick(others)
        }
    };
    let name = toml_string(half(rng, "mine", NAMES));
    let mut command = vec![half(rng, "sh", PROGRAMS).to_string()];
    for _ in 0..rng.below(4) {
        command.push(rng.pick(ARGUMENTS).to_string());
    }
    let command: Vec<String> = command
        .iter()
        .map(|a| toml_string(&a.replace("@RAN@", &ran.display().to_string())))
        .collect();
    let solvers = if rng.below(2) == 0 {
        format!("solvers = [\"hertz\", {name}]")
    } else {
        "solvers = [\"hertz\", \"mdr\"]".to_owned()
    };
    let mut text = SMALL_CASE.replace("solvers = [\"hertz\", \"mdr\"]", &solvers);
    text.push_str(&format!(
        "\n[[command_solvers]]\nname = {name}\nkind = \"analytic\"\ncommand = [{}]\ntimeout = {}\ndescription = {}\n",
        command.join(", "),
        half(rng, "60", TIMEOUTS),
        toml_string(*rng.pick(NAMES))
    ));
    if rng.below(3) > 0 {
        text.push_str(&format!(
            "\n[[checks]]\nsolver = {name}\nquantity = \"normal_force\"\nat = \"every-step\"\n\
             reference = {{ solver = \"hertz\" }}\ntolerance = 1e-6\nreason = \"fuzz\"\n"
        ));
    }
    text
}

/// `text` as a TOML string (quoted, control characters escaped as TOML escapes them).
fn toml_string(text: &str) -> String {
    toml::Value::String(text.to_owned()).to_string()
}

/// The promises one input must keep; `Some(what broke)` otherwise. `loaded` counts the inputs
/// that loaded as cases (and were verified).
fn judge(input: &str, dir: &Path, ran: &Path, cli: bool, loaded_count: &mut u64) -> Option<String> {
    let file = dir.join("case.toml");
    std::fs::write(&file, input).unwrap();
    let loaded = catch_unwind(AssertUnwindSafe(|| Case::parse(&file, input)));
    let Ok(loaded) = loaded else {
        return Some("the parser panicked".into());
    };
    if let Ok(case) = loaded {
        *loaded_count += 1;
        let run = catch_unwind(AssertUnwindSafe(|| verify::run_case(case)));
        let Ok(run) = run else {
            return Some("verify panicked".into());
        };
        let rows = table::case_block(&run);
        if !raw_controls(&rows).is_empty() {
            return Some(format!("raw control characters in the rows: {rows:?}"));
        }
    }
    if ran.exists() {
        return Some("a program ran without the opt-in (in the process)".into());
    }
    if cli {
        let output = spherecontact_guarded(&["verify", "case.toml"], dir);
        let shown = text(&output);
        if !matches!(output.status.code(), Some(0..=2)) {
            return Some(format!("exit {:?}: {shown}", output.status.code()));
        }
        if ran.exists() {
            return Some("a program ran without the opt-in (verify)".into());
        }
        if !raw_controls(&shown).is_empty() {
            return Some(format!("raw control characters on the terminal: {shown:?}"));
        }
    }
    None
}

/// The opt-in runs the fuzzer's own kind of program: its `ran` check can fail.
fn the_opt_in_runs_such_a_program(dir: &Path, ran: &Path) {
    let program = format!("touch {}", ran.display());
    let case =
        format!(
        "{}\n[[command_solvers]]\nname = \"mine\"\nkind = \"analytic\"\ncommand = [\"sh\", \"-c\", {program:?}]\ntimeout = 60\n",
        SMALL_CASE.replace("solvers = [\"hertz\", \"mdr\"]", "solvers = [\"hertz\", \"mine\"]")
    );
    let file = dir.join("case.toml");
    std::fs::write(&file, &case).unwrap();
    let mut loaded = Case::parse(&file, &case).unwrap();
    loaded.permit_commands(&CommandPermission::allowed());
    let _ = verify::run_case(loaded);
    assert!(
        ran.exists(),
        "the allowed program did not run: the fuzzer could not see one run"
    );
    std::fs::remove_file(ran).unwrap();
}

/// Mutates the command sections of `iterations` inputs from `seed`; panics with the inputs that
/// broke a promise.
pub fn fuzz(seed: u64, iterations: u64) {
    let dir = tempfile::tempdir().unwrap();
    let ran = dir.path().join("ran");
    std::fs::write(
        dir.path().join("run.sh"),
        format!("#!/bin/sh\ntouch {}\n", ran.display()),
    )
    .unwrap();
    the_opt_in_runs_such_a_program(dir.path(), &ran);
    let mut rng = Rng(seed);
    let (mut broken, mut loaded) = (Vec::new(), 0);
    for i in 0..iterations {
        let input = command_case(&mut rng, &ran);
        if let Some(what) = judge(&input, dir.path(), &ran, i % 40 == 0, &mut loaded) {
            let _ = std::fs::remove_file(&ran);
            broken.push(format!("{what}\n--- input ---\n{input}"));
        }
    }
    println!(
        "fuzz_commands: {iterations} inputs, {loaded} loaded and verified, {} broke a promise",
        broken.len()
    );
    // A fuzzer whose inputs never load would verify nothing: a valid name, program and timeout
    // are each drawn half the time, so a share of the inputs are valid cases (127 of 400 with
    // the default seed).
    assert!(
        loaded * 10 >= iterations,
        "only {loaded} of {iterations} inputs loaded"
    );
    assert!(
        broken.is_empty(),
        "{} inputs broke a promise:\n{}",
        broken.len(),
        broken.join("\n\n")
    );
}
