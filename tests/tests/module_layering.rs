//! The core's modules form layers with no import circle, read from the `use` lines of
//! `core/src` (tests excluded):
//! - between top-level modules, every `crate::<module>` path is an edge, and the graph must be
//!   acyclic, with the query layer below every structure and structures independent of each
//!   other (the wide BVH, collapsed from the binary one, is the one exception);
//! - between files, every `use` path and every path written inline in code (`super::x::f()`,
//!   `crate::query::SplitRefs::NONE`) is resolved to the file that defines the item (through
//!   `pub use` re-exports), and no file may reach itself. A synthetic crate with an injected
//!   circle shows that the check finds one made by either kind of path.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// Top-level module → the top-level modules its code names.
fn module_graph() -> BTreeMap<String, BTreeSet<String>> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("../core/src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for file in files {
        let rel = file.strip_prefix(&src).unwrap();
        let first = rel
            .components()
            .next()
            .unwrap()
            .as_os_str()
            .to_string_lossy();
        let module = first.trim_end_matches(".rs").to_owned();
        if module == "lib" || module == "prelude" || module == "advanced" {
            continue; // the crate root, the prelude and `advanced` only re-export
        }
        let text = fs::read_to_string(&file).unwrap();
        let deps = graph.entry(module.clone()).or_default();
        for line in text.lines().take_while(|l| l.trim() != "#[cfg(test)]") {
            let code = line.split("//").next().unwrap_or("");
            for (at, _) in code.match_indices("crate::") {
                let name: String = code[at + 7..]
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                if !name.is_empty() && name != module {
                    deps.insert(name);
                }
            }
        }
    }
    graph
}

fn reaches(graph: &BTreeMap<String, BTreeSet<String>>, from: &str, to: &str) -> bool {
    let mut seen = BTreeSet::new();
    let mut stack = vec![from.to_owned()];
    while let Some(m) = stack.pop() {
        for d in graph.get(&m).into_iter().flatten() {
            if d == to {
                return true;
            }
            if seen.insert(d.clone()) {
                stack.push(d.clone());
            }
        }
    }
    false
}

#[test]
fn core_modules_have_no_import_circle() {
    let graph = module_graph();
    assert!(
        graph.contains_key("query") && graph.contains_key("bvh"),
        "{graph:?}"
    );
    for module in graph.keys() {
        assert!(
            !reaches(&graph, module, module),
            "{module} depends on itself through {:?}",
            graph[module]
        );
    }
}

#[test]
fn the_query_layer_sits_below_every_structure() {
    let graph = module_graph();
    let structures = ["bvh", "wide", "blob", "owned"];
    for s in structures {
        assert!(
            !reaches(&graph, "query", s),
            "query depends on {s}: {graph:?}"
        );
    }
    for low in ["math", "geom", "mesh", "error"] {
        for s in structures.iter().chain(&["query"]) {
            assert!(!reaches(&graph, low, s), "{low} depends on {s}: {graph:?}");
        }
    }
    // Structures do not know each other; the wide tree is collapsed from the binary one.
    assert!(!reaches(&graph, "bvh", "wide"), "{graph:?}");
    assert!(!reaches(&graph, "bvh", "blob"), "{graph:?}");
    assert!(!reaches(&graph, "wide", "blob"), "{graph:?}");
}

/// The code of a file up to its tests, comments removed.
fn code_of(file: &Path) -> String {
    let text = fs::read_to_string(file).unwrap();
    text.lines()
        .take_while(|l| l.trim() != "#[cfg(test)]")
        .map(|l| l.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The `use` declarations of `code`, each expanded into full paths (`a::{b, c::d}` gives
/// `a::b` and `a::c::d`; `self` in a group names the group's prefix).
fn use_paths(code: &str) -> Vec<Vec<String>> {
    fn expand(prefix: &[String], tree: &str, out: &mut Vec<Vec<String>>) {
        let tree = tree.trim();
        if let Some(open) = tree.find('{') {
            let head: Vec<String> = tree[..open]
                .split("::")
                .map(str::trim)
                .filter(|s| !s.is_empty())
                .map(String::from)
                .collect();
            let inner = &tree[open + 1..tree.rfind('}').unwrap()];
            let (mut depth, mut start) = (0, 0);
            let mut parts = Vec::new();
            for (i, c) in inner.char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        parts.push(&inner[start..i]);
                        start = i + 1;
                    }
                    _ => {}
                }
            }
            parts.push(&inner[start..]);
            let base: Vec<String> = prefix.iter().cloned().chain(head).collect();
            for part in parts.into_iter().filter(|p| !p.trim().is_empty()) {
                if part.trim() == "self" {
                    out.push(base.clone());
                } else {
                    expand(&base, part, out);
                }
            }
        } else {
            let name = tree.split(" as ").next().unwrap_or(tree);
            let mut path = prefix.to_vec();
            path.extend(name.split("::").map(|s| s.trim().to_owned()));
            out.push(path);
        }
    }
    let mut out = Vec::new();
    for (at, _) in code.match_indices("use ") {
        let before = code[..at].chars().last();
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
            continue;
        }
        let Some(end) = code[at..].find(';') else {
            continue;
        };
        let mut paths = Vec::new();
        expand(&[], &code[at + 4..at + end], &mut paths);
        out.extend(paths.into_iter().map(|p| from_file_module(code, at, p)));
    }
    out
}

