//! The structure `src/lib.rs` promises, checked on the source as written:
//! - each top-level module uses only the modules declared before it there;
//! - no two modules of `src/` use each other, directly or through others (a module and its
//!   parent aside: they name each other by nature).
//!
//! Both checks read the same paths: every `crate::` and `super::` path of a file's code
//! (comments aside), `use` groups such as `crate::{a, b::{c, d}}` expanded.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// A module's path below the crate root, e.g. `["orient", "verdict"]`.
type ModulePath = Vec<String>;

/// The top-level modules in the order `src/lib.rs` declares them.
fn declared_order(source: &Path) -> Vec<String> {
    let lib = std::fs::read_to_string(source.join("lib.rs")).expect("src/lib.rs");
    lib.lines().filter_map(|line| line.trim().strip_prefix("pub mod ")).map(|rest| rest.trim_end_matches(';').trim().to_string()).collect()
}

/// The `.rs` files below `directory`.
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

/// The library's source files (the binaries sit above every layer and are left out), each
/// with the module it defines.
fn library_files(source: &Path) -> Vec<(PathBuf, ModulePath)> {
    let mut files = Vec::new();
    rust_files(source, &mut files);
    files.retain(|file| !file.strip_prefix(source).expect("under src").starts_with("bin"));
    files.sort();
    files
        .into_iter()
        .map(|file| {
            let relative = file.strip_prefix(source).expect("under src").with_extension("");
            let mut module: ModulePath = relative.components().map(|c| c.as_os_str().to_string_lossy().into_owned()).collect();
            if module.last().is_some_and(|last| last == "mod" || last == "lib") {
                module.pop();
            }
            (file, module)
        })
        .collect()
}

