//! The layers of ARCHITECTURE.md, checked on Cargo's own dependency data:
//! physics knows nothing of rendering, windows, egui or file formats (and
//! its `gpu` feature adds only the wgpu stack); render knows nothing of the
//! physics or the app; the app's window and bench are cargo features that
//! the headless build leaves out.
//!
//! # How it works
//!
//! `cargo metadata` lists every package of the lock file with its declared
//! dependencies (optional or not, with the features they ask for), its
//! feature table, and the resolved graph (which package each dependency
//! became). [`closure`] walks that data from one package with a chosen
//! feature set, the way Cargo's feature resolver does for normal
//! dependencies: non-optional dependencies always, optional ones when a
//! feature enables them (`dep:x`, `x/f`, `x?/f` when `x` is on, or an
//! implicit feature named after the dependency), to a fixed point. Build
//! and dev dependencies are not followed (they are not linked into the
//! library). The metadata is filtered to the host platform (`cargo
//! metadata --filter-platform`, which also keeps it from needing other
//! platforms' packages offline), so the check holds for the platform that
//! builds; the layers are platform-independent manifests, so a crate
//! forbidden here could only enter elsewhere through a platform-specific
//! dependency of the workspace's own crates, which they do not declare.

use std::collections::{BTreeMap, BTreeSet};
use std::process::Command;
use std::sync::OnceLock;

use serde_json::Value;

/// The crates a library below the app must not reach: the other layers,
/// windows and egui, and the file formats (styles, meshes, pictures,
/// tables, charts, JSON).
const WINDOW_AND_FORMATS: [&str; 12] = [
    "helixhair-app",
    "winit",
    "egui",
    "egui-wgpu",
    "egui-winit",
    "ron",
    "tobj",
    "image",
    "png",
    "csv",
    "plotters",
    "serde_json",
];

/// What the physics crate's `gpu` feature may add as direct dependencies.
const GPU_ADDITIONS: [&str; 4] = ["wgpu", "bytemuck", "pollster", "helixhair-gpu"];

/// The window's and the bench's own crates, which the headless app leaves out.
const WINDOW_CRATES: [&str; 4] = ["winit", "egui", "egui-wgpu", "egui-winit"];
const BENCH_CRATES: [&str; 2] = ["plotters", "csv"];

/// `cargo metadata` of the workspace, parsed.
struct Metadata {
    /// Package id → package.
    packages: BTreeMap<String, Value>,
    /// Package id → resolved dependency package ids.
    resolved: BTreeMap<String, Vec<String>>,
}

/// The host's target triple, as `cargo -vV` reports it.
fn host_triple() -> String {
    let output = Command::new(env!("CARGO"))
        .arg("-vV")
        .output()
        .expect("cargo -vV runs");
    let text = String::from_utf8_lossy(&output.stdout).into_owned();
    text.lines()
        .find_map(|l| l.strip_prefix("host: "))
        .expect("cargo -vV names the host")
        .to_owned()
}

impl Metadata {
    /// The workspace's metadata, read once for all the tests.
    fn get() -> &'static Self {
        static METADATA: OnceLock<Metadata> = OnceLock::new();
        METADATA.get_or_init(Self::load)
    }

    fn load() -> Self {
        let host = host_triple();
        let output = Command::new(env!("CARGO"))
            .args(["metadata", "--format-version", "1", "--offline", "--locked"])
            .args(["--filter-platform", &host])
            .current_dir(helixhair_e2e::workspace_root())
            .output()
            .expect("cargo metadata runs");
        assert!(
            output.status.success(),
            "cargo metadata failed: {}",
            String::from_utf8_lossy(&output.stderr)
        );
        let json: Value = serde_json::from_slice(&output.stdout).expect("cargo metadata's JSON");
        let packages = json["packages"]
            .as_array()
            .expect("packages")
            .iter()
            .map(|p| (p["id"].as_str().expect("id").to_owned(), p.clone()))
            .collect();
        let resolved = json["resolve"]["nodes"]
            .as_array()
            .expect("resolve nodes")
            .iter()
            .map(|n| {
                let deps = n["dependencies"].as_array().expect("dependencies");
                let deps = deps.iter().map(|d| d.as_str().expect("id").to_owned());
                (n["id"].as_str().expect("id").to_owned(), deps.collect())
            })
            .collect();
        Self { packages, resolved }
    }

    /// The id of the workspace package `name`.
    fn id(&self, name: &str) -> String {
        self.packages
            .iter()
            .find(|(_, p)| p["name"] == name && p["source"].is_null())
            .map(|(id, _)| id.clone())
            .unwrap_or_else(|| panic!("no workspace package {name}"))
    }

    fn name(&self, id: &str) -> &str {
        self.packages[id]["name"].as_str().expect("name")
    }

    /// The package a normal dependency `dep` of package `id` resolved to
    /// (`None` when the workspace's resolution never enabled it).
    fn target(&self, id: &str, dep: &Value) -> Option<String> {
        let name = dep["name"].as_str().expect("dependency name");
        self.resolved
            .get(id)?
            .iter()
            .find(|t| self.name(t) == name)
            .cloned()
    }
}

