//! The house stays clean: no import cycle between the crate's top-level modules (a low-level
//! module never reaches up into one that uses it), no source file over 600 lines, and every test
//! said to be run by CI as heavy is in the heavy list of `.ci/run`.
//!
//! The module graph is read from the sources: an edge A → B for every `crate::B` path (in a
//! `use` or in code) in the files of module A, and for `super::B` where `super` is the crate
//! root. Comments and test-only code (`#[cfg(test)] mod …`) are left out: a test may build a
//! case to exercise a solver.
//!
//! Run: `cargo test --test suite house::`.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The longest source file allowed [lines].
const MAX_LINES: usize = 600;

/// Every `.rs` file under `dir`, recursively.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            files.extend(rust_files(&path));
        } else if path.extension().is_some_and(|e| e == "rs") {
            files.push(path);
        }
    }
    files.sort();
    files
}

/// The source root.
fn src() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// The files declared test-only (`#[cfg(test)]` on the line before `mod name;`), and their
/// folders' files.
fn test_only(files: &[PathBuf]) -> BTreeSet<PathBuf> {
    let mut only = BTreeSet::new();
    for file in files {
        let text = std::fs::read_to_string(file).unwrap();
        let lines: Vec<&str> = text.lines().map(str::trim).collect();
        for pair in lines.windows(2) {
            let Some(name) = pair[1]
                .strip_prefix("mod ")
                .or_else(|| pair[1].strip_prefix("pub mod "))
                .and_then(|rest| rest.strip_suffix(';'))
            else {
                continue;
            };
            if pair[0] == "#[cfg(test)]" {
                let dir = if file.file_name().is_some_and(|f| f == "mod.rs" || f == "lib.rs") {
                    file.parent().unwrap().to_path_buf()
                } else {
                    file.with_extension("")
                };
                only.insert(dir.join(format!("{name}.rs")));
                only.insert(dir.join(name));
            }
        }
    }
    only
}

/// The top-level module a file belongs to (`bem` for src/bem/state.rs, `scene` for
/// src/scene.rs), `None` for lib.rs and main.rs.
fn module_of(file: &Path) -> Option<String> {
    let relative = file.strip_prefix(src()).unwrap();
    let first = relative.components().next()?.as_os_str().to_str()?.to_owned();
    let name = first.strip_suffix(".rs").unwrap_or(&first).to_owned();
    (name != "lib" && name != "main").then_some(name)
}

/// The code of `text` without comments and without its `#[cfg(test)]` tail module.
fn code_of(text: &str) -> String {
    let mut code = String::new();
    let mut lines = text.lines().peekable();
    while let Some(line) = lines.next() {
        let trimmed = line.trim();
        if trimmed == "#[cfg(test)]" && lines.peek().is_some_and(|l| l.trim().starts_with("mod tests")) {
            break;
        }
        if trimmed.starts_with("//") {
            continue;
        }
        code.push_str(line.split(" //").next().unwrap_or(""));
        code.push('\n');
    }
    code
}

/// The top-level modules `code` of a file in module `own` refers to.
fn references(code: &str, at_root: bool, modules: &BTreeSet<String>) -> BTreeSet<String> {
    let mut found = BTreeSet::new();
    let prefixes: &[&str] = if at_root {
        &["crate::", "super::"]
    } else {
        &["crate::"]
    };
    for prefix in prefixes {
        for (at, _) in code.match_indices(prefix) {
            let before = code[..at].chars().next_back();
            if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
                continue;
            }
            let rest = &code[at + prefix.len()..];
            // `use crate::{a, b::c}` names several modules.
            let names: Vec<&str> = match rest.strip_prefix('{') {
                Some(group) => group[..group.find('}').unwrap_or(group.len())]
                    .split(',')
                    .map(|s| s.trim().split("::").next().unwrap_or("").trim())
                    .collect(),
                None => vec![rest
                    .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                    .next()
                    .unwrap_or("")],
            };
            found.extend(
                names
                    .into_iter()
                    .filter(|n| modules.contains(*n))
                    .map(str::to_owned),
            );
        }
    }
    found
}

/// The graph of top-level modules: module → the modules it refers to, with one file of each
/// edge for the message.
fn module_graph() -> BTreeMap<String, BTreeMap<String, PathBuf>> {
    let files = rust_files(&src());
    let only = test_only(&files);
    let modules: BTreeSet<String> = files.iter().filter_map(|f| module_of(f)).collect();
    let mut graph: BTreeMap<String, BTreeMap<String, PathBuf>> = BTreeMap::new();
    for file in &files {
        if only.iter().any(|t| file.starts_with(t)) {
            continue;
        }
        let Some(own) = module_of(file) else { continue };
        let depth = file.strip_prefix(src()).unwrap().components().count();
        let at_root = depth == 1 || (depth == 2 && file.file_name().is_some_and(|f| f == "mod.rs"));
        let code = code_of(&std::fs::read_to_string(file).unwrap());
        let edges = graph.entry(own.clone()).or_default();
        for target in references(&code, at_root, &modules) {
            if target != own {
                edges.entry(target).or_insert_with(|| file.clone());
            }
        }
    }
    graph
}

/// Every module reachable from `start`.
fn reachable(graph: &BTreeMap<String, BTreeMap<String, PathBuf>>, start: &str) -> BTreeSet<String> {
    let mut seen = BTreeSet::new();
    let mut stack = vec![start.to_owned()];
    while let Some(module) = stack.pop() {
        for next in graph.get(&module).into_iter().flat_map(|e| e.keys()) {
            if seen.insert(next.clone()) {
                stack.push(next.clone());
            }
        }
    }
    seen
}

#[test]
fn no_cycle_between_top_level_modules() {
    let graph = module_graph();
    let mut cycles = Vec::new();
    for (module, edges) in &graph {
        for (target, file) in edges {
            if reachable(&graph, target).contains(module) {
                cycles.push(format!(
                    "{module} → {target} ({}) and {target} reaches back to {module}",
                    file.strip_prefix(src()).unwrap().display()
                ));
            }
        }
    }
    assert!(cycles.is_empty(), "import cycles:\n{}", cycles.join("\n"));
}

#[test]
fn the_graph_reader_sees_edges_and_cycles() {
    // The reader must see what it judges, or the test above could never fail.
    let modules: BTreeSet<String> = ["bem", "case", "scene"].map(String::from).into();
    let code = code_of("use crate::{bem::Bem, scene};\n// use crate::case;\nfn f() { crate::case::x(); }\n#[cfg(test)]\nmod tests { use crate::scene; }\n");
    assert_eq!(references(&code, false, &modules), modules);
    let code = code_of("use super::case::Case;\n");
    assert!(references(&code, false, &modules).is_empty());
    assert_eq!(references(&code, true, &modules), ["case".to_owned()].into());
    let graph = module_graph();
    assert!(
        graph["bem"].contains_key("contact"),
        "bem uses the contact engine"
    );
    assert!(graph.len() > 20, "{} modules", graph.len());
}

#[test]
fn no_source_file_over_600_lines() {
    let long: Vec<String> = rust_files(&src())
        .into_iter()
        .chain(rust_files(
            &PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests"),
        ))
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
