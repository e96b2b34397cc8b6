//! No import circles between files of different concerns, in any crate.
//!
//! A reader should be able to take the files of a crate one at a time, each
//! leaning only on files already read. Two files that name each other defeat
//! that: neither can be understood first. The one exception is a single
//! module written across several files (an `impl` block kept apart to keep a
//! file short, a builder beside the type it builds); those circles are
//! listed in [`ONE_MODULE_IN_SEVERAL_FILES`] with the reason, and the test
//! fails if a listed circle no longer exists, so the list stays true.
//!
//! # How it works
//!
//! Rust has no metadata for module dependencies, so the test reads the
//! sources of `crates/*/src`. Each file is a module: its path by Rust's
//! convention (`a/b.rs` and `a/b/mod.rs` are `a::b`), or the path a
//! `#[path = "…"] mod name;` declaration gives it (the `*_tests.rs` files).
//! Every `crate::…`, `super::…` and `self::…` path in a file (comments
//! removed, `use` groups opened) and every bare `use child::…` in a folder's
//! `mod.rs` names a module; the longest module prefix of the path is the
//! file it points at. Tarjan's algorithm then finds strongly connected
//! groups of files: a group of more than one file is a circle.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use helixhair_e2e::{edges_within, strongly_connected as circles, workspace_root};

/// Circles allowed because their files are one module's parts, each as
/// its files' paths under `crates/` (sorted), with why.
const ONE_MODULE_IN_SEVERAL_FILES: &[(&[&str], &str)] = &[
    (
        &[
            "app/src/window/state/app_state.rs",
            "app/src/window/state/head_of_style.rs",
            "app/src/window/state/unsaved.rs",
        ],
        "AppState's impl blocks for opening a style's head and for leaving unsaved work",
    ),
    (
        &[
            "physics/src/collision/sdf.rs",
            "physics/src/collision/sdf_build.rs",
        ],
        "the signed distance field and its builder",
    ),
    (
        &["physics/src/volume/cell.rs", "physics/src/volume/grid.rs"],
        "the hair-hair grid and the search of the cell holding a point",
    ),
];

/// One crate's source files: module path → file, and file → module path.
struct Sources {
    module_file: BTreeMap<Vec<String>, PathBuf>,
    file_module: BTreeMap<PathBuf, Vec<String>>,
}

/// The module path a file has by Rust's file naming convention.
fn conventional_module(relative: &Path) -> Vec<String> {
    let mut parts: Vec<String> = relative
        .with_extension("")
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if matches!(
        parts.last().map(String::as_str),
        Some("mod" | "lib" | "main")
    ) {
        parts.pop();
    }
    parts
}