/// The name a dependency goes by in its package's feature table.
fn dep_key(dep: &Value) -> &str {
    dep["rename"]
        .as_str()
        .unwrap_or_else(|| dep["name"].as_str().expect("dependency name"))
}

/// Normal (not build or dev) dependencies of a package.
fn normal_deps(package: &Value) -> impl Iterator<Item = &Value> {
    package["dependencies"]
        .as_array()
        .expect("dependencies")
        .iter()
        .filter(|d| d["kind"].is_null())
}

/// What one package links with `features` on (its default features too
/// when `default`): every package reached, by id, with the features it
/// ends up with.
fn closure(
    meta: &Metadata,
    root: &str,
    features: &[&str],
    default: bool,
) -> BTreeMap<String, BTreeSet<String>> {
    let root_id = meta.id(root);
    let mut on: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    let mut root_features: BTreeSet<String> = features.iter().map(|f| f.to_string()).collect();
    if default {
        root_features.insert("default".into());
    }
    on.insert(root_id, root_features);
    let mut enabled_deps: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    loop {
        let before = (on.clone(), enabled_deps.clone());
        for id in on.keys().cloned().collect::<Vec<_>>() {
            let package = &meta.packages[&id];
            let table = package["features"].as_object().expect("features");
            let optional: BTreeSet<&str> = normal_deps(package)
                .filter(|d| d["optional"] == true)
                .map(dep_key)
                .collect();
            // Expand the package's features into features and enabled deps.
            let mut stack: Vec<String> = on[&id].iter().cloned().collect();
            let mut seen = BTreeSet::new();
            let mut dep_features: Vec<(String, String)> = Vec::new();
            let mut weak: Vec<(String, String)> = Vec::new();
            while let Some(feature) = stack.pop() {
                if !seen.insert(feature.clone()) {
                    continue;
                }
                let Some(values) = table.get(&feature) else {
                    // An implicit feature: an optional dependency's name.
                    if optional.contains(feature.as_str()) {
                        enabled_deps.entry(id.clone()).or_default().insert(feature);
                    }
                    continue;
                };
                for value in values.as_array().expect("feature values") {
                    let value = value.as_str().expect("feature value");
                    if let Some(dep) = value.strip_prefix("dep:") {
                        enabled_deps
                            .entry(id.clone())
                            .or_default()
                            .insert(dep.into());
                    } else if let Some((dep, feature)) = value.split_once("?/") {
                        weak.push((dep.into(), feature.into()));
                    } else if let Some((dep, feature)) = value.split_once('/') {
                        if optional.contains(dep) {
                            enabled_deps
                                .entry(id.clone())
                                .or_default()
                                .insert(dep.into());
                        }
                        dep_features.push((dep.into(), feature.into()));
                    } else {
                        stack.push(value.into());
                    }
                }
            }
            on.get_mut(&id).expect("on").extend(seen);
            let enabled = enabled_deps.get(&id).cloned().unwrap_or_default();
            for dep in normal_deps(package) {
                let key = dep_key(dep);
                if dep["optional"] == true && !enabled.contains(key) {
                    continue;
                }
                let Some(target) = meta.target(&id, dep) else {
                    continue;
                };
                let mut wanted: BTreeSet<String> = dep["features"]
                    .as_array()
                    .expect("features")
                    .iter()
                    .map(|f| f.as_str().expect("feature").to_owned())
                    .collect();
                if dep["uses_default_features"] == true {
                    wanted.insert("default".into());
                }
                for (d, f) in dep_features.iter().chain(&weak) {
                    if d == key {
                        wanted.insert(f.clone());
                    }
                }
                on.entry(target).or_default().extend(wanted);
            }
        }
        if (on.clone(), enabled_deps.clone()) == before {
            return on;
        }
    }
}

/// The package names of a closure.
fn names(meta: &Metadata, closure: &BTreeMap<String, BTreeSet<String>>) -> BTreeSet<String> {
    closure.keys().map(|id| meta.name(id).to_owned()).collect()
}

