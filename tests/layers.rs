//! The layering `src/lib.rs` promises: each top-level module uses only the modules declared
//! before it there. A `crate::` path in a file of one module that names a later module
//! fails the test, with the file, the line and the path.

use std::path::{Path, PathBuf};

/// The top-level modules in the order `src/lib.rs` declares them.
fn declared_order(source: &Path) -> Vec<String> {
    let lib = std::fs::read_to_string(source.join("lib.rs")).expect("src/lib.rs");
    lib.lines().filter_map(|line| line.trim().strip_prefix("pub mod ")).map(|rest| rest.trim_end_matches(';').trim().to_string()).collect()
}

fn rust_files(directory: &Path, found: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(directory).expect("readable source directory") {
        let path = entry.expect("directory entry").path();
        if path.is_dir() {
            rust_files(&path, found);
        } else if path.extension().is_some_and(|e| e == "rs") {
            found.push(path);
        }
    }
}

/// The names `crate::NAME` in `text`, with their line numbers.
fn crate_paths(text: &str) -> Vec<(usize, String)> {
    let mut paths = Vec::new();
    for (number, line) in text.lines().enumerate() {
        let code = line.split("//").next().unwrap_or("");
        let mut rest = code;
        while let Some(at) = rest.find("crate::") {
            let after = &rest[at + "crate::".len()..];
            let name: String = after.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
            let preceded_by_word = rest[..at].chars().last().is_some_and(|c| c.is_alphanumeric() || c == '_');
            if !preceded_by_word && !name.is_empty() {
                paths.push((number + 1, name));
            }
            rest = after;
        }
    }
    paths
}

/// A `use crate::{a, b::c}` group names several modules at once, over one line or several.
fn grouped_paths(text: &str) -> Vec<(usize, String)> {
    let mut paths = Vec::new();
    let mut search_from = 0;
    while let Some(found) = text[search_from..].find("crate::{") {
        let start = search_from + found + "crate::{".len();
        let (mut depth, mut item_start) = (1usize, start);
        for (offset, c) in text[start..].char_indices() {
            let at = start + offset;
            let item_ends = match c {
                '{' => {
                    depth += 1;
                    false
                }
                '}' => {
                    depth -= 1;
                    depth == 0
                }
                ',' => depth == 1,
                _ => false,
            };
            if item_ends {
                let item = text[item_start..at].trim_start();
                let name: String = item.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
                if !name.is_empty() {
                    let leading = text[item_start..at].len() - item.len();
                    let line = text[..item_start + leading].matches('\n').count() + 1;
                    paths.push((line, name));
                }
                item_start = at + 1;
            }
            if depth == 0 {
                search_from = at;
                break;
            }
        }
        if depth != 0 {
            break;
        }
    }
    paths
}

#[test]
fn each_module_uses_only_the_modules_declared_before_it() {
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let order = declared_order(&source);
    assert!(order.len() >= 8, "src/lib.rs declares too few modules to check: {order:?}");
    let rank = |name: &str| order.iter().position(|m| m == name);
    let mut files = Vec::new();
    rust_files(&source, &mut files);
    let mut breaches = Vec::new();
    for file in &files {
        let relative = file.strip_prefix(&source).expect("under src");
        let top = relative.components().next().expect("a component").as_os_str().to_string_lossy().trim_end_matches(".rs").to_string();
        // The crate root declares the order; the binaries sit above every layer.
        let Some(own_rank) = rank(&top) else { continue };
        let text = std::fs::read_to_string(file).expect("readable source file");
        for (line, name) in crate_paths(&text).into_iter().chain(grouped_paths(&text)) {
            // `crate::Error` and `crate::Result` are the error module's re-exports.
            let name = if name == "Error" || name == "Result" { "error".to_string() } else { name };
            if let Some(used_rank) = rank(&name) {
                if used_rank > own_rank {
                    breaches.push(format!("src/{}:{line}: `{top}` uses `crate::{name}`, declared after it", relative.display()));
                }
            }
        }
    }
    assert!(breaches.is_empty(), "imports against the layer order of src/lib.rs ({}):\n{}", order.join(" < "), breaches.join("\n"));
}