/// Code without its `//` comments (doc comments included).
fn strip_comments(text: &str) -> String {
    text.lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n")
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("a readable source folder") {
        let path = entry.expect("a directory entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

fn read_sources(src: &Path) -> Sources {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    let mut file_module: BTreeMap<PathBuf, Vec<String>> = files
        .iter()
        .map(|f| {
            let relative = f.strip_prefix(src).expect("under src").to_path_buf();
            let module = conventional_module(&relative);
            (relative, module)
        })
        .collect();
    // `#[path = "x_tests.rs"] mod tests;` gives x_tests.rs the path x::tests.
    let declared: Vec<(PathBuf, Vec<String>)> = file_module
        .iter()
        .flat_map(|(relative, module)| {
            let text = std::fs::read_to_string(src.join(relative)).expect("a source file");
            let dir = relative.parent().unwrap_or(Path::new("")).to_path_buf();
            let mut found = Vec::new();
            let mut pending: Option<String> = None;
            for line in text.lines().map(str::trim) {
                if let Some(rest) = line.strip_prefix("#[path = \"") {
                    pending = rest.split('"').next().map(str::to_owned);
                } else if let Some(target) = pending.take() {
                    let name = line
                        .trim_start_matches("pub ")
                        .strip_prefix("mod ")
                        .and_then(|r| r.strip_suffix(';'));
                    match name {
                        Some(name) => {
                            let mut child = module.clone();
                            child.push(name.to_owned());
                            found.push((dir.join(target), child));
                        }
                        // An attribute between #[path] and mod: keep waiting.
                        None if line.starts_with("#[") => pending = Some(target),
                        None => {}
                    }
                }
            }
            found
        })
        .collect();
    for (file, module) in declared {
        file_module.insert(file, module);
    }
    let module_file = file_module
        .iter()
        .map(|(f, m)| (m.clone(), f.clone()))
        .collect();
    Sources {
        module_file,
        file_module,
    }
}

/// The identifiers of a path starting at `text` (`a::b::c`), stopping
/// before a `{` group or `*`; and the rest of the text.
fn path_at(text: &str) -> (Vec<String>, &str) {
    let mut segments = Vec::new();
    let mut rest = text;
    loop {
        let ident: String = rest
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
            .collect();
        if ident.is_empty() {
            break;
        }
        rest = &rest[ident.len()..];
        segments.push(ident);
        match rest.strip_prefix("::") {
            Some(after) if !after.starts_with('{') && !after.starts_with('*') => rest = after,
            _ => break,
        }
    }
    (segments, rest)
}

/// Every path a `use` group names, relative to the group's prefix: the
/// items of `{a::B, c::{d, e}}` are `a::B`, `c::d`, `c::e`.
fn group_paths(group: &str) -> Vec<Vec<String>> {
    let mut paths = Vec::new();
    let mut depth = 0;
    let mut item = String::new();
    let mut items = Vec::new();
    for c in group.chars() {
        match c {
            '{' => {
                depth += 1;
                item.push(c);
            }
            '}' => {
                depth -= 1;
                item.push(c);
            }
            ',' if depth == 0 => items.push(std::mem::take(&mut item)),
            c => item.push(c),
        }
    }
    items.push(item);
    for item in items {
        let item = item.trim();
        let (segments, rest) = path_at(item);
        if let Some(inner) = rest.strip_prefix("::{") {
            let inner = inner.strip_suffix('}').unwrap_or(inner);
            for sub in group_paths(inner) {
                paths.push(segments.iter().cloned().chain(sub).collect());
            }
        } else if !segments.is_empty() {
            paths.push(segments);
        }
    }
    paths
}

/// The text of the `{…}` group at the start of `text`, without its braces.
fn group_at(text: &str) -> &str {
    let mut depth = 0;
    for (i, c) in text.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => {
                depth -= 1;
                if depth == 0 {
                    return &text[1..i];
                }
            }
            _ => {}
        }
    }
    &text[1..]
}

/// The absolute paths (from the crate root) that `code` names, for a file
/// whose module is `module` (`is_folder`: a `mod.rs` or `lib.rs`, whose bare
/// `use` paths may name its children).
fn named_paths(code: &str, module: &[String], is_folder: bool) -> Vec<Vec<String>> {
    let mut found = Vec::new();
    let mut push_from = |base: Vec<String>, rest: &str| {
        let (segments, after) = path_at(rest);
        let base: Vec<String> = base.into_iter().chain(segments).collect();
        if let Some(group) = after.strip_prefix("::").filter(|g| g.starts_with('{')) {
            for sub in group_paths(group_at(group)) {
                found.push(base.iter().cloned().chain(sub).collect());
            }
        } else if after.starts_with('{') {
            for sub in group_paths(group_at(after)) {
                found.push(base.iter().cloned().chain(sub).collect());
            }
        } else {
            found.push(base);
        }
    };
    let boundary = |i: usize| {
        i == 0
            || !code[..i]
                .chars()
                .next_back()
                .is_some_and(|c| c.is_ascii_alphanumeric() || c == '_' || c == ':')
    };
    for (i, _) in code.match_indices("crate::") {
        if boundary(i) {
            push_from(Vec::new(), &code[i + "crate::".len()..]);
        }
    }
    for (i, _) in code.match_indices("self::") {
        if boundary(i) {
            push_from(module.to_vec(), &code[i + "self::".len()..]);
        }
    }
    for (i, _) in code.match_indices("super::") {
        if !boundary(i) {
            continue;
        }
        let mut rest = &code[i..];
        let mut base = module.to_vec();
        while let Some(after) = rest.strip_prefix("super::") {
            base.pop();
            rest = after;
        }
        push_from(base, rest);
    }
    if is_folder {
        for line in code.lines() {
            let line = line.trim();
            let line = line.strip_prefix("pub ").unwrap_or(line);
            if let Some(rest) = line.strip_prefix("use ")
                && !rest.starts_with("crate::")
                && !rest.starts_with("self::")
                && !rest.starts_with("super::")
            {
                push_from(module.to_vec(), rest);
            }
        }
    }
    found
}

/// What a folder's file re-exports: item name → the absolute path it
/// stands for (`pub use child::Item;` in `a/mod.rs`: `Item` → `a::child::Item`).
fn reexports(code: &str, module: &[String]) -> BTreeMap<String, Vec<String>> {
    let public_uses: String = code
        .split(';')
        .filter_map(|statement| statement.trim().strip_prefix("pub use "))
        .map(|rest| format!("use {rest};\n"))
        .collect();
    named_paths(&public_uses, module, true)
        .into_iter()
        .filter_map(|path| Some((path.last()?.clone(), path)))
        .collect()
}

/// File → the other files of its crate it names.
fn file_graph(crate_dir: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let src = crate_dir.join("src");
    let sources = read_sources(&src);
    let crate_name = crate_dir
        .file_name()
        .expect("a crate folder")
        .to_string_lossy()
        .into_owned();
    let label = |f: &Path| format!("{crate_name}/src/{}", f.display());
    // Item names a folder's file re-exports, so a path through the
    // re-export leads to the file that defines the item.
    let exported: BTreeMap<&PathBuf, BTreeMap<String, Vec<String>>> = sources
        .file_module
        .iter()
        .filter(|(f, _)| f.ends_with("mod.rs") || f.ends_with("lib.rs"))
        .map(|(f, m)| {
            let text = std::fs::read_to_string(src.join(f)).expect("a source file");
            (f, reexports(&strip_comments(&text), m))
        })
        .collect();
    let resolve = |path: &[String]| -> Option<&PathBuf> {
        let mut path = path.to_vec();
        // Follow re-exports a few times at most (a chain, never a loop).
        for _ in 0..4 {
            let n = (1..=path.len())
                .rev()
                .find(|n| sources.module_file.contains_key(&path[..*n]))?;
            let file = &sources.module_file[&path[..n]];
            match path.get(n).and_then(|item| exported.get(file)?.get(item)) {
                Some(target) if target.as_slice() != path.as_slice() => path = target.clone(),
                _ => return Some(file),
            }
        }
        None
    };
    let mut graph = BTreeMap::new();
    for (file, module) in &sources.file_module {
        let text = std::fs::read_to_string(src.join(file)).expect("a source file");
        let is_folder = file.ends_with("mod.rs") || file.ends_with("lib.rs");
        let mut targets = BTreeSet::new();
        for path in named_paths(&strip_comments(&text), module, is_folder) {
            // The longest prefix of the path that is a module is its file.
            let Some(target) = resolve(&path).filter(|t| *t != file) else {
                continue;
            };
            // A file naming a folder above it (`use super::*` in tests, a
            // submodule using its folder's items, often re-exports of its
            // siblings) is no edge: the folder declares the file and
            // exists to gather it, so the pair is one concern.
            let ancestor = sources.file_module[target].len() < module.len()
                && module.starts_with(&sources.file_module[target]);
            if !ancestor {
                targets.insert(label(target));
            }
        }
        graph.insert(label(file), targets);
    }
    graph
}

#[test]
fn the_reader_opens_use_groups_and_resolves_relative_paths() {
    let module = vec!["window".to_owned(), "state".to_owned()];
    let code = "use crate::{a::B, c::{d, e::F}};\nuse super::panels::ui;\nuse self::x::Y;";
    let paths: BTreeSet<String> = named_paths(code, &module, false)
        .into_iter()
        .map(|p| p.join("::"))
        .collect();
    let expected: BTreeSet<String> = [
        "a::B",
        "c::d",
        "c::e::F",
        "window::panels::ui",
        "window::state::x::Y",
    ]
    .map(String::from)
    .into();
    assert_eq!(paths, expected);
    let folder: BTreeSet<String> = named_paths("pub use child::Thing;", &module, true)
        .into_iter()
        .map(|p| p.join("::"))
        .collect();
    assert_eq!(folder, ["window::state::child::Thing".to_owned()].into());
}

#[test]
fn no_file_circles_but_one_module_in_several_files() {
    let crates = workspace_root().join("crates");
    let mut graph = BTreeMap::new();
    for entry in std::fs::read_dir(&crates).expect("the crates folder") {
        let dir = entry.expect("a crate").path();
        if dir.join("src").is_dir() {
            graph.extend(file_graph(&dir));
        }
    }
    assert!(graph.len() > 100, "read the crates' files: {}", graph.len());
    let allowed: Vec<Vec<String>> = ONE_MODULE_IN_SEVERAL_FILES
        .iter()
        .map(|(files, _)| files.iter().map(|f| (*f).to_owned()).collect())
        .collect();
    let found = circles(&graph);
    let explain = |group: &Vec<String>| edges_within(&graph, group);
    let unexpected: Vec<String> = found
        .iter()
        .filter(|g| !allowed.contains(g))
        .map(explain)
        .collect();
    assert!(
        unexpected.is_empty(),
        "files of different concerns import each other: {}",
        unexpected.join("; ")
    );
    for group in &allowed {
        assert!(
            found.contains(group),
            "ONE_MODULE_IN_SEVERAL_FILES lists {group:?}, which is no longer a circle: remove it"
        );
    }
}
