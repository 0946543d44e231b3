//! What a case file may read and show (issue 27, the reads and text): one test per finding, each
//! failing before its fix. The hostile cases are in `tests/hostile/reads/`; most are copied into a
//! project folder of the test's own (`cases/`, `reference/`, and secrets beside the project) so
//! that relative names, links, FIFOs and sparse files mean what they say. The rules:
//! docs/security.md.
//!
//! Run: `cargo test --test suite hostile_reads::`.

use crate::common;

use std::path::Path;
use std::process::{Command, Output};

use common::reads::{
    hostile, raw_controls, spherecontact_guarded as spherecontact, symlink, text, Project, SECRET,
};
use spherecontact::case::Case;

/// A bad-input refusal: exit 2, `fragments` in the message, no secret, no raw control character.
fn assert_refused(output: &Output, fragments: &[&str]) {
    let all = text(output);
    assert_eq!(output.status.code(), Some(2), "{all}");
    for fragment in fragments {
        assert!(all.contains(fragment), "`{fragment}` not in: {all}");
    }
    assert!(!all.contains(SECRET), "a secret leaked: {all}");
    assert!(!all.contains("root:x:0"), "/etc/passwd leaked: {all}");
    assert!(raw_controls(&all).is_empty(), "raw control characters: {all:?}");
}

#[test]
fn the_base_case_reads_its_own_tree() {
    let p = Project::new();
    let case = p.case("ok.toml", "data/good.csv", "../reference/values.toml", |t| t);
    let output = p.verify(&case, &[]);
    assert!(output.status.success(), "{}", text(&output));
}

#[test]
fn every_shipped_case_reads_only_its_tree_and_still_loads() {
    // The shipped cases name ../reference/ and ../../reference/: the nearest reference/ folder.
    for file in common::all_case_files() {
        Case::load(&file).unwrap_or_else(|e| panic!("{e}"));
    }
}

#[cfg(unix)]
#[test]
fn stored_results_outside_the_tree_are_refused_without_echo() {
    let p = Project::new();
    symlink(&p.dir.path().join("secret.csv"), &p.cases().join("data/link.csv"));
    let absolute = p.dir.path().join("secret.csv");
    for (i, name) in [
        absolute.to_str().unwrap(),
        "../../secret.csv",
        "data/link.csv",
        "data/../../../secret.csv",
    ]
    .into_iter()
    .enumerate()
    {
        let case = p.case(&format!("out{i}.toml"), name, "../reference/values.toml", |t| t);
        assert_refused(
            &p.verify(&case, &[]),
            &[
                case.to_str().unwrap(),
                "stored_results[0].file",
                name,
                "outside the folders",
                "--allow-read",
            ],
        );
        // `list` loads every case under cases/: it shows the refusal, never the file.
        let listed = spherecontact(&["list"], &p.project());
        let all = text(&listed);
        assert!(
            all.contains("outside the folders") && !all.contains(SECRET),
            "{all}"
        );
        std::fs::remove_file(case).unwrap();
    }
}

#[test]
fn proc_self_environ_is_refused_without_echo() {
    let case = hostile("stored-proc-environ.toml");
    assert_refused(
        &spherecontact(&["verify", case.to_str().unwrap()], &common::root()),
        &[
            "stored-proc-environ.toml",
            "/proc/self/environ",
            "outside the folders",
        ],
    );
    let case = hostile("stored-climbs-out.toml");
    assert_refused(
        &spherecontact(&["verify", case.to_str().unwrap()], &common::root()),
        &["stored-climbs-out.toml", "outside the folders"],
    );
}

#[cfg(unix)]
#[test]
fn reference_files_outside_the_tree_are_refused() {
    let p = Project::new();
    symlink(
        &p.dir.path().join("secret.toml"),
        &p.project().join("reference/link.toml"),
    );
    let absolute = p.dir.path().join("secret.toml");
    for (i, name) in [
        absolute.to_str().unwrap(),
        "../../secret.toml",
        "../reference/link.toml",
    ]
    .into_iter()
    .enumerate()
    {
        let case = p.case(&format!("ref{i}.toml"), "data/good.csv", name, |t| t);
        assert_refused(
            &p.verify(&case, &[]),
            &["checks[1].reference.file", name, "outside the folders"],
        );
    }
    let case = hostile("reference-absolute.toml");
    assert_refused(
        &spherecontact(&["verify", case.to_str().unwrap()], &common::root()),
        &["/etc/passwd", "outside the folders"],
    );
}