/// How many inline modules (`mod tables { … }`) of `code` are open at byte `at`.
fn inline_modules_open_at(code: &str, at: usize) -> usize {
    let (mut depth, mut open) = (0usize, Vec::new());
    let bytes = code.as_bytes();
    for (i, &c) in bytes.iter().enumerate().take(at) {
        match c {
            b'{' => {
                // `mod name {`: the word before the name is `mod`.
                let head = code[..i].trim_end();
                let name_start = head
                    .rfind(|c: char| !(c.is_alphanumeric() || c == '_'))
                    .map_or(0, |k| k + 1);
                if head[..name_start].trim_end().ends_with("mod") && name_start < head.len() {
                    open.push(depth);
                }
                depth += 1;
            }
            b'}' => {
                depth = depth.saturating_sub(1);
                if open.last() == Some(&depth) {
                    open.pop();
                }
            }
            _ => {}
        }
    }
    open.len()
}

/// `path`, written at byte `at` of `code`, as seen from the file's own module: each leading
/// `super` that leaves an inline module stays in the file (it becomes `self`).
fn from_file_module(code: &str, at: usize, mut path: Vec<String>) -> Vec<String> {
    if path.first().is_none_or(|s| s != "super") {
        return path;
    }
    let mut inline = inline_modules_open_at(code, at);
    let mut stripped = false;
    while inline > 0 && path.first().is_some_and(|s| s == "super") {
        path.remove(0);
        inline -= 1;
        stripped = true;
    }
    if stripped && path.first().is_some_and(|s| s != "super") {
        path.insert(0, "self".to_owned());
    }
    path
}

/// The paths written inline in `code` outside `use` declarations that start at `crate`,
/// `super` or `self` (`super::check::check(..)` gives `super::check::check`), as seen from
/// the file's own module.
fn inline_paths(code: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    for start in ["crate::", "super::", "self::"] {
        for (at, _) in code.match_indices(start) {
            let before = code[..at].chars().last();
            if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
                continue; // inside a longer path (`super::super::`) or a word
            }
            let text: String = code[at..]
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':')
                .collect();
            let path: Vec<String> = text
                .split("::")
                .filter(|s| !s.is_empty())
                .map(String::from)
                .collect();
            if path.len() > 1 {
                out.push(from_file_module(code, at, path));
            }
        }
    }
    out
}

/// A module: its directory and the file that holds its code.
#[derive(Clone, Debug)]
struct Module {
    dir: PathBuf,
    file: PathBuf,
}

fn child(m: &Module, name: &str) -> Option<Module> {
    let as_dir = m.dir.join(name);
    if as_dir.join("mod.rs").is_file() {
        return Some(Module {
            file: as_dir.join("mod.rs"),
            dir: as_dir,
        });
    }
    let as_file = m.dir.join(format!("{name}.rs"));
    as_file.is_file().then(|| Module {
        dir: m.dir.join(name),
        file: as_file,
    })
}

/// The module that declares `m` (for a file module `x.rs` its directory's module, for a
/// `mod.rs` the directory above).
fn parent(m: &Module, root: &Path) -> Module {
    let dir = m.dir.parent().unwrap().to_path_buf();
    let file = if dir == root {
        root.join("lib.rs")
    } else {
        dir.join("mod.rs")
    };
    Module { dir, file }
}

fn module_of(file: &Path, root: &Path) -> Module {
    if file.ends_with("mod.rs") || file == root.join("lib.rs") {
        Module {
            dir: file.parent().unwrap().to_path_buf(),
            file: file.to_path_buf(),
        }
    } else {
        Module {
            dir: file.with_extension(""),
            file: file.to_path_buf(),
        }
    }
}