fn is_word(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// The paths that follow `crate::` or `super::` in `code` (comments already removed), with
/// their line numbers: `(line, head, segments)`, `head` being `crate` or `super` and a
/// group expanded into one path per item. `super::super::x` gives `super` and
/// `["super", "x"]`.
fn paths(code: &str) -> Vec<(usize, &'static str, Vec<String>)> {
    let mut heads: Vec<(usize, &'static str)> = Vec::new();
    for head in ["crate", "super"] {
        heads.extend(code.match_indices(&format!("{head}::")).map(|(at, _)| (at, head)));
    }
    heads.sort();
    let mut found = Vec::new();
    // The end of the last path read: a `super::` inside a group belongs to the group.
    let mut read_until = 0;
    for (at, head) in heads {
        if at < read_until || code[..at].chars().last().is_some_and(is_word) {
            continue; // inside a group, or `supercrate::`, `my_super::`
        }
        let line = code[..at].matches('\n').count() + 1;
        let start = at + head.len() + 2;
        let mut items = Vec::new();
        read_until = start + read_path(&code[start..], &[], &mut items);
        found.extend(items.into_iter().map(|segments| (line, head, segments)));
    }
    found
}

/// The length of the white space at the start of `text`.
fn leading_space(text: &str) -> usize {
    text.len() - text.trim_start().len()
}

/// Reads the path at the start of `text`: words joined by `::`, ending in a word or in a
/// `{...}` group of such paths. Appends each complete path, after `prefix`, to `out`, and
/// returns how many bytes it read.
fn read_path(text: &str, prefix: &[String], out: &mut Vec<Vec<String>>) -> usize {
    let mut path = prefix.to_vec();
    let mut at = 0;
    loop {
        at += leading_space(&text[at..]);
        if text[at..].starts_with('{') {
            at += 1;
            loop {
                at += read_path(&text[at..], &path, out);
                at += leading_space(&text[at..]);
                // `a as b`: the alias names nothing.
                if let Some(alias) = text[at..].strip_prefix("as").filter(|rest| rest.starts_with(char::is_whitespace)) {
                    let name_start = at + 2 + leading_space(alias);
                    at = name_start + text[name_start..].find(|c: char| !is_word(c)).unwrap_or(text.len() - name_start);
                    at += leading_space(&text[at..]);
                }
                match text[at..].chars().next() {
                    Some(',') => at += 1,
                    Some('}') => return at + 1,
                    _ => return at,
                }
            }
        }
        let word_length = text[at..].find(|c: char| !is_word(c)).unwrap_or(text.len() - at);
        if word_length == 0 {
            break;
        }
        let word = &text[at..at + word_length];
        at += word_length;
        if word != "self" {
            path.push(word.to_string());
        }
        match text[at..].strip_prefix("::") {
            Some(_) => at += 2,
            None => break,
        }
    }
    if path.len() > prefix.len() {
        out.push(path);
    }
    at
}

/// `text` with its `//` comments (doc comments too) blanked, lines kept.
fn without_comments(text: &str) -> String {
    text.lines().map(|line| line.split("//").next().unwrap_or("")).collect::<Vec<_>>().join("\n")
}

/// The absolute module path a path of `own`'s file names: `crate::a::b` or `super::a`
/// resolved, before its last segments are matched against the modules.
fn absolute(own: &[String], head: &str, segments: &[String]) -> Option<Vec<String>> {
    let mut base: Vec<String> = match head {
        "crate" => Vec::new(),
        _ => own.split_last()?.1.to_vec(),
    };
    let mut rest = segments;
    while let Some((first, tail)) = rest.split_first() {
        if first != "super" {
            break;
        }
        base.pop()?;
        rest = tail;
    }
    base.extend(rest.iter().cloned());
    Some(base)
}

/// The longest module of `modules` that `path` starts with.
fn module_named(path: &[String], modules: &BTreeSet<ModulePath>) -> Option<ModulePath> {
    (1..=path.len()).rev().map(|k| path[..k].to_vec()).find(|prefix| modules.contains(prefix))
}

#[test]
fn each_module_uses_only_the_modules_declared_before_it() {
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let order = declared_order(&source);
    assert!(order.len() >= 8, "src/lib.rs declares too few modules to check: {order:?}");
    let rank = |name: &str| order.iter().position(|m| m == name);
    let mut breaches = Vec::new();
    for (file, own) in library_files(&source) {
        // The crate root declares the order.
        let Some(own_rank) = own.first().and_then(|top| rank(top)) else { continue };
        let code = without_comments(&std::fs::read_to_string(&file).expect("readable source file"));
        for (line, head, segments) in paths(&code) {
            let Some(path) = absolute(&own, head, &segments) else { continue };
            // `crate::Error` and `crate::Result` are the error module's re-exports.
            let Some(top) = path.first().map(|name| if name == "Error" || name == "Result" { "error" } else { name.as_str() }) else {
                continue;
            };
            if rank(top).is_some_and(|used_rank| used_rank > own_rank) {
                let relative = file.strip_prefix(&source).expect("under src").display().to_string();
                breaches.push(format!("src/{relative}:{line}: `{}` uses `crate::{top}`, declared after it", own[0]));
            }
        }
    }
    assert!(breaches.is_empty(), "imports against the layer order of src/lib.rs ({}):\n{}", order.join(" < "), breaches.join("\n"));
}

#[test]
fn no_two_modules_use_each_other() {
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let files = library_files(&source);
    let modules: BTreeSet<ModulePath> = files.iter().map(|(_, module)| module.clone()).collect();
    let mut uses: BTreeMap<ModulePath, BTreeSet<ModulePath>> = BTreeMap::new();
    for (file, own) in &files {
        let code = without_comments(&std::fs::read_to_string(file).expect("readable source file"));
        for (_, head, segments) in paths(&code) {
            let Some(used) = absolute(own, head, &segments).and_then(|path| module_named(&path, &modules)) else { continue };
            // A module and its parent name each other by nature (`mod` items, `super::`).
            if !(used.starts_with(own) || own.starts_with(&used)) {
                uses.entry(own.clone()).or_default().insert(used);
            }
        }
    }
    // A circle: a module reachable from itself through the modules it uses.
    let mut circles = Vec::new();
    for start in uses.keys() {
        let mut stack: Vec<&ModulePath> = uses[start].iter().collect();
        let mut seen = BTreeSet::new();
        while let Some(next) = stack.pop() {
            if next == start {
                circles.push(format!("{} reaches itself", start.join("::")));
                break;
            }
            if seen.insert(next) {
                stack.extend(uses.get(next).into_iter().flatten());
            }
        }
    }
    assert!(circles.is_empty(), "modules that use each other, directly or through others:\n{}", circles.join("\n"));
}

#[test]
fn the_checker_reads_paths_in_code_and_in_groups() {
    let text = "use crate::mesh::Mesh;\nuse crate::{orient, refine::Criterion};\nlet x = crate::draw::f(); // crate::ffi in a comment\nsupercrate::x\nuse super::{\n    profile::{a, b},\n    self,\n    super::pipeline,\n};\nuse crate::{axis::Axis as A, synth};";
    let found: Vec<(usize, &str, String)> =
        paths(&without_comments(text)).into_iter().map(|(line, head, segments)| (line, head, segments.join("::"))).collect();
    let expected = [
        (1, "crate", "mesh::Mesh"),
        (2, "crate", "orient"),
        (2, "crate", "refine::Criterion"),
        (3, "crate", "draw::f"),
        (5, "super", "profile::a"),
        (5, "super", "profile::b"),
        (5, "super", "super::pipeline"),
        (10, "crate", "axis::Axis"),
        (10, "crate", "synth"),
    ];
    assert_eq!(found, expected.map(|(line, head, path)| (line, head, path.to_string())));
    let own = ["orient".to_string(), "verdict".to_string()];
    assert_eq!(absolute(&own, "super", &["super".to_string(), "refine".to_string()]), Some(vec!["refine".to_string()]));
    assert_eq!(absolute(&own, "super", &["axis".to_string()]), Some(vec!["orient".to_string(), "axis".to_string()]));
}