#[test]
fn a_reference_folder_reached_through_a_link_is_no_root() {
    let p = Project::new();
    let dir = p.dir.path().join("download");
    std::fs::create_dir_all(&dir).unwrap();
    #[cfg(unix)]
    symlink(p.dir.path(), &dir.join("reference"));
    let case = p.case(
        "linked.toml",
        "reference/secret.csv",
        "reference/secret.toml",
        |t| t,
    );
    let moved = dir.join("linked.toml");
    std::fs::rename(&case, &moved).unwrap();
    assert_refused(&p.verify(&moved, &[]), &["outside the folders"]);
}

#[test]
fn allow_read_admits_a_named_folder_and_only_an_existing_one() {
    let p = Project::new();
    let case = p.case(
        "allowed.toml",
        "../../outside.csv",
        "../reference/values.toml",
        |t| t,
    );
    assert_refused(&p.verify(&case, &[]), &["outside the folders"]);
    let outside = p.dir.path().to_str().unwrap().to_owned();
    let output = p.verify(&case, &["--allow-read", &outside]);
    assert!(output.status.success(), "{}", text(&output));
    // The option is global: before the command too.
    let output = spherecontact(
        &["--allow-read", &outside, "verify", case.to_str().unwrap()],
        &p.project(),
    );
    assert!(output.status.success(), "{}", text(&output));
    let missing = p.dir.path().join("nowhere");
    assert_refused(
        &p.verify(&case, &["--allow-read", missing.to_str().unwrap()]),
        &["--allow-read", "nowhere", "allowed: an existing folder"],
    );
}

#[cfg(unix)]
#[test]
fn stored_results_must_be_regular_files_of_bounded_size() {
    let p = Project::new();
    let data = p.cases().join("data");
    let fifo = data.join("fifo.csv");
    let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success());
    // A sparse file far past the limit: refused by its size, never read.
    let sparse = std::fs::File::create(data.join("sparse.csv")).unwrap();
    sparse.set_len(5 << 30).unwrap();
    std::fs::create_dir(data.join("folder.csv")).unwrap();
    symlink(Path::new("/dev/zero"), &data.join("zero.csv"));
    for (name, says) in [
        ("data/fifo.csv", "not a regular file (a FIFO"),
        ("data/sparse.csv", "at most 256 MiB"),
        ("data/folder.csv", "not a regular file (a directory"),
        ("data/zero.csv", "outside the folders"),
    ] {
        let case = p.case("kind.toml", name, "../reference/values.toml", |t| t);
        assert_refused(&p.verify(&case, &[]), &["stored_results[0].file", says]);
    }
    // Allowed to read /dev, a device is still no file.
    let case = p.case("kind.toml", "data/zero.csv", "../reference/values.toml", |t| t);
    assert_refused(
        &p.verify(&case, &["--allow-read", "/dev"]),
        &["not a regular file (a device"],
    );
}

#[test]
fn a_bad_stored_file_is_located_without_repeating_its_text() {
    let p = Project::new();
    let good = std::fs::read_to_string(p.cases().join("data/good.csv")).unwrap();
    let (header, rows) = good.split_once('\n').unwrap();
    let bad_header = format!("{header},{SECRET}\n{rows}");
    std::fs::write(p.cases().join("data/header.csv"), bad_header).unwrap();
    let case = p.case(
        "header.toml",
        "data/header.csv",
        "../reference/values.toml",
        |t| t,
    );
    assert_refused(
        &p.verify(&case, &[]),
        &[
            "header.csv:1: header",
            "is not a known column",
            "allowed: step,position,delta_n,delta_t first",
        ],
    );
    let bad_cell = good.replacen("\n1,", &format!("\n{SECRET},"), 1);
    std::fs::write(p.cases().join("data/cell.csv"), bad_cell).unwrap();
    let case = p.case("cell.toml", "data/cell.csv", "../reference/values.toml", |t| t);
    assert_refused(
        &p.verify(&case, &[]),
        &["cell.csv:3: column `step`", "not the path's step 1"],
    );
}