/// The file that defines what `path` names, seen from module `at`; `None` outside the crate.
fn resolve(path: &[String], at: &Module, root: &Path, depth: usize) -> Option<PathBuf> {
    if depth > 16 || path.is_empty() {
        return None;
    }
    let mut m = match path[0].as_str() {
        "crate" => Module {
            dir: root.to_path_buf(),
            file: root.join("lib.rs"),
        },
        "super" => parent(at, root),
        "self" => at.clone(),
        // Not a child module: another crate (core, glam, serde, …).
        first => child(at, first)?,
    };
    let mut rest = &path[1..];
    while let Some(seg) = rest.first() {
        if seg == "super" {
            m = parent(&m, root);
        } else if let Some(c) = child(&m, seg) {
            m = c;
        } else {
            // An item: defined in this module's file, or re-exported from elsewhere.
            for used in use_paths(&code_of(&m.file)) {
                if used.last() == Some(seg) && used.len() > 1 {
                    return resolve(&used, &m, root, depth + 1);
                }
            }
            return Some(m.file.clone());
        }
        rest = &rest[1..];
    }
    Some(m.file.clone())
}

/// File (relative to `root`) → the files its `use` lines and inline paths name.
fn file_graph(root: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let mut files = Vec::new();
    rust_files(root, &mut files);
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    let name = |p: &Path| p.strip_prefix(root).unwrap().display().to_string();
    for file in &files {
        let at = module_of(file, root);
        let deps = graph.entry(name(file)).or_default();
        let code = code_of(file);
        for path in use_paths(&code).into_iter().chain(inline_paths(&code)) {
            if let Some(target) = resolve(&path, &at, root, 0)
                && target != *file
            {
                deps.insert(name(&target));
            }
        }
    }
    graph
}

/// The files of `graph` that reach themselves, with what each uses.
fn circular(graph: &BTreeMap<String, BTreeSet<String>>) -> Vec<(&String, &BTreeSet<String>)> {
    graph.iter().filter(|(f, _)| reaches(graph, f, f)).collect()
}

#[test]
fn core_files_have_no_import_circle() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../core/src")
        .canonicalize()
        .unwrap();
    let graph = file_graph(&root);
    assert!(
        graph["query/ray.rs"].contains("query/traverse.rs"),
        "{graph:?}"
    );
    assert!(
        graph["bvh/traverse.rs"].contains("bvh/sizing.rs"),
        "{graph:?}"
    );
    // An inline path is an edge too: the grid's tree calls its check by path.
    assert!(graph["grid/tree.rs"].contains("grid/check.rs"), "{graph:?}");
    let circular = circular(&graph);
    assert!(
        circular.is_empty(),
        "files that reach themselves (file -> what it uses): {circular:?}"
    );
}

/// The check on a crate made here: `tree.rs` imports nothing from `check.rs` but calls it by
/// an inline path, and `check.rs` imports `tree.rs`'s type, the shape of the circle the k-d
/// tree and octree once had. Without the inline edge it goes unseen; with it, both files are
/// named, and nothing else: `super::` inside `check.rs`'s inline module names `check.rs`
/// itself, not its parent.
#[test]
fn an_injected_circle_through_an_inline_path_is_found() {
    let root = std::env::temp_dir().join(format!("meshq-layering-{}", std::process::id()));
    let _ = fs::remove_dir_all(&root);
    fs::create_dir_all(root.join("octree")).unwrap();
    let write = |rel: &str, text: &str| fs::write(root.join(rel), text).unwrap();
    write("lib.rs", "pub mod octree;\n");
    write(
        "octree/mod.rs",
        "mod check;\nmod tree;\npub use tree::Octree;\n",
    );
    write(
        "octree/tree.rs",
        "pub struct Octree;\nimpl Octree {\n    pub fn from_parts() -> Self {\n        \
         super::check::check(&Octree);\n        Octree\n    }\n}\n",
    );
    write(
        "octree/check.rs",
        "use super::Octree;\npub(super) fn check(_: &Octree) {}\n\
         mod inline {\n    pub(super) fn again() {\n        super::check(&super::Octree);\n    }\n}\n",
    );
    let graph = file_graph(&root);
    let found: Vec<&String> = circular(&graph).into_iter().map(|(f, _)| f).collect();
    // Only `use` lines: check.rs → tree.rs, no way back.
    assert!(
        !use_paths(&code_of(&root.join("octree/tree.rs")))
            .iter()
            .any(|p| p.iter().any(|s| s == "check")),
        "the circle is made by the inline path alone"
    );
    fs::remove_dir_all(&root).unwrap();
    assert_eq!(found, ["octree/check.rs", "octree/tree.rs"], "{graph:?}");
}
