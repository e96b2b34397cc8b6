//! Helpers for the end-to-end tests of the `helixhair` binary.
//!
//! The tests run the binary that Cargo built in the same profile as the
//! test itself: a test executable lives in `target/<profile>/deps/`, the
//! binary in `target/<profile>/`. Cargo builds that binary during
//! `cargo test --workspace` (or `-p helixhair-app -p helixhair-e2e`)
//! because the app package has integration tests of its own; when only this
//! package is tested, build it first with `cargo build -p helixhair-app`
//! (add `--release` for release tests), or the tests fail saying so.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The marker that broken fixtures put on the line an error must name.
pub const ERROR_MARKER: &str = "// <- error";

/// The workspace root (the parent of this package's directory).
pub fn workspace_root() -> PathBuf {
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    here.parent().unwrap_or(here).to_path_buf()
}

/// Path of the `helixhair` binary next to the running test's profile
/// directory; panics with build instructions when it is missing.
pub fn helixhair_bin() -> PathBuf {
    let exe = std::env::current_exe().expect("the test executable's path");
    // target/<profile>/deps/<test>-<hash> → target/<profile>/helixhair
    let profile_dir = exe
        .parent()
        .and_then(Path::parent)
        .expect("the test executable lies in target/<profile>/deps");
    let bin = profile_dir.join(format!("helixhair{}", std::env::consts::EXE_SUFFIX));
    if !bin.is_file() {
        let release = if profile_dir.ends_with("release") {
            " --release"
        } else {
            ""
        };
        panic!(
            "the helixhair binary is missing at {}: build it with `cargo build -p helixhair-app{release}` \
             (or run `cargo test --workspace{release}`, which builds it)",
            bin.display()
        );
    }
    bin
}

/// Runs `helixhair` with `args` from the workspace root.
pub fn run_helixhair(args: &[&str]) -> Output {
    Command::new(helixhair_bin())
        .args(args)
        .current_dir(workspace_root())
        .output()
        .expect("helixhair starts")
}

/// stdout and stderr of `output`, for assertion messages.
pub fn describe(output: &Output) -> String {
    format!(
        "status {}\n--- stdout\n{}\n--- stderr\n{}",
        output.status,
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    )
}

/// The example styles shipped in `assets/styles/`, relative to the root.
pub fn example_styles() -> Vec<String> {
    let dir = workspace_root().join("assets/styles");
    let mut styles: Vec<String> = std::fs::read_dir(&dir)
        .expect("assets/styles is readable")
        .map(|entry| {
            entry
                .expect("a directory entry")
                .file_name()
                .to_string_lossy()
                .into_owned()
        })
        .filter(|name| name.ends_with(".ron"))
        .map(|name| format!("assets/styles/{name}"))
        .collect();
    styles.sort();
    styles
}

/// The line number (from 1) of [`ERROR_MARKER`] in the file at `path`
/// (relative to the workspace root).
pub fn marker_line(path: &str) -> usize {
    let text =
        std::fs::read_to_string(workspace_root().join(path)).expect("the fixture is readable");
    text.lines()
        .position(|line| line.contains(ERROR_MARKER))
        .map(|i| i + 1)
        .unwrap_or_else(|| panic!("{path} has no `{ERROR_MARKER}` line"))
}

/// A fresh scratch directory for one test's output files.
pub fn scratch_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("helixhair-e2e-{name}-{}", std::process::id()));
    // A leftover from an earlier run with the same id is simply replaced.
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create a scratch directory");
    dir
}

/// Strongly connected groups of `graph` with more than one node,
/// each sorted, the groups in the order found (Tarjan's algorithm): the
/// cycles of a module or file graph (`app_modules.rs`, `file_circles.rs`).
pub fn strongly_connected(graph: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    struct Walk<'a> {
        graph: &'a BTreeMap<String, BTreeSet<String>>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        groups: Vec<Vec<String>>,
    }
    impl<'a> Walk<'a> {
        fn visit(&mut self, v: &'a str) {
            let i = self.index.len();
            self.index.insert(v, i);
            self.low.insert(v, i);
            self.stack.push(v);
            for w in &self.graph[v] {
                let w = w.as_str();
                if !self.index.contains_key(w) {
                    self.visit(w);
                    let low = self.low[v].min(self.low[w]);
                    self.low.insert(v, low);
                } else if self.stack.contains(&w) {
                    let low = self.low[v].min(self.index[w]);
                    self.low.insert(v, low);
                }
            }
            if self.low[v] == self.index[v] {
                let mut group = Vec::new();
                while let Some(w) = self.stack.pop() {
                    group.push(w.to_owned());
                    if w == v {
                        break;
                    }
                }
                if group.len() > 1 {
                    group.sort();
                    self.groups.push(group);
                }
            }
        }
    }
    let mut walk = Walk {
        graph,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        groups: Vec::new(),
    };
    for v in graph.keys() {
        if !walk.index.contains_key(v.as_str()) {
            walk.visit(v);
        }
    }
    walk.groups
}

/// The edges of `graph` inside `group` ("a → b, b → a"), to say what ties
/// a cycle [`strongly_connected`] found.
pub fn edges_within(graph: &BTreeMap<String, BTreeSet<String>>, group: &[String]) -> String {
    let edges: Vec<String> = group
        .iter()
        .flat_map(|a| {
            graph[a]
                .iter()
                .filter(|b| group.contains(b))
                .map(move |b| format!("{a} → {b}"))
        })
        .collect();
    edges.join(", ")
}
