//! The module graph of a crate, read from its sources: for every folder, an edge A → B between two
//! of its modules for every path (`crate::…`, `super::…`, `self::…`, in a `use` or in code, a
//! group `{a, b::c}` as several) that a file of A (or of a module below A) names into B (or
//! below). Comments and test-only code (the `#[cfg(test)] mod tests` tail of a file, and the
//! files a `#[cfg(test)] mod x;` declares) are left out: a test may build what it needs.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// A module's path from its crate's root: `["external", "process"]`; the root is `[]`.
pub type Module = Vec<String>;

/// Every `.rs` file under `dir`, recursively, sorted.
pub fn rust_files(dir: &Path) -> Vec<PathBuf> {
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

/// The module of `file` under the crate's source folder `src` (`lib.rs`, `main.rs` and `mod.rs`
/// are their folder's module).
fn module_of(src: &Path, file: &Path) -> Module {
    let relative = file.strip_prefix(src).unwrap().with_extension("");
    let mut parts: Module = relative
        .iter()
        .map(|p| p.to_string_lossy().into_owned())
        .collect();
    if parts
        .last()
        .is_some_and(|l| l == "mod" || l == "lib" || l == "main")
    {
        parts.pop();
    }
    parts
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
                let named = file.file_name().and_then(|f| f.to_str());
                let dir = if matches!(named, Some("mod.rs" | "lib.rs" | "main.rs")) {
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

/// The code of `text` without comments and without its `#[cfg(test)]` tail module.
pub fn code_of(text: &str) -> String {
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

/// The paths `code` names relative to its file's module `own`: each as the absolute path of
/// names it leads to (modules, then perhaps an item).
pub fn references(code: &str, own: &[String]) -> Vec<Module> {
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    let mut found = Vec::new();
    let mut at = 0;
    while let Some(offset) = code[at..].find(|c: char| c == 'c' || c == 's') {
        let start = at + offset;
        at = start + 1;
        if code[..start]
            .chars()
            .next_back()
            .is_some_and(|c| ident(c) || c == ':' || c == '$')
        {
            continue;
        }
        let mut base: Option<Module> = None;
        let mut rest = &code[start..];
        for (head, up) in [("crate::", None), ("self::", Some(0)), ("super::", Some(1))] {
            if let Some(tail) = rest.strip_prefix(head) {
                base = Some(match up {
                    None => Vec::new(),
                    Some(n) => own[..own.len() - n.min(own.len())].to_vec(),
                });
                rest = tail;
                break;
            }
        }
        let Some(mut base) = base else { continue };
        while let Some(tail) = rest.strip_prefix("super::") {
            base.pop();
            rest = tail;
        }
        let group = rest
            .strip_prefix('{')
            .map(|g| &g[..g.find('}').unwrap_or(g.len())]);
        let items: Vec<&str> = match group {
            Some(group) => group.split(',').collect(),
            None => vec![rest],
        };
        for item in items {
            let path: Vec<String> = item
                .trim()
                .split("::")
                .map(|s| s.chars().take_while(|&c| ident(c)).collect::<String>())
                .take_while(|s| !s.is_empty())
                .collect();
            found.push([base.clone(), path].concat());
        }
    }
    found
}

/// A crate's sibling edges: folder → (module → (module it reaches → a file that does)).
pub type Edges = BTreeMap<Module, BTreeMap<String, BTreeMap<String, PathBuf>>>;

/// The sibling edges of the crate whose sources are under `src`.
pub fn edges(src: &Path) -> Edges {
    let files = rust_files(src);
    let only = test_only(&files);
    let modules: BTreeSet<Module> = files.iter().map(|f| module_of(src, f)).collect();
    let mut edges = Edges::new();
    for file in files.iter().filter(|f| !only.iter().any(|t| f.starts_with(t))) {
        let own = module_of(src, file);
        let code = code_of(&std::fs::read_to_string(file).unwrap());
        for target in references(&code, &own) {
            // The module named: the longest prefix of the path that is a module.
            let Some(len) = (1..=target.len()).rev().find(|&n| modules.contains(&target[..n])) else {
                continue;
            };
            let target = &target[..len];
            let shared = own.iter().zip(target).take_while(|(a, b)| a == b).count();
            if shared < own.len() && shared < target.len() {
                let (from, to) = (own[shared].clone(), target[shared].clone());
                let folder = edges.entry(own[..shared].to_vec()).or_default();
                folder
                    .entry(from)
                    .or_default()
                    .entry(to)
                    .or_insert_with(|| file.clone());
            }
        }
    }
    edges
}

/// Every circle among the siblings of a folder, in words: `folder: a → b (file) and b reaches
/// back to a`.
pub fn circles(edges: &Edges) -> Vec<String> {
    let mut found = Vec::new();
    for (folder, graph) in edges {
        let reach = |start: &str| {
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
        };
        for (module, targets) in graph {
            for (target, file) in targets {
                if reach(target).contains(module) {
                    let folder = if folder.is_empty() {
                        "(root)".into()
                    } else {
                        folder.join("::")
                    };
                    found.push(format!(
                        "{folder}: {module} → {target} ({}) and {target} reaches back to {module}",
                        file.display()
                    ));
                }
            }
        }
    }
    found
}