/// The module a source file defines, as its path below the crate (`["orient", "verdict"]`).
fn module_of(source: &Path, file: &Path) -> Vec<String> {
    let relative = file.strip_prefix(source).expect("under src").with_extension("");
    let mut path: Vec<String> = relative.components().map(|c| c.as_os_str().to_string_lossy().into_owned()).collect();
    if path.last().is_some_and(|last| last == "mod" || last == "lib") {
        path.pop();
    }
    path
}

/// The modules a file's code (comments aside) names through `crate::` or `super::` paths,
/// each resolved to the longest module of `modules` it starts with.
fn modules_named(text: &str, own: &[String], modules: &std::collections::BTreeSet<Vec<String>>) -> Vec<Vec<String>> {
    let mut named = Vec::new();
    for line in text.lines() {
        let code = line.split("//").next().unwrap_or("");
        for (start, _) in code.match_indices("::") {
            let head_start = code[..start].rfind(|c: char| !(c.is_alphanumeric() || c == '_')).map_or(0, |at| at + 1);
            let head = &code[head_start..start];
            let base: Vec<String> = match head {
                "crate" => Vec::new(),
                "super" if own.is_empty() => continue,
                "super" => own[..own.len() - 1].to_vec(),
                _ => continue,
            };
            let rest: Vec<String> = code[start + 2..]
                .split("::")
                .map(|segment| segment.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect::<String>())
                .take_while(|segment| !segment.is_empty())
                .collect();
            let mut path = base;
            path.extend(rest);
            if let Some(found) = (1..=path.len()).rev().map(|k| path[..k].to_vec()).find(|prefix| modules.contains(prefix)) {
                named.push(found);
            }
        }
    }
    named
}

#[test]
fn no_two_modules_use_each_other() {
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&source, &mut files);
    files.retain(|file| !file.strip_prefix(&source).expect("under src").starts_with("bin"));
    let modules: std::collections::BTreeSet<Vec<String>> = files.iter().map(|file| module_of(&source, file)).collect();
    let mut uses: std::collections::BTreeMap<Vec<String>, std::collections::BTreeSet<Vec<String>>> = Default::default();
    for file in &files {
        let own = module_of(&source, file);
        let text = std::fs::read_to_string(file).expect("readable source file");
        for used in modules_named(&text, &own, &modules) {
            // A module and its parent name each other by nature (`mod` items, `super::`).
            let related = used.starts_with(&own) || own.starts_with(&used);
            if !related {
                uses.entry(own.clone()).or_default().insert(used);
            }
        }
    }
    let mut circles = Vec::new();
    for (module, used) in &uses {
        for other in used {
            if module < other && uses.get(other).is_some_and(|back| back.contains(module)) {
                circles.push(format!("{} <-> {}", module.join("::"), other.join("::")));
            }
        }
    }
    // Longer circles: a module reachable from itself through others.
    for start in uses.keys() {
        let mut stack: Vec<Vec<String>> = uses[start].iter().cloned().collect();
        let mut seen = std::collections::BTreeSet::new();
        while let Some(next) = stack.pop() {
            if &next == start {
                circles.push(format!("{} reaches itself", start.join("::")));
                break;
            }
            if seen.insert(next.clone()) {
                stack.extend(uses.get(&next).into_iter().flatten().cloned());
            }
        }
    }
    circles.sort();
    circles.dedup();
    assert!(circles.is_empty(), "modules that use each other, directly or through others:\n{}", circles.join("\n"));
}

#[test]
fn the_checker_sees_paths_in_code_and_in_groups() {
    let text = "use crate::mesh::Mesh;\nuse crate::{orient, refine::Criterion};\nlet x = crate::draw::f(); // crate::ffi in a comment\nsupercrate::x\nuse crate::{\n    profile::{a, b},\n    pipeline,\n};";
    let found: Vec<(usize, String)> = crate_paths(text).into_iter().chain(grouped_paths(text)).collect();
    let expected = [(1, "mesh"), (3, "draw"), (2, "orient"), (2, "refine"), (6, "profile"), (7, "pipeline")];
    assert_eq!(found, expected.map(|(line, name)| (line, name.to_string())));
}
