//! The core's modules form layers with no import circle: every `crate::<module>` path in the
//! code of `core/src` (tests excluded) is an edge between two top-level modules, and the graph
//! must be acyclic, with the query layer below every structure and structures independent of
//! each other (the wide BVH, collapsed from the binary one, is the one exception).

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
        if module == "lib" || module == "prelude" {
            continue; // the crate root and the prelude only re-export
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