/// The direct dependencies of `root` with `features` (no defaults).
fn direct(meta: &Metadata, root: &str, features: &[&str]) -> BTreeSet<String> {
    let root_id = meta.id(root);
    let reached = closure(meta, root, features, false);
    let package = &meta.packages[&root_id];
    normal_deps(package)
        .filter_map(|d| meta.target(&root_id, d))
        .filter(|t| reached.contains_key(t))
        .map(|t| meta.name(&t).to_owned())
        .collect()
}

fn assert_none_of(reached: &BTreeSet<String>, forbidden: &[&str], what: &str) {
    let found: Vec<&&str> = forbidden.iter().filter(|f| reached.contains(**f)).collect();
    assert!(found.is_empty(), "{what} reaches {found:?}");
}

#[test]
fn physics_depends_on_no_render_app_window_egui_or_file_format_crate() {
    let meta = Metadata::get();
    let plain = names(meta, &closure(meta, "helixhair-physics", &[], true));
    let mut forbidden = vec!["helixhair-render"];
    forbidden.extend(WINDOW_AND_FORMATS);
    assert_none_of(&plain, &forbidden, "helixhair-physics (default features)");
    assert_none_of(
        &plain,
        &["helixhair-gpu", "wgpu", "naga", "pollster"],
        "helixhair-physics without `gpu`",
    );
    for needed in ["glam", "nalgebra", "rayon", "wide"] {
        assert!(
            plain.contains(needed),
            "the walk misses {needed}: {plain:?}"
        );
    }

    let gpu = names(meta, &closure(meta, "helixhair-physics", &["gpu"], true));
    assert_none_of(&gpu, &forbidden, "helixhair-physics with `gpu`");
    let added: BTreeSet<String> = direct(meta, "helixhair-physics", &["gpu"])
        .difference(&direct(meta, "helixhair-physics", &[]))
        .cloned()
        .collect();
    assert!(added.contains("wgpu"), "`gpu` adds wgpu: {added:?}");
    let other: Vec<&String> = added
        .iter()
        .filter(|a| !GPU_ADDITIONS.contains(&a.as_str()))
        .collect();
    assert!(other.is_empty(), "`gpu` adds more than wgpu's: {other:?}");
}

#[test]
fn render_depends_on_neither_the_physics_nor_the_app() {
    let meta = Metadata::get();
    let reached = names(meta, &closure(meta, "helixhair-render", &[], true));
    assert_none_of(
        &reached,
        &["helixhair-physics", "helixhair-app", "winit", "egui"],
        "helixhair-render",
    );
}

#[test]
fn the_app_without_default_features_leaves_the_window_and_the_bench_out() {
    let meta = Metadata::get();
    let physics = meta.id("helixhair-physics");
    let headless = closure(meta, "helixhair-app", &[], false);
    let headless_names = names(meta, &headless);
    assert_none_of(&headless_names, &WINDOW_CRATES, "the headless app");
    assert_none_of(&headless_names, &BENCH_CRATES, "the headless app");
    assert!(
        !headless[&physics].contains("gpu"),
        "the headless app turns on the physics' `gpu`"
    );

    let window = names(meta, &closure(meta, "helixhair-app", &["window"], false));
    for c in WINDOW_CRATES {
        assert!(window.contains(c), "feature `window` lacks {c}");
    }
    assert_none_of(&window, &BENCH_CRATES, "feature `window`");

    let bench = closure(meta, "helixhair-app", &["bench"], false);
    let bench_names = names(meta, &bench);
    for c in BENCH_CRATES {
        assert!(bench_names.contains(c), "feature `bench` lacks {c}");
    }
    assert_none_of(&bench_names, &WINDOW_CRATES, "feature `bench`");
    assert!(
        bench[&physics].contains("gpu"),
        "the bench's throughput study needs the physics' `gpu`"
    );

    let default = names(meta, &closure(meta, "helixhair-app", &[], true));
    for c in WINDOW_CRATES.iter().chain(&BENCH_CRATES) {
        assert!(default.contains(*c), "the default app lacks {c}");
    }
}

#[test]
fn the_formats_crate_reaches_no_other_layer_and_none_below_the_app_reaches_it() {
    let meta = Metadata::get();
    let formats = names(meta, &closure(meta, "helixhair-formats", &[], true));
    assert_none_of(
        &formats,
        &[
            "helixhair-physics",
            "helixhair-render",
            "helixhair-app",
            "helixhair-gpu",
            "wgpu",
            "winit",
            "egui",
            "ron",
            "serde_json",
        ],
        "helixhair-formats",
    );
    for below in ["helixhair-physics", "helixhair-render"] {
        let reached = names(meta, &closure(meta, below, &[], true));
        assert_none_of(&reached, &["helixhair-formats"], below);
    }
}
