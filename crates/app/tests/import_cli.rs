//! `helixhair import` end to end: grooms written by the test (clean and
//! hostile) through the binary; the style it writes runs with `sim` and
//! survives a save and load.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use helixhair_app::style::Style;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("helixhair-import-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

fn helixhair(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_helixhair"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// A TressFX 4 file: `strands` strands of `points` points, each an arc
/// hanging from y = 0.1 (metres).
fn tfx(strands: u32, points: u32, declared_strands: u32) -> Vec<u8> {
    let mut b = Vec::new();
    b.extend_from_slice(&4.0f32.to_le_bytes());
    b.extend_from_slice(&declared_strands.to_le_bytes());
    b.extend_from_slice(&points.to_le_bytes());
    b.extend_from_slice(&160u32.to_le_bytes());
    for _ in 0..4 + 32 {
        b.extend_from_slice(&0u32.to_le_bytes());
    }
    for s in 0..strands {
        for p in 0..points {
            let t = p as f32 / (points - 1) as f32;
            let x = 0.01 * s as f32 + 0.1 * (t * 1.2).sin();
            let y = 0.1 - 0.1 * (1.0 - (t * 1.2).cos());
            for v in [x, y, 0.0, if p == 0 { 0.0 } else { 1.0 }] {
                b.extend_from_slice(&v.to_le_bytes());
            }
        }
    }
    b
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> String {
    let path = dir.join(name);
    std::fs::write(&path, bytes).expect("write groom");
    path.display().to_string()
}

#[test]
fn an_obj_groom_imports_reports_and_simulates() {
    let dir = scratch("obj");
    // Two clean arcs and two degenerate strands: one point only, and a NaN.
    let mut obj = String::new();
    let mut v = 0;
    for s in 0..2 {
        let first = v + 1;
        for p in 0..8 {
            let t = p as f64 / 7.0;
            obj += &format!(
                "v {} {} 0\n",
                0.02 * s as f64 + 0.1 * t.sin(),
                0.1 * t.cos()
            );
            v += 1;
        }
        let list: Vec<String> = (first..=v).map(|i| i.to_string()).collect();
        obj += &format!("l {}\n", list.join(" "));
    }
    obj += "v 0 0 0\nv nan 0 0\nv 0 1 0\n";
    obj += &format!("l {} {}\n", v + 1, v + 2);
    obj += &format!("l {}\n", v + 3);
    let groom = write(&dir, "groom.obj", obj.as_bytes());
    let style = dir.join("style.ron").display().to_string();
    let report = dir.join("report.json").display().to_string();
    let out = helixhair(&["import", &groom, "--out", &style, "--json", &report]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).expect("report")).expect("JSON");
    assert_eq!(json["strands_imported"], 2, "{json}");
    assert!(json["strands_read"].as_u64().expect("count") >= 3, "{json}");
    assert!(
        json["skipped"].as_object().expect("map").values().count() >= 1,
        "{json}"
    );
    let max = json["fit_error_over_length"]["max"].as_f64().expect("max");
    assert!(max <= 0.005, "{json}");
    assert!(json["sag_free"]["held"].as_u64().is_some(), "{json}");

    // The style loads, saves and loads back the same, and `sim` runs it.
    let loaded = Style::load(Path::new(&style)).expect("the written style loads");
    let again = dir.join("again.ron");
    loaded.save(&again).expect("saves");
    assert_eq!(Style::load(&again).expect("reloads"), loaded);
    let imported = loaded.groups[0].imported.as_ref().expect("imported group");
    assert_eq!(imported.source, "groom.obj");
    let out = helixhair(&["sim", "--style", &style, "--steps", "3"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
}

#[test]
fn the_material_given_at_import_sets_the_style_and_the_sag_free_shape() {
    // Issue 30: the sag-free solve balances weight against stiffness, so
    // the material must be the hair's. The same arcs imported as the
    // default fibre and as one twice as dense: the style records each
    // material, and the denser hair's natural strains differ (it needs
    // more curvature to hang in the same shape).
    let dir = scratch("material");
    let groom = write(&dir, "groom.tfx", &tfx(3, 16, 3));
    let import = |name: &str, extra: &[&str]| {
        let style = dir.join(name).display().to_string();
        let mut args = vec!["import", groom.as_str(), "--out", style.as_str()];
        args.extend_from_slice(extra);
        let out = helixhair(&args);
        assert!(out.status.success(), "{}", text(&out.stderr));
        Style::load(Path::new(&style)).expect("the written style loads")
    };
    let plain = import("plain.ron", &[]);
    let curly = format!(
        "{}/../../assets/styles/curly.ron",
        env!("CARGO_MANIFEST_DIR")
    );
    let dense = import(
        "dense.ron",
        &["--material", &curly, "--density-kg-per-m3", "2600"],
    );
    let curly = Style::load(Path::new(&curly)).expect("the example loads");
    let (plain_params, dense_params) = (&plain.groups[0].params, &dense.groups[0].params);
    assert_eq!(plain_params.density_kg_per_m3, 1300.0);
    assert_eq!(dense_params.density_kg_per_m3, 2600.0);
    assert_eq!(dense_params.radius_m, curly.groups[0].params.radius_m);
    assert_eq!(dense_params.ellipticity, curly.groups[0].params.ellipticity);
    let natural = |style: &Style| -> Vec<glam::DVec3> {
        let imported = style.groups[0].imported.as_ref().expect("imported");
        imported
            .strands
            .iter()
            .flat_map(|s| s.natural.clone())
            .collect()
    };
    let (a, b) = (natural(&plain), natural(&dense));
    assert_eq!(a.len(), b.len());
    let moved = a
        .iter()
        .zip(&b)
        .map(|(x, y)| (*x - *y).length())
        .fold(0.0, f64::max);
    assert!(
        moved > 1e-3,
        "the denser hair's natural strains moved {moved} m⁻¹"
    );
    // An impossible value is refused, naming the flag and the field.
    let style = dir.join("bad.ron").display().to_string();
    let out = helixhair(&["import", &groom, "--out", &style, "--radius-m=-1"]);
    assert_eq!(out.status.code(), Some(1));
    let message = text(&out.stderr);
    assert!(
        message.contains("--radius-m") && message.contains("radius_m"),
        "{message}"
    );
    assert!(!Path::new(&style).exists(), "nothing written");
}

#[test]
fn guides_are_a_subset_and_the_rest_follow() {
    let dir = scratch("guides");
    let groom = write(&dir, "g.tfx", &tfx(6, 8, 6));
    let style = dir.join("s.ron").display().to_string();
    let out = helixhair(&[
        "import",
        &groom,
        "--guides",
        "2",
        "--no-sag-free",
        "--out",
        &style,
        "--json",
        "-",
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON on stdout");
    assert_eq!(
        (json["guides"].as_u64(), json["strands_imported"].as_u64()),
        (Some(2), Some(6))
    );
    assert!(json["sag_free"].is_null());
    let loaded = Style::load(Path::new(&style)).expect("loads");
    let imported = loaded.groups[0].imported.as_ref().expect("imported");
    // Farthest-point sampling: the first strand and the one farthest from it.
    let guides: Vec<usize> = (0..6).filter(|&i| imported.strands[i].guide).collect();
    assert_eq!(guides, vec![0, 5]);
    assert!(imported.strands.iter().all(|s| s.natural == s.strains));
}

/// Each hostile groom must fail with exit code 1 and a message naming the
/// file and what is wrong.
#[test]
fn malformed_grooms_are_clear_errors_with_exit_code_1() {
    let dir = scratch("bad");
    let good = tfx(3, 8, 3);
    let mut wrong_magic = good.clone();
    wrong_magic[..4].copy_from_slice(&7.5f32.to_le_bytes());
    let mut nan = tfx(2, 8, 2);
    for s in 0..2 {
        let at = 160 + s * 8 * 16 + 16;
        nan[at..at + 4].copy_from_slice(&f32::NAN.to_le_bytes());
    }
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        (
            "truncated.tfx",
            good[..good.len() - 40].to_vec(),
            "not a valid groom",
        ),
        ("header.tfx", good[..20].to_vec(), "not a valid groom"),
        ("magic.tfx", wrong_magic, "not a valid groom"),
        ("counts.tfx", tfx(3, 8, 5), "not a valid groom"),
        ("absurd.tfx", tfx(1, 8, u32::MAX), "not a valid groom"),
        ("nan.tfx", nan, "no strand could be imported"),
        ("groom.xyz", good.clone(), "unknown groom format"),
        ("bad.hair", b"HAIRxx".to_vec(), "not a valid groom"),
        // Issue 32, item 11: a layer without metersPerUnit is read in
        // centimetres, USD's fallback; when that leaves nothing to import,
        // the error says so (it gave only the skipped counts).
        (
            "no_unit.usda",
            b"#usda 1.0\n(\n    upAxis = \"Y\"\n)\n\ndef BasisCurves \"hair\"\n{\n    \
              uniform token type = \"linear\"\n    int[] curveVertexCounts = [6]\n    \
              point3f[] points = [(0, 0, 0), (0.1, 0, 0), (0.1, 0.1, 0), (0.2, 0.1, 0), \
              (0.2, 0.2, 0), (0.3, 0.2, 0)]\n}\n"
                .to_vec(),
            "metersPerUnit",
        ),
    ];
    for (name, bytes, expect) in cases {
        let groom = write(&dir, name, &bytes);
        let style = dir.join(format!("{name}.ron"));
        let out = helixhair(&["import", &groom, "--out", &style.display().to_string()]);
        let err = text(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{name}: {err}");
        assert!(err.contains(name) && err.contains(expect), "{name}: {err}");
        assert!(!style.exists(), "{name}: no style may be written");
    }
    let missing = helixhair(&["import", "no/such/groom.tfx", "--out", "x.ron"]);
    assert_eq!(missing.status.code(), Some(1));
    assert!(text(&missing.stderr).contains("no/such/groom.tfx"));
    // An impossible tolerance is refused, naming the flag, before any fit.
    let groom = write(&dir, "good.tfx", &good);
    for (flag, value) in [
        ("--fit-tolerance", "0"),
        ("--natural-tolerance", "0"),
        ("--natural-tolerance", "1.5"),
    ] {
        let style = dir.join("tolerance.ron").display().to_string();
        let out = helixhair(&["import", &groom, "--out", &style, flag, value]);
        let err = text(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{flag} {value}: {err}");
        assert!(
            err.contains(&format!("{flag} {value}")) && err.contains("must lie in (0, 1)"),
            "{flag} {value}: {err}"
        );
    }
}

/// An OBJ groom of straight strands rooted at y = 0 (metres), one per
/// length given, 2 cm apart, leaning 3° off the vertical (a perfectly
/// upright column is an equilibrium no round-off disturbs).
fn upright_obj(lengths_m: &[f64]) -> String {
    let mut obj = String::new();
    let mut v = 0;
    for (s, length) in lengths_m.iter().enumerate() {
        let first = v + 1;
        for p in 0..12 {
            let y = length * p as f64 / 11.0;
            obj += &format!("v {} {y} 0\n", 0.02 * s as f64 + 0.05 * y);
            v += 1;
        }
        let list: Vec<String> = (first..=v).map(|i| i.to_string()).collect();
        obj += &format!("l {}\n", list.join(" "));
    }
    obj
}

/// Largest distance between the boundary points of the strands in a `sim`
/// JSON report and the same strands in another, metres.
fn moved_m(start: &serde_json::Value, end: &serde_json::Value) -> f64 {
    let points = |json: &serde_json::Value| -> Vec<[f64; 3]> {
        json["strands"]
            .as_array()
            .expect("strands")
            .iter()
            .flat_map(|s| s["points_m"].as_array().expect("points").clone())
            .map(|p| {
                let p = p.as_array().expect("a point");
                [0, 1, 2].map(|i| p[i].as_f64().expect("a number"))
            })
            .collect()
    };
    points(start)
        .iter()
        .zip(points(end))
        .map(|(a, b)| (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt())
        .fold(0.0, f64::max)
}

#[test]
fn strands_standing_past_their_buckling_length_are_stiffened_and_stand() {
    // Default hair buckles under its own weight standing up longer than
    // about 11 cm (Greenhill's column); 30 cm strands are far past it, a
    // 5 cm one is not.
    let dir = scratch("stiffen");
    let groom = write(
        &dir,
        "upright.obj",
        upright_obj(&[0.3, 0.3, 0.05]).as_bytes(),
    );
    let run = |extra: &[&str], name: &str| -> (serde_json::Value, f64) {
        let style = dir.join(format!("{name}.ron")).display().to_string();
        let mut args = vec!["import", &groom, "--out", &style, "--json", "-"];
        args.extend_from_slice(extra);
        let out = helixhair(&args);
        assert!(out.status.success(), "{}", text(&out.stderr));
        let report: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
        let sim = |steps: &str| -> serde_json::Value {
            let out = helixhair(&["sim", "--style", &style, "--steps", steps, "--json", "-"]);
            // A falling strand may well trip the guard; the shape is what is judged.
            let out = if out.status.success() {
                out
            } else {
                helixhair(&[
                    "sim",
                    "--style",
                    &style,
                    "--steps",
                    steps,
                    "--json",
                    "-",
                    "--accept-resets",
                ])
            };
            assert!(out.status.success(), "{}", text(&out.stderr));
            serde_json::from_slice(&out.stdout).expect("sim JSON")
        };
        (report, moved_m(&sim("1"), &sim("600")))
    };
    let (report, moved) = run(&[], "stiffened");
    assert_eq!(report["sag_free"]["stiffened"], 2, "{report}");
    assert_eq!(report["sag_free"]["held"], 1, "{report}");
    assert!(
        moved < 1e-3,
        "the stiffened strands moved {moved} m in 10 s"
    );
    let style = Style::load(&dir.join("stiffened.ron")).expect("loads");
    let strands = &style.groups[0].imported.as_ref().expect("imported").strands;
    assert!(strands[0].stiffness_scale > 1.0 && strands[2].stiffness_scale == 1.0);

    let (report, fell) = run(&["--no-stiffen"], "left");
    assert_eq!(report["sag_free"]["unstable"], 2, "{report}");
    assert!(
        fell > 0.05,
        "unstiffened, the strands should fall: moved {fell} m"
    );
}

/// The default head moved 1.5 m up and 0.3 m aside, as a scanned bust
/// stands in its file, and three 8 cm strands from its crown, as OBJ.
fn lifted_head_and_groom(dir: &Path) -> (String, String) {
    use helixhair_render::head_generate::default_head;
    let lift = glam::Vec3::new(0.3, 1.5, 0.0);
    let mut head = default_head();
    for p in &mut head.mesh.positions {
        *p += lift;
    }
    let crown = head
        .mesh
        .positions
        .iter()
        .copied()
        .fold(
            glam::Vec3::splat(f32::MIN),
            |a, b| if b.y > a.y { b } else { a },
        );
    let mut obj = String::new();
    for s in 0..3 {
        for p in 0..9 {
            let t = p as f32 / 8.0;
            let at = crown + glam::Vec3::new(0.08 * t, 0.001, 0.01 * s as f32 - 0.01);
            obj += &format!("v {} {} {}\n", at.x, at.y, at.z);
        }
        let list: Vec<String> = (s * 9 + 1..=s * 9 + 9).map(|i| i.to_string()).collect();
        obj += &format!("l {}\n", list.join(" "));
    }
    let head_obj = helixhair_render::obj::write_head_obj(&head, "lifted");
    (
        write(dir, "head.obj", head_obj.as_bytes()),
        write(dir, "groom.obj", obj.as_bytes()),
    )
}

#[test]
fn an_imported_head_far_from_the_origin_nods_about_itself() {
    // A 20° nod about the origin would carry hair 1.5 m up through about
    // half a metre; about the head's own pivot the tips stay near it.
    let dir = scratch("pivot");
    let (head, groom) = lifted_head_and_groom(&dir);
    let style = dir.join("lifted.ron").display().to_string();
    let out = helixhair(&["import", &groom, "--head", &head, "--out", &style]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let args = ["sim", "--style", &style, "--steps", "90", "--play", "nod"];
    let out = helixhair(&[&args[..], &["--tip-trajectories", "--json", "-"]].concat());
    assert!(out.status.success(), "{}", text(&out.stderr));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let travel_m = json["tip_trajectories"]["tips_m"]
        .as_array()
        .expect("tips")
        .iter()
        .map(|tips| {
            let tips: Vec<[f64; 3]> = tips
                .as_array()
                .expect("a strand's tips")
                .iter()
                .map(|p| [0, 1, 2].map(|i| p[i].as_f64().expect("a number")))
                .collect();
            tips.iter()
                .map(|p| {
                    (0..3)
                        .map(|i| (p[i] - tips[0][i]).powi(2))
                        .sum::<f64>()
                        .sqrt()
                })
                .fold(0.0, f64::max)
        })
        .fold(0.0, f64::max);
    assert!(
        travel_m < 0.1,
        "the tips travelled {travel_m} m during the nod"
    );
}

#[test]
fn sim_export_of_an_imported_groom_carries_its_own_head_under_the_hair() {
    // Issue 32, item 2: `sim --export` wrote the default head (at the
    // origin) under hair imported 1.5 m up on its own head.
    let dir = scratch("export-head");
    let (head, groom) = lifted_head_and_groom(&dir);
    let style = dir.join("lifted.ron").display().to_string();
    let out = helixhair(&["import", &groom, "--head", &head, "--out", &style]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let usda = dir.join("out.usda").display().to_string();
    let args = ["sim", "--style", &style, "--steps", "3", "--export", &usda];
    let out = helixhair(&args);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let written = std::fs::read_to_string(dir.join("out.usda")).expect("the export");
    let (low, high) = helixhair_app::export::usda_head_extent(&written).expect("a head");
    let hair = helixhair_formats::read(
        written.as_bytes(),
        helixhair_formats::Format::Usda,
        &helixhair_formats::ReadOptions::default(),
    )
    .expect("the hair reads back");
    let points: Vec<glam::Vec3> = hair
        .curves
        .curves
        .iter()
        .flat_map(|c| c.points_m.iter().copied())
        .collect();
    let hair_low = points.iter().fold(f32::MAX, |a, p| a.min(p.y));
    let hair_high = points.iter().fold(f32::MIN, |a, p| a.max(p.y));
    // The head is under the hair: the strands, lying on its crown, start
    // within a centimetre of its top (the default head at the origin would
    // put its top 1.5 m below them).
    assert!(
        low.y < f64::from(hair_high) && f64::from(hair_low) < high.y + 0.01,
        "head y {:.2}..{:.2}, hair y {hair_low:.2}..{hair_high:.2}",
        low.y,
        high.y
    );
}

/// Issue 30: a binary crate file Pixar's USD wrote (centimetres, Z up, a
/// transformed parent, time samples) imports; `sim --export` writes a
/// `.usdc` and `export` a `.usdz` and a `.usd`, which import again.
#[test]
fn binary_usd_grooms_import_and_every_command_exports_them() {
    let dir = scratch("binary-usd");
    let groom = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../formats/tests/data/pxr_groom.usdc"
    );
    let style = dir.join("pxr.ron").display().to_string();
    let report = dir.join("report.json").display().to_string();
    let out = helixhair(&["import", groom, "--out", &style, "--json", &report]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).expect("report")).expect("JSON");
    // 20 animated strands and 16 static ones; a class and an inactive prim
    // are not read.
    assert_eq!(json["strands_read"], 36, "{json}");
    assert_eq!(json["format"], "usdc", "{json}");
    let read = |path: &Path| {
        let bytes = std::fs::read(path).expect("the export");
        let format = helixhair_formats::Format::from_path(path).expect("a USD name");
        helixhair_formats::read(&bytes, format, &helixhair_formats::ReadOptions::default())
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
    };
    let usdc = dir.join("sim.usdc");
    let usdc_name = usdc.display().to_string();
    let args = [
        "sim", "--style", &style, "--steps", "3", "--export", &usdc_name,
    ];
    let out = helixhair(&args);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let frames = read(&usdc).animation.expect("time samples").frames;
    assert_eq!(frames.len(), 4, "the start and 3 steps");
    for name in ["last.usdz", "last.usd"] {
        let path = dir.join(name);
        let path_name = path.display().to_string();
        let out = helixhair(&["export", "--style", &style, "--out", &path_name]);
        assert!(out.status.success(), "{name}: {}", text(&out.stderr));
        assert!(!read(&path).curves.curves.is_empty(), "{name}");
        let again = dir.join(format!("{name}.ron")).display().to_string();
        let out = helixhair(&["import", &path_name, "--out", &again]);
        assert!(out.status.success(), "{name}: {}", text(&out.stderr));
    }
    std::fs::remove_dir_all(&dir).expect("clean up");
}

/// Issue 30: an Alembic archive the Alembic library wrote (a transformed
/// parent, samples at 30 per second, indexed and Unreal widths) imports;
/// `sim --export` writes an `.abc` that imports again.
#[test]
fn alembic_grooms_import_and_sim_exports_them() {
    let dir = scratch("alembic");
    let groom = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../formats/tests/data/alembic3d_groom.abc"
    );
    let style = dir.join("abc.ron").display().to_string();
    let report = dir.join("report.json").display().to_string();
    let out = helixhair(&["import", groom, "--out", &style, "--json", &report]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).expect("report")).expect("JSON");
    assert_eq!(json["strands_read"], 7, "{json}");
    assert_eq!(json["format"], "abc", "{json}");
    let abc = dir.join("sim.abc");
    let abc_name = abc.display().to_string();
    let args = [
        "sim", "--style", &style, "--steps", "3", "--export", &abc_name,
    ];
    let out = helixhair(&args);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let bytes = std::fs::read(&abc).expect("the export");
    let read = helixhair_formats::read(
        &bytes,
        helixhair_formats::Format::Abc,
        &helixhair_formats::ReadOptions::default(),
    )
    .expect("reads");
    assert_eq!(read.animation.expect("samples").frames.len(), 4);
    let again = dir.join("again.ron").display().to_string();
    let out = helixhair(&["import", &abc_name, "--out", &again]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    std::fs::remove_dir_all(&dir).expect("clean up");
}