#[test]
fn control_characters_never_reach_the_terminal_or_the_reports() {
    let dir = tempfile::tempdir().unwrap();
    let case = hostile("control-characters.toml");
    let junit = dir.path().join("junit.xml");
    let output = spherecontact(
        &[
            "verify",
            case.to_str().unwrap(),
            "--junit",
            junit.to_str().unwrap(),
        ],
        dir.path(),
    );
    let all = text(&output);
    assert_eq!(output.status.code(), Some(1), "{all}");
    assert!(raw_controls(&all).is_empty(), "raw control characters: {all:?}");
    let rows: Vec<&str> = all.lines().filter(|l| l.contains("mdr normal_force")).collect();
    assert_eq!(rows.len(), 1, "one row for the check: {all}");
    assert!(
        rows[0].starts_with("NOOK") && rows[0].contains("\\u{1b}[2K"),
        "{all}"
    );
    assert!(
        !all.lines().any(|l| l.starts_with("OK")),
        "a forged OK row: {all}"
    );
    let xml = std::fs::read_to_string(&junit).unwrap();
    assert!(raw_controls(&xml).is_empty(), "JUnit: {xml:?}");
    let out = dir.path().join("compare");
    let output = spherecontact(
        &["compare", case.to_str().unwrap(), "--out", out.to_str().unwrap()],
        dir.path(),
    );
    assert_eq!(output.status.code(), Some(1), "{}", text(&output));
    assert!(raw_controls(&text(&output)).is_empty(), "{}", text(&output));
    let mut files = vec![out.join("report.md"), out.join("report.html")];
    for folder in ["data", "figures"] {
        files.extend(
            std::fs::read_dir(out.join(folder))
                .unwrap()
                .map(|e| e.unwrap().path()),
        );
    }
    for file in files {
        let report = std::fs::read_to_string(&file).unwrap();
        assert!(
            raw_controls(&report).is_empty(),
            "{}: {:?}",
            file.display(),
            raw_controls(&report)
        );
    }
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(
        md.contains("escape \\\\u{1b}\\[31mred"),
        "the description is shown, escaped"
    );
}

/// Requirement: `merge` shows a run folder's name and the run file's fields (`shard`, a run's
/// `solver` in an error) with their control characters escaped (crates/system/src/text.rs), on one line: none
/// can redraw the terminal nor forge a line.
#[test]
fn merge_escapes_the_control_characters_of_folder_names_and_shard_fields() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("case.toml"), common::SMALL_CASE).unwrap();
    let folder = "run\u{1b}[2K\rOK";
    let output = spherecontact(&["verify", "case.toml", "--out", folder], dir.path());
    assert!(output.status.success(), "{}", text(&output));
    let run_file = dir.path().join(folder).join("run.json");
    let mut run: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&run_file).unwrap()).unwrap();
    run["shard"] = "1/1\u{1b}[1A\nOK forged".into();
    std::fs::write(&run_file, run.to_string()).unwrap();
    let output = spherecontact(&["merge", folder], dir.path());
    let all = text(&output);
    assert!(output.status.success(), "{all}");
    assert!(raw_controls(&all).is_empty(), "raw control characters: {all:?}");
    assert!(
        all.contains("merge: run\\u{1b}[2K\\u{d}OK (shard 1/1\\u{1b}[1A\\nOK forged): runs"),
        "{all}"
    );
    assert!(!all.lines().any(|l| l.starts_with("OK")), "a forged line: {all}");
    run["runs"][0]["solver"] = "mdr\u{1b}[2K\nOK forged".into();
    std::fs::write(&run_file, run.to_string()).unwrap();
    let output = spherecontact(&["merge", folder], dir.path());
    let all = text(&output);
    assert_eq!(output.status.code(), Some(2), "{all}");
    assert!(raw_controls(&all).is_empty(), "raw control characters: {all:?}");
    assert!(
        all.contains(
            "run of solver `mdr\\u{1b}[2K\\nOK forged` for case case.toml is not a run of the cases"
        ),
        "{all}"
    );
    assert!(!all.lines().any(|l| l.starts_with("OK")), "a forged line: {all}");
}

/// HTML and Markdown that a case's strings and a run file's metadata carry into the reports.
const MARKUP: &str = "<script>alert(10)</script> | [v](javascript:alert(11)) <IMG SRC=x onerror=alert(12)>";

/// How often `pattern` starts at a character of `text` that no backslash escapes (Markdown reads
/// those: a `|` that breaks a cell, a `](` that opens a link's address).
fn unescaped(text: &str, pattern: &str) -> usize {
    let (mut found, mut escaped) = (0, false);
    for (at, c) in text.char_indices() {
        if escaped {
            escaped = false;
        } else if c == '\\' {
            escaped = true;
        } else if text[at..].starts_with(pattern) {
            found += 1;
        }
    }
    found
}

