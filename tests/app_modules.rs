//! The app crate's modules lean on each other in one direction only: the
//! graph of its top-level modules (`crates/app/src/*.rs` and folders such
//! as `window/` and `bench/`) has no cycle, so the style format, the
//! simulation core's face (`headless`), the commands and the optional faces
//! (window, bench) stand in layers a reader can take one at a time.
//!
//! # How it works
//!
//! Rust has no metadata for module dependencies, so the test reads the
//! sources: an edge A → B for every `crate::B` path in A's files (comments
//! removed, `use crate::{B, C}` groups included), then Tarjan's algorithm
//! finds strongly connected groups. A group of more than one module is a
//! cycle, and the message names its modules and the edges between them.
//! Test modules (`*_tests.rs`) count like any other file: a test that needs
//! a module above its own is a sign the code is in the wrong place.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use helixhair_e2e::{edges_within, strongly_connected as cycles, workspace_root};

/// Top-level module → the top-level modules its files name.
fn module_graph(src: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    let mut stack = vec![src.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).expect("the app's sources are readable") {
            let path = entry.expect("a directory entry").path();
            if path.is_dir() {
                stack.push(path);
                continue;
            }
            if path.extension().is_none_or(|e| e != "rs") {
                continue;
            }
            let relative = path.strip_prefix(src).expect("under src");
            let first = relative.components().next().expect("a component");
            let top = first
                .as_os_str()
                .to_string_lossy()
                .trim_end_matches(".rs")
                .to_owned();
            if top == "main" || top == "lib" {
                continue;
            }
            let text = std::fs::read_to_string(&path).expect("a source file");
            let edges = graph.entry(top.clone()).or_default();
            for target in crate_paths(&text) {
                if target != top {
                    edges.insert(target);
                }
            }
        }
    }
    let modules: BTreeSet<String> = graph.keys().cloned().collect();
    for edges in graph.values_mut() {
        edges.retain(|m| modules.contains(m));
    }
    graph
}

/// The first segment of every `crate::` path in `text`, comments removed.
fn crate_paths(text: &str) -> BTreeSet<String> {
    let code: String = text
        .lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n");
    let mut found = BTreeSet::new();
    let ident = |s: &str| -> String {
        s.trim_start()
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
            .collect()
    };
    for (i, _) in code.match_indices("crate::") {
        let rest = &code[i + "crate::".len()..];
        if let Some(group) = rest.strip_prefix('{') {
            let inner = group.split('}').next().unwrap_or("");
            // Top-level items of the group: names after `{` or a comma
            // outside nested braces.
            let mut depth = 0;
            let mut start = true;
            for (j, c) in inner.char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' => depth -= 1,
                    ',' if depth == 0 => start = true,
                    c if start && !c.is_whitespace() => {
                        found.insert(ident(&inner[j..]));
                        start = false;
                    }
                    _ => {}
                }
            }
        } else {
            found.insert(ident(rest));
        }
    }
    found.remove("");
    found
}

#[test]
fn the_cycle_finder_finds_a_cycle_and_reads_use_groups() {
    let paths = crate_paths("use crate::{a::X, b, c::{d, e}}; // crate::z\nlet _ = crate::f::g();");
    let expected: BTreeSet<String> = ["a", "b", "c", "f"].map(String::from).into();
    assert_eq!(paths, expected);
    let graph: BTreeMap<String, BTreeSet<String>> = [
        ("a", vec!["b"]),
        ("b", vec!["c"]),
        ("c", vec!["a"]),
        ("d", vec!["a"]),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_owned(), v.into_iter().map(String::from).collect()))
    .collect();
    assert_eq!(cycles(&graph), vec![vec!["a", "b", "c"]]);
}

#[test]
fn the_app_modules_form_no_cycle() {
    let graph = module_graph(&workspace_root().join("crates/app/src"));
    assert!(graph.len() > 10, "read the app's modules: {graph:?}");
    let found = cycles(&graph);
    let explain: Vec<String> = found
        .iter()
        .map(|group| format!("{{{}}}: {}", group.join(", "), edges_within(&graph, group)))
        .collect();
    assert!(
        found.is_empty(),
        "cycles among the app's modules: {}",
        explain.join("; ")
    );
}
