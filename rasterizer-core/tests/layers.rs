//! The crate's module graph flows one way: each top-level module uses only modules of lower
//! layers, and no group of modules (down to the second level) uses itself in a cycle.
//!
//! The check reads the sources: every `crate::` path in code (comments and doc links are free to
//! point anywhere) and every `super::` path, resolved to the module it names.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// The layers, lowest first. A module may use modules of lower layers only.
const LAYERS: &[&[&str]] = &[
    // The 64-bit divisions every layer may need (math's exact ratios among them).
    &["wide"],
    &["math", "numerics", "color", "fingerprint"],
    &["geom", "texture"],
    &["surface"],
    &["mesh", "transform", "clip", "cull", "depth"],
    &["raster", "shade"],
    &["pipeline"],
    // Whole screens of commands, meshes among them.
    &["frame"],
    &["prelude"],
];

fn layer_of(module: &str) -> usize {
    LAYERS
        .iter()
        .position(|l| l.contains(&module))
        .unwrap_or_else(|| panic!("module `{module}` has no layer: add it to LAYERS"))
}

/// Module path of a source file: `src/raster/line/mod.rs` is `raster::line`.
fn module_of(src: &Path, file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(src).unwrap().with_extension("");
    let mut parts: Vec<String> = rel
        .iter()
        .map(|p| p.to_string_lossy().into_owned())
        .collect();
    if parts.last().is_some_and(|p| p == "mod" || p == "lib") {
        parts.pop();
    }
    parts
}

fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The source without comments (line, block and doc comments) and string literals.
fn code_only(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let b = text.as_bytes();
    let mut i = 0;
    while i < b.len() {
        if b[i..].starts_with(b"//") {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
        } else if b[i..].starts_with(b"/*") {
            let mut depth = 0;
            while i < b.len() {
                if b[i..].starts_with(b"/*") {
                    depth += 1;
                    i += 2;
                } else if b[i..].starts_with(b"*/") {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
        } else if b[i] == b'"' {
            i += 1;
            while i < b.len() && b[i] != b'"' {
                i += if b[i] == b'\\' { 2 } else { 1 };
            }
            i += 1;
        } else {
            out.push(b[i] as char);
            i += 1;
        }
    }
    out
}

fn is_ident(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

/// Every path starting with `root::` in `code`, with `use` groups (`a::{b, c::d}`) expanded, as
/// segments after the root.
fn paths_from(code: &str, root: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let pat = format!("{root}::");
    let mut start = 0;
    while let Some(found) = code[start..].find(&pat) {
        let at = start + found;
        start = at + pat.len();
        if code[..at].chars().next_back().is_some_and(is_ident) {
            continue;
        }
        expand(&code[start..], Vec::new(), &mut out);
    }
    out
}

/// Expands the use tree at the start of `rest` under `prefix`.
fn expand(rest: &str, prefix: Vec<String>, out: &mut Vec<Vec<String>>) -> usize {
    let rest_trim = rest.trim_start();
    let skipped = rest.len() - rest_trim.len();
    if let Some(inner) = rest_trim.strip_prefix('{') {
        let mut pos = 0;
        loop {
            let part = &inner[pos..];
            let item = part.trim_start_matches([' ', '\n', '\r', '\t', ',']);
            pos += part.len() - item.len();
            if item.is_empty() || item.starts_with('}') {
                return skipped + 1 + pos + 1;
            }
            pos += expand(item, prefix.clone(), out);
        }
    }
    let ident: String = rest_trim.chars().take_while(|&c| is_ident(c)).collect();
    if ident.is_empty() {
        out.push(prefix);
        return skipped + rest_trim.len().min(1);
    }
    let mut path = prefix;
    path.push(ident.clone());
    let after = &rest_trim[ident.len()..];
    if let Some(next) = after.strip_prefix("::") {
        return skipped + ident.len() + 2 + expand(next, path, out);
    }
    out.push(path);
    skipped + ident.len()
}

/// The module a path names, down to two levels: `raster::line::draw_line` is `raster::line` when
/// that is a module, `geom::SubPoint` is `geom`.
fn node(path: &[String], modules: &BTreeSet<Vec<String>>) -> Vec<String> {
    let two = path.iter().take(2).cloned().collect::<Vec<_>>();
    if two.len() == 2 && modules.contains(&two) {
        two
    } else {
        path.iter().take(1).cloned().collect()
    }
}

struct Graph {
    /// Module (two levels) -> modules it uses, each with a file that uses it.
    edges: BTreeMap<Vec<String>, BTreeMap<Vec<String>, PathBuf>>,
}

fn graph() -> Graph {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    sources(&src, &mut files);
    let modules: BTreeSet<Vec<String>> = files.iter().map(|f| module_of(&src, f)).collect();
    let mut edges: BTreeMap<_, BTreeMap<_, _>> = BTreeMap::new();
    for file in &files {
        let module = module_of(&src, file);
        if module.is_empty() {
            continue;
        }
        let code = code_only(&fs::read_to_string(file).unwrap());
        let from = node(&module, &modules);
        let mut used = paths_from(&code, "crate");
        // `super::x` from module `a::b` names `a::x`.
        for p in paths_from(&code, "super") {
            let mut full = module[..module.len() - 1].to_vec();
            full.extend(p);
            used.push(full);
        }
        for p in used {
            if p.is_empty() {
                continue;
            }
            let to = node(&p, &modules);
            if to != from {
                edges
                    .entry(from.clone())
                    .or_default()
                    .entry(to)
                    .or_insert_with(|| file.clone());
            }
        }
    }
    Graph { edges }
}

#[test]
fn modules_use_only_lower_layers() {
    let g = graph();
    let mut wrong = Vec::new();
    for (from, tos) in &g.edges {
        for (to, file) in tos {
            if from[0] != to[0] && layer_of(&to[0]) >= layer_of(&from[0]) {
                wrong.push(format!(
                    "{} uses {} ({})",
                    from.join("::"),
                    to.join("::"),
                    file.display()
                ));
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "uses against the layers:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn no_module_cycles() {
    let g = graph();
    // Depth-first search for a back edge.
    fn visit(
        n: &Vec<String>,
        g: &Graph,
        state: &mut BTreeMap<Vec<String>, u8>,
        stack: &mut Vec<Vec<String>>,
    ) -> Option<Vec<Vec<String>>> {
        match state.get(n) {
            Some(2) => return None,
            Some(1) => {
                let at = stack.iter().position(|m| m == n).unwrap();
                let mut cycle = stack[at..].to_vec();
                cycle.push(n.clone());
                return Some(cycle);
            }
            _ => {}
        }
        state.insert(n.clone(), 1);
        stack.push(n.clone());
        if let Some(tos) = g.edges.get(n) {
            for to in tos.keys() {
                // A module and its parent share a file tree; `a` using `a::b` is containment.
                if to.len() < n.len() && n.starts_with(to)
                    || n.len() < to.len() && to.starts_with(n)
                {
                    continue;
                }
                if let Some(c) = visit(to, g, state, stack) {
                    return Some(c);
                }
            }
        }
        stack.pop();
        state.insert(n.clone(), 2);
        None
    }
    let mut state = BTreeMap::new();
    for n in g.edges.keys() {
        let mut stack = Vec::new();
        if let Some(cycle) = visit(n, &g, &mut state, &mut stack) {
            let names: Vec<_> = cycle.iter().map(|m| m.join("::")).collect();
            panic!("module cycle: {}", names.join(" -> "));
        }
    }
}

#[test]
fn the_check_sees_grouped_and_relative_uses() {
    let code = code_only(
        "use crate::{a::{b::C, d}, e::F}; // crate::ignored::X\nfn f() { super::g::h(); }",
    );
    let paths = paths_from(&code, "crate");
    let flat: Vec<String> = paths.iter().map(|p| p.join("::")).collect();
    assert_eq!(flat, ["a::b::C", "a::d", "e::F"]);
    assert_eq!(paths_from(&code, "super"), [vec!["g", "h"]]);
}
