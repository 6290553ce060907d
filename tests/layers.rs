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

#[test]
fn the_checker_sees_paths_in_code_and_in_groups() {
    let text = "use crate::mesh::Mesh;\nuse crate::{orient, refine::Criterion};\nlet x = crate::draw::f(); // crate::ffi in a comment\nsupercrate::x\nuse crate::{\n    profile::{a, b},\n    pipeline,\n};";
    let found: Vec<(usize, String)> = crate_paths(text).into_iter().chain(grouped_paths(text)).collect();
    let expected = [(1, "mesh"), (3, "draw"), (2, "orient"), (2, "refine"), (6, "profile"), (7, "pipeline")];
    assert_eq!(found, expected.map(|(line, name)| (line, name.to_string())));
}
