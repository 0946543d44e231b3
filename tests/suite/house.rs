//! The house stays clean: no import circle in any folder of any crate of the workspace (the
//! modules of a folder read one way: none reaches, directly or through its siblings, back to one
//! that uses it; between crates cargo refuses a circle itself), no source file over 600 lines, and
//! every test said to be run by CI as heavy is in the heavy list of `.ci/run`.
//!
//! The module graphs are read from the sources ([`graph`]).
//!
//! Run: `cargo test --test suite house::`.

mod graph;

use std::path::PathBuf;

use graph::{circles, code_of, edges, references, rust_files};

/// The longest source file allowed [lines].
const MAX_LINES: usize = 600;

/// The workspace's folder.
fn workspace() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The source folder of every crate of the workspace: the root package's `src/` and each
/// `crates/*/src/`.
fn crate_sources() -> Vec<PathBuf> {
    let mut sources = vec![workspace().join("src")];
    let crates = std::fs::read_dir(workspace().join("crates")).unwrap();
    let mut members: Vec<PathBuf> = crates
        .map(|e| e.unwrap().path().join("src"))
        .filter(|p| p.is_dir())
        .collect();
    members.sort();
    sources.extend(members);
    sources
}

/// Requirement (issue 38): no import circle anywhere, in any folder of any crate.
#[test]
fn no_import_circle_in_any_folder_of_any_crate() {
    let found: Vec<String> = crate_sources()
        .iter()
        .flat_map(|src| circles(&edges(src)))
        .collect();
    assert!(found.is_empty(), "import circles:\n{}", found.join("\n"));
}

/// The reader must see what it judges, or the test above could never fail: a folder with a
/// circle, and the workspace's own edges.
#[test]
fn the_graph_reader_sees_edges_and_circles() {
    let own: Vec<String> = vec!["bem".into(), "solver".into()];
    let code = code_of("use crate::{bem::Bem, scene};\n// use crate::case;\nfn f() { super::grid::x(); }\n#[cfg(test)]\nmod tests { use crate::case; }\n");
    let found = references(&code, &own);
    let expected: Vec<Vec<String>> = [vec!["bem", "Bem"], vec!["scene"], vec!["bem", "grid", "x"]]
        .iter()
        .map(|p| p.iter().map(|s| s.to_string()).collect())
        .collect();
    assert_eq!(found, expected);
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, text: &str| {
        let file = dir.path().join(name);
        std::fs::create_dir_all(file.parent().unwrap()).unwrap();
        std::fs::write(file, text).unwrap();
    };
    write("lib.rs", "pub mod a;\npub mod b;\n");
    write("a/mod.rs", "pub mod x;\npub mod y;\nuse crate::b::B;\n");
    write("a/x.rs", "use super::y::Y;\n");
    write("a/y.rs", "pub struct Y;\nfn f() { crate::a::x::g(); }\n");
    write("b.rs", "pub struct B;\n");
    let found = circles(&edges(dir.path()));
    assert_eq!(found.len(), 2, "{found:?}");
    assert!(found[0].starts_with("a: x → y"), "{found:?}");
    let workspace_edges = edges(&workspace().join("crates/solvers/src"));
    assert!(
        workspace_edges[&Vec::new()]["bem"].contains_key("fit"),
        "bem uses the fits: {workspace_edges:?}"
    );
}

#[test]
fn no_source_file_over_600_lines() {
    let long: Vec<String> = crate_sources()
        .iter()
        .chain([&workspace().join("tests")])
        .flat_map(|dir| rust_files(dir))
        .filter_map(|f| {
            let lines = std::fs::read_to_string(&f).unwrap().lines().count();
            (lines > MAX_LINES).then(|| format!("{}: {lines} lines", f.display()))
        })
        .collect();
    assert!(long.is_empty(), "over {MAX_LINES} lines:\n{}", long.join("\n"));
}

/// The tests of `tests/suite/<module>.rs` marked `#[ignore = "heavy: …; .ci/run runs it …"]`, as
/// `module::name`.
fn heavy_tests_ci_runs() -> Vec<String> {
    let suite = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/suite");
    let mut tests = Vec::new();
    for file in rust_files(&suite) {
        let Some(module) = file.strip_prefix(&suite).ok().and_then(|f| f.to_str()) else {
            continue;
        };
        let module = module.trim_end_matches(".rs").replace('/', "::");
        let text = std::fs::read_to_string(&file).unwrap();
        let mut marked = false;
        for line in text.lines() {
            let line = line.trim();
            if line.starts_with("#[ignore = \"heavy:") && line.contains(".ci/run runs it") {
                marked = true;
            } else if let Some(rest) = line.strip_prefix("fn ").filter(|_| marked) {
                let name = rest.split('(').next().unwrap_or_default();
                tests.push(format!("{module}::{name}"));
                marked = false;
            } else if !line.starts_with("#[") && !line.starts_with("//") {
                marked = false;
            }
        }
    }
    tests
}

/// Requirement: a test that says CI runs it as heavy is in the `heavy=(…)` list of `.ci/run`,
/// by its module or its name (else neither the README's command nor CI would run it).
#[test]
fn every_heavy_test_said_to_run_in_ci_is_in_its_list() {
    let ci = std::fs::read_to_string(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(".ci/run")).unwrap();
    let listed = ci
        .split("heavy=(")
        .nth(1)
        .and_then(|rest| rest.split(')').next())
        .expect(".ci/run has a heavy=(…) list");
    let filters: Vec<&str> = listed.split_whitespace().collect();
    let tests = heavy_tests_ci_runs();
    assert!(tests.len() >= 10, "{tests:?}");
    let missing: Vec<&String> = tests
        .iter()
        .filter(|t| !filters.iter().any(|f| t.contains(f)))
        .collect();
    assert!(missing.is_empty(), "not in .ci/run's heavy list: {missing:?}");
}

/// Requirement (issue 38): no arrow back up. The workspace lists its layer crates in the order
/// data flows (the root `Cargo.toml`'s `members`); each crate may depend only on those before
/// it. Cargo refuses a circle between crates; this refuses an arrow up that makes none yet.
/// Reference: the order in the manifest. No tolerance: any dependency up is a failure.
#[test]
fn every_crate_depends_only_on_the_layers_before_it() {
    let root = std::fs::read_to_string(workspace().join("Cargo.toml")).unwrap();
    let members_line = root
        .lines()
        .find(|l| l.starts_with("members = ["))
        .expect("a members line");
    let order: Vec<&str> = members_line
        .split('"')
        .filter_map(|m| m.strip_prefix("crates/"))
        .collect();
    assert!(order.len() >= 10, "the layers: {order:?}");
    let mut upward = Vec::new();
    let mut seen = 0;
    for (i, name) in order.iter().enumerate() {
        let manifest =
            std::fs::read_to_string(workspace().join("crates").join(name).join("Cargo.toml")).unwrap();
        for line in manifest.lines() {
            let Some(dep) = line
                .split_once(" = { path = \"../")
                .map(|(_, rest)| rest.trim_end_matches("\" }"))
            else {
                continue;
            };
            seen += 1;
            match order.iter().position(|m| *m == dep) {
                Some(j) if j < i => {}
                _ => upward.push(format!("{name} -> {dep}")),
            }
        }
    }
    // The reader sees the manifests' path dependencies (the report layer alone names nine), so
    // a change of their form cannot make this test pass on nothing.
    assert!(seen >= order.len(), "path dependencies read: {seen}");
    assert!(upward.is_empty(), "dependencies up the layers: {upward:?}");
}
