//! Malformed case files (`tests/hostile/malformed/*.toml`): each breaks one rule of the valid
//! `tests/hostile/valid/base.toml` and says so in its header,
//!
//! ```text
//! # rule: what is broken
//! # field: the field the message must name          (where the rule has one)
//! # at: LINE:COLUMN the message must point at        (where the parser knows it)
//! # says: a fragment of the message, with the allowed range where there is one
//! ```
//!
//! Each is run through the command line: exit code 2, the message names the file, the field and
//! the location and says what is allowed, no panic, nothing written. Inputs that are not case
//! files at all (a folder, a device, binary bytes, an empty file) are made here.
//!
//! Run: `cargo test --test suite hostile_cases::`.

use crate::common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use spherecontact::case::Case;

/// What a malformed file's header says its message must hold.
#[derive(Debug, Default)]
struct Expectation {
    rule: String,
    field: Option<String>,
    at: Option<String>,
    says: String,
}

fn expectation(file: &Path) -> Expectation {
    let text = std::fs::read_to_string(file).unwrap();
    let mut e = Expectation::default();
    for line in text.lines().take_while(|l| l.starts_with('#')) {
        let value = |key: &str| line.strip_prefix(key).map(str::to_owned);
        if let Some(v) = value("# rule: ") {
            e.rule = v;
        } else if let Some(v) = value("# field: ") {
            e.field = Some(v);
        } else if let Some(v) = value("# at: ") {
            e.at = Some(v);
        } else if let Some(v) = value("# says: ") {
            e.says = v;
        }
    }
    assert!(
        !e.rule.is_empty() && !e.says.is_empty(),
        "{}: header lacks rule or says",
        file.display()
    );
    e
}

fn hostile(relative: &str) -> PathBuf {
    common::root().join("tests/hostile").join(relative)
}

fn malformed_files() -> Vec<PathBuf> {
    let mut files: Vec<_> = std::fs::read_dir(hostile("malformed"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    files
}

/// `spherecontact run FILE --out out` in a fresh folder: its output, and whether out/ exists.
fn run_in_fresh_folder(file: &Path) -> (Output, bool) {
    let dir = tempfile::tempdir().unwrap();
    let output = Command::new(env!("CARGO_BIN_EXE_spherecontact"))
        .args(["run", file.to_str().unwrap(), "--out", "out"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    (output, dir.path().join("out").exists())
}

/// Judges a rejection as bad input: exit 2, message holding every `fragment`, no panic, nothing
/// written. Returns the message, or what is wrong.
fn judge_bad_input(file: &Path, fragments: &[&str]) -> Result<String, String> {
    let (output, wrote) = run_in_fresh_folder(file);
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    let name = file.display();
    let fail = |what: String| Err(format!("{name}: {what}\n    {stderr}"));
    if output.status.code() != Some(2) {
        return fail(format!("exit code {:?}", output.status.code()));
    }
    if stderr.contains("panicked") || wrote || !output.stdout.is_empty() {
        return fail("panicked, wrote or printed results".into());
    }
    match fragments.iter().find(|f| !stderr.contains(*f)) {
        Some(missing) => fail(format!("no `{missing}`")),
        None => Ok(stderr),
    }
}

/// Asserts that every judgement passed, listing those that did not.
fn assert_all(judgements: Vec<Result<String, String>>) {
    let failures: Vec<_> = judgements.into_iter().filter_map(Result::err).collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn the_base_of_the_malformed_files_is_valid() {
    Case::load(&hostile("valid/base.toml")).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn every_malformed_case_is_bad_input_with_a_located_message() {
    let files = malformed_files();
    assert!(
        files.len() >= 40,
        "the issue asks for at least 40 malformed cases"
    );
    let judgements = files.iter().map(|file| {
        let e = expectation(file);
        let shown = file.display().to_string();
        // With a location the file is followed by it; without, by the field or the text.
        let named = match &e.at {
            Some(at) => format!("{shown}:{at}: "),
            None => format!("{shown}: "),
        };
        let field = e.field.as_ref().map(|f| format!("field `{f}`"));
        let mut fragments = vec![e.says.as_str(), named.as_str()];
        fragments.extend(field.as_deref());
        judge_bad_input(file, &fragments)
    });
    assert_all(judgements.collect());
}

#[test]
fn files_that_are_not_case_files_are_bad_input() {
    let dir = tempfile::tempdir().unwrap();
    let path = |name: &str| dir.path().join(name);
    std::fs::create_dir(path("folder.toml")).unwrap();
    std::fs::write(path("empty.toml"), "").unwrap();
    std::fs::write(path("binary.toml"), [0x00, 0xff, 0xfe, 0x13, 0x37, 0x80]).unwrap();
    std::fs::write(path("latin1.toml"), b"name = \"caf\xe9\"\n").unwrap();
    std::fs::write(path("nul.toml"), "name = \"a\0b\"\n").unwrap();
    let cases: [(PathBuf, &[&str]); 7] = [
        (
            path("folder.toml"),
            &["folder.toml", "not a regular file (a directory"],
        ),
        (path("empty.toml"), &["empty.toml", "missing field"]),
        (path("binary.toml"), &["binary.toml", "not UTF-8"]),
        (
            path("latin1.toml"),
            &["latin1.toml", "not UTF-8 text: invalid byte at offset 11"],
        ),
        (path("nul.toml"), &["nul.toml"]),
        (path("missing.toml"), &["missing.toml", "No such file"]),
        (
            PathBuf::from("/dev/zero"),
            &["/dev/zero", "not a regular file (a device"],
        ),
    ];
    assert_all(
        cases
            .iter()
            .map(|(file, fragments)| judge_bad_input(file, fragments))
            .collect(),
    );
}

#[test]
fn deeply_nested_toml_is_bad_input_with_a_short_message() {
    let dir = tempfile::tempdir().unwrap();
    let n = 1_000_000;
    let inputs = [
        ("arrays.toml", format!("a = {}{}\n", "[".repeat(n), "]".repeat(n))),
        (
            "tables.toml",
            format!("a = {}1{}\n", "{b=".repeat(100_000), "}".repeat(100_000)),
        ),
        ("keys.toml", format!("[{}]\n", vec!["a"; 200_000].join("."))),
    ];
    let judgements = inputs.iter().map(|(name, text)| {
        let file = dir.path().join(name);
        std::fs::write(&file, text).unwrap();
        let message = judge_bad_input(&file, &[name, "recursion limit exceeded"])?;
        match message.len() {
            0..=2_000 => Ok(message),
            n => Err(format!("{name}: a message of {n} bytes")),
        }
    });
    assert_all(judgements.collect());
}