/// Requirement: report.md shows a case's strings (description, a check's reason, a solver's
/// description) and a run file's metadata (version, model) as text, as report.html does: no
/// raw HTML tag, no link, no `javascript:`, and no `|` that adds a table cell.
#[test]
fn markup_in_case_strings_and_run_files_is_text_in_the_markdown_report() {
    let p = Project::new();
    let case = p.cases().join("markup.toml");
    std::fs::copy(hostile("markup.toml"), &case).unwrap();
    let verified = p.project().join("verified");
    let output = spherecontact(
        &[
            "verify",
            case.to_str().unwrap(),
            "--out",
            verified.to_str().unwrap(),
        ],
        &p.project(),
    );
    assert!(output.status.success(), "{}", text(&output));
    // The run file's hertz history says what a forged or foreign run file may say about its
    // solver (lab-rig's model is the stored results' description).
    let run_file = verified.join("run.json");
    let mut run: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&run_file).unwrap()).unwrap();
    for record in run["runs"].as_array_mut().unwrap() {
        if record["solver"] == "hertz" {
            let metadata = &mut record["result"]["history"]["metadata"];
            metadata["version"] = MARKUP.into();
            metadata["model"] = MARKUP.into();
        }
    }
    std::fs::write(&run_file, run.to_string()).unwrap();
    let out = p.project().join("out");
    let output = spherecontact(
        &[
            "compare",
            case.to_str().unwrap(),
            "--from",
            verified.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        &p.project(),
    );
    assert!(output.status.success(), "{}", text(&output));
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    let lower = md.to_lowercase();
    for raw in ["<script", "<img", "javascript:"] {
        assert!(!lower.contains(raw), "raw `{raw}` in report.md:\n{md}");
    }
    // The only links are the harness's own: `![caption](figures/…)`, `[data/…](data/…)`.
    let own = md.matches("](figures/").count() + md.matches("](data/").count();
    assert_eq!(
        unescaped(&md, "]("),
        own,
        "a link of the case's in report.md:\n{md}"
    );
    for shown in ["alert(1)", "alert(4)", "alert(7)", "alert(10)", "&lt;script&gt;"] {
        assert!(md.contains(shown), "`{shown}` is shown: {md}");
    }
    let mut header_cells = None;
    for line in md.lines() {
        match line.starts_with('|') {
            true => {
                let cells = *header_cells.get_or_insert(unescaped(line, "|"));
                assert_eq!(
                    unescaped(line, "|"),
                    cells,
                    "a row with other cells than its header: {line}"
                );
            }
            false => header_cells = None,
        }
    }
}

#[test]
fn reproduce_paper_without_its_reference_fails_before_any_solver() {
    let dir = tempfile::tempdir().unwrap();
    let cases = dir.path().join("cases");
    std::fs::create_dir(&cases).unwrap();
    let marker = dir.path().join("a-solver-ran");
    let case = cases.join("paper.toml");
    let template = std::fs::read_to_string(hostile("paper-reference-missing.toml")).unwrap();
    std::fs::write(&case, template.replace("@MARKER@", marker.to_str().unwrap())).unwrap();
    let out = dir.path().join("out");
    let output = spherecontact(
        &[
            "reproduce-paper",
            "--case",
            case.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        dir.path(),
    );
    assert_refused(
        &output,
        &[
            case.to_str().unwrap(),
            "paper's reference file",
            "../reference/paper.toml",
            "cannot read it",
        ],
    );
    let all = text(&output);
    assert!(
        !all.contains("Unreadable(") && !all.contains("Os {"),
        "a debug dump: {all}"
    );
    assert!(!marker.exists(), "a solver ran before the reference was read");
    assert!(!out.exists(), "something was written");
}

#[test]
fn bench_refuses_a_solver_that_the_case_defines() {
    let p = Project::new();
    let case = p.case("bench.toml", "data/good.csv", "../reference/values.toml", |t| t);
    let out = p.dir.path().join("bench");
    let bench = |extra: &[&str], case: &Path| {
        let mut args = vec![
            "bench",
            case.to_str().unwrap(),
            "--repeat",
            "1",
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend(extra);
        spherecontact(&args, &p.project())
    };
    assert_refused(
        &bench(&["--solver", "lab-rig"], &case),
        &[
            "--solver `lab-rig`",
            "stored results defined by the case",
            "no resolutions to sweep",
        ],
    );
    let only = p.case("only.toml", "data/good.csv", "../reference/values.toml", |t| {
        t.replace("solvers = [\"hertz\", \"lab-rig\"]", "solvers = [\"lab-rig\"]")
    });
    assert_refused(
        &bench(&[], &only),
        &["every solver of the case is defined by the case (lab-rig)"],
    );
    assert!(!out.exists(), "nothing written");
    // From the case's own list, it is left out with a note and the rest is swept.
    let output = bench(&[], &case);
    let all = text(&output);
    assert!(output.status.success(), "{all}");
    assert!(
        all.contains("note: lab-rig is defined by the case") && all.contains("hertz"),
        "{all}"
    );
}
