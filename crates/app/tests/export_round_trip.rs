//! Export round trips, per format: a shaken curly style exported frame by
//! frame, read back with `helixhair-formats`' readers, and compared with
//!
//! - the physics' own element end points (a known answer from another
//!   code path: with 15 elements and 16 points per strand, every exported
//!   point is an element end), to f32 rounding;
//! - the curves captured in memory, to the bit (the formats print the
//!   shortest decimal that reads back as the same f32);
//! - for USD (`.usda`, `.usdc`, `.usdz`), Pixar's own reader (`pxr`,
//!   from `usd-core`), and for Alembic (`.abc`) the Alembic library's
//!   (`alembic3d`): the same
//!   points at every time sample, and the head's transform at every time
//!   sample equal to the head's pose in the simulation. Skips without
//!   `pxr` unless `HELIXHAIR_REQUIRE_USD=1`, without `alembic3d` unless
//!   `HELIXHAIR_REQUIRE_ALEMBIC=1`.

use std::path::{Path, PathBuf};
use std::process::Command;

use glam::{DVec3, Vec3};
use helixhair_app::export::command::simulate_and_export;
use helixhair_app::export::{ExportSpec, FrameChoice, StrandChoice, capture_curves, sequence_path};
use helixhair_app::head::groom::Groom;
use helixhair_app::{HeadlessSim, SimOverrides, Style};
use helixhair_formats::{CurveSet, Format, Imported, ReadOptions, StrandValue, TriangleMesh, read};
use helixhair_render::head_generate::default_head;

#[path = "../../formats/tests/support/alembic.rs"]
mod alembic;
#[path = "../../formats/tests/support/pxr.rs"]
mod pxr;

use alembic::alembic_available;
use pxr::pxr_available;

/// Frames simulated (the export holds the start too).
const STEPS: usize = 6;

/// The curly example has 15 elements per strand: 16 points put one on
/// every element end (and 16 is a power of two, as TressFX needs).
const POINTS: usize = 16;

/// A point computed in f64 by two code paths, each rounded once to f32:
/// they differ by at most one f32 step at 0.3 m (3e-8 m).
const F32_ROUNDING_M: f32 = 6e-8;

fn curly() -> Style {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/styles/curly.ron");
    Style::load(Path::new(path)).expect("the curly example loads")
}

fn shaken_sim(style: &Style) -> HeadlessSim {
    let mut sim = HeadlessSim::new(style, SimOverrides::default()).expect("builds");
    sim.play(helixhair_app::motion::clip::Clip::Shake);
    sim
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("helixhair-export-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// Per frame (the start, then each step): every strand's element ends,
/// and the captured curves, from a second run in lockstep (the reference
/// engine is deterministic).
fn expected_frames(style: &Style) -> (Vec<Vec<Vec<Vec3>>>, Vec<CurveSet>) {
    let mut sim = shaken_sim(style);
    let mut ends = Vec::new();
    let mut captured = Vec::new();
    for frame in 0..=STEPS {
        if frame > 0 {
            sim.run(1).expect("finite");
        }
        let engine = sim.engine();
        ends.push(
            (0..engine.strand_count())
                .map(|i| {
                    engine
                        .boundary_points_world(i)
                        .into_iter()
                        .map(DVec3::as_vec3)
                        .collect()
                })
                .collect(),
        );
        captured
            .push(capture_curves(engine, None, StrandChoice::Simulated, POINTS).expect("captures"));
    }
    (ends, captured)
}

fn export(format: Format, dir: &Path, head: Option<&TriangleMesh>) -> PathBuf {
    let style = curly();
    let path = dir.join(format!("nested/curly.{format}"));
    let spec = ExportSpec::new(
        &path,
        StrandChoice::Simulated,
        POINTS,
        FrameChoice::All,
        true,
    )
    .expect("a valid spec");
    let mut sim = shaken_sim(&style);
    let (wall, outcome) =
        simulate_and_export(&mut sim, STEPS, spec, None, head, &mut |_| true).expect("exports");
    assert_eq!(wall.len(), STEPS);
    assert_eq!(outcome.frames, STEPS + 1);
    path
}

fn read_file(path: &Path) -> Imported {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let format = Format::from_path(path).expect("a known extension");
    read(&bytes, format, &ReadOptions::default())
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn flat(curves: &CurveSet) -> Vec<Vec3> {
    curves
        .curves
        .iter()
        .flat_map(|c| c.points_m.iter().copied())
        .collect()
}

fn assert_frame(read_points: &[Vec3], ends: &[Vec<Vec3>], captured: &CurveSet, what: &str) {
    assert_eq!(
        read_points,
        flat(captured),
        "{what}: not the captured points, bit for bit"
    );
    assert_eq!(read_points.len(), ends.len() * POINTS, "{what}");
    for (s, strand_ends) in ends.iter().enumerate() {
        assert_eq!(strand_ends.len(), POINTS, "{what}: 15 elements");
        for (k, want) in strand_ends.iter().enumerate() {
            let got = read_points[s * POINTS + k];
            let d = got.distance(*want);
            assert!(
                d <= F32_ROUNDING_M,
                "{what}: strand {s} point {k}: {got} is {d} m from {want}"
            );
        }
    }
}

#[test]
fn one_frame_formats_round_trip_as_numbered_sequences() {
    let (ends, captured) = expected_frames(&curly());
    for format in [Format::Hair, Format::Tfx, Format::Obj] {
        let dir = scratch(format.name());
        let path = export(format, &dir, None);
        assert!(!path.exists(), "{format}: a sequence, not one file");
        for frame in 0..=STEPS {
            let file = sequence_path(&path, frame);
            let imported = read_file(&file);
            assert_eq!(imported.animation, None);
            let what = format!("{} frame {frame}", file.display());
            assert_frame(
                &flat(&imported.curves),
                &ends[frame],
                &captured[frame],
                &what,
            );
            if format == Format::Hair {
                // .hair keeps widths (per point): the fibre diameter, 2 × 35 µm.
                for curve in &imported.curves.curves {
                    let widths = curve.width_m.as_ref().expect("widths");
                    assert!(
                        (0..POINTS).all(|k| widths.at(k) == Some(70e-6)),
                        "{what}: {widths:?}"
                    );
                }
            }
        }
        assert!(!sequence_path(&path, STEPS + 1).exists());
        let names: Vec<String> = std::fs::read_dir(path.parent().expect("folder"))
            .expect("lists")
            .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
            .collect();
        assert_eq!(
            names.len(),
            STEPS + 1,
            "{format}: no temporary files left: {names:?}"
        );
        std::fs::remove_dir_all(&dir).expect("clean up");
    }
}

#[test]
fn usda_round_trips_with_time_samples_widths_and_a_moving_head() {
    let (ends, captured) = expected_frames(&curly());
    let dir = scratch("usda");
    let head = helixhair_app::export::head_triangle_mesh(&default_head());
    let path = export(Format::Usda, &dir, Some(&head));
    let imported = read_file(&path);
    let animation = imported.animation.as_ref().expect("time samples");
    assert_eq!(animation.time_codes_per_second, 60.0);
    assert_eq!(animation.frames.len(), STEPS + 1);
    for (frame, sample) in animation.frames.iter().enumerate() {
        assert_eq!(sample.time_code, frame as f64);
        let what = format!("usda time code {frame}");
        assert_frame(&sample.points_m, &ends[frame], &captured[frame], &what);
    }
    for curve in &imported.curves.curves {
        assert_eq!(curve.width_m, Some(StrandValue::PerStrand(70e-6)));
    }
    pixar_reads(&path, &ends, &head);
    std::fs::remove_dir_all(&dir).expect("clean up");
}

/// Binary USD (issue 30): a crate file and a package hold what the text
/// layer holds, read back to the bit here and point for point by Pixar's
/// library, the head's pose at every sample included.
#[test]
fn binary_usd_round_trips_with_time_samples_widths_and_a_moving_head() {
    let (ends, captured) = expected_frames(&curly());
    let head = helixhair_app::export::head_triangle_mesh(&default_head());
    for format in [Format::Usdc, Format::Usdz] {
        let dir = scratch(format.name());
        let path = export(format, &dir, Some(&head));
        let imported = read_file(&path);
        let animation = imported.animation.as_ref().expect("time samples");
        assert_eq!(animation.time_codes_per_second, 60.0);
        assert_eq!(animation.frames.len(), STEPS + 1);
        for (frame, sample) in animation.frames.iter().enumerate() {
            assert_eq!(sample.time_code, frame as f64);
            let what = format!("{format} time code {frame}");
            assert_frame(&sample.points_m, &ends[frame], &captured[frame], &what);
        }
        for curve in &imported.curves.curves {
            assert_eq!(curve.width_m, Some(StrandValue::PerStrand(70e-6)));
        }
        pixar_reads(&path, &ends, &head);
        std::fs::remove_dir_all(&dir).expect("clean up");
    }
}

/// Alembic (issue 30): the curves' point samples and the head's sampled
/// transform, read back to the bit here and by the Alembic library.
#[test]
fn alembic_round_trips_with_samples_widths_and_a_moving_head() {
    let (ends, captured) = expected_frames(&curly());
    let head = helixhair_app::export::head_triangle_mesh(&default_head());
    let dir = scratch("abc");
    let path = export(Format::Abc, &dir, Some(&head));
    let imported = read_file(&path);
    let animation = imported.animation.as_ref().expect("samples");
    assert_eq!(animation.time_codes_per_second, 60.0);
    assert_eq!(animation.frames.len(), STEPS + 1);
    for (frame, sample) in animation.frames.iter().enumerate() {
        assert_eq!(sample.time_code, frame as f64);
        let what = format!("abc sample {frame}");
        assert_frame(&sample.points_m, &ends[frame], &captured[frame], &what);
    }
    for curve in &imported.curves.curves {
        assert_eq!(curve.width_m, Some(StrandValue::PerStrand(70e-6)));
    }
    alembic_reads(&path, &ends, &head);
    std::fs::remove_dir_all(&dir).expect("clean up");
}

/// Drawn strands need the groom; they come back as exported, widths per
/// point and colours per strand.
#[test]
fn drawn_strands_export_with_colours_and_tapered_widths() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/styles/groomed/curly.ron"
    );
    let style = Style::load(Path::new(path)).expect("loads");
    let groom = Groom::new(style.clone(), default_head());
    let dir = scratch("drawn");
    let out = dir.join("drawn.hair");
    let spec =
        ExportSpec::new(&out, StrandChoice::Drawn, 12, FrameChoice::Last, true).expect("spec");
    let mut sim = HeadlessSim::new(&groom.grown, SimOverrides::default()).expect("builds");
    let drawn_count = style
        .groups
        .iter()
        .map(|g| g.render.as_ref().map_or(0, |r| r.count))
        .sum::<u32>();
    simulate_and_export(&mut sim, 2, spec, Some(&groom), None, &mut |_| true).expect("exports");
    let imported = read_file(&out);
    assert_eq!(imported.curves.curves.len(), drawn_count as usize);
    let expected =
        capture_curves(sim.engine(), Some(&groom), StrandChoice::Drawn, 12).expect("captures");
    assert_eq!(flat(&imported.curves), flat(&expected));
    for (got, want) in imported.curves.curves.iter().zip(&expected.curves) {
        assert_eq!(got.points_m.len(), 12);
        let want_colour = want
            .colour
            .as_ref()
            .and_then(|c| c.at(0))
            .expect("a colour");
        let got_colour = got.colour.as_ref().expect("colours come back");
        assert!(
            (0..12).all(|k| got_colour.at(k) == Some(want_colour)),
            "{got_colour:?}"
        );
        let Some(StrandValue::PerPoint(widths)) = &got.width_m else {
            panic!("per-point widths, got {:?}", got.width_m);
        };
        assert!(
            widths.windows(2).all(|w| w[1] < w[0]),
            "tapering: {widths:?}"
        );
    }
    std::fs::remove_dir_all(&dir).expect("clean up");
}

const READ_WITH_PXR: &str = r#"
import sys
from pxr import Usd, UsdGeom
stage = Usd.Stage.Open(sys.argv[1])
curves = UsdGeom.BasisCurves(stage.GetPrimAtPath("/HelixHair/hair"))
print("counts", *curves.GetCurveVertexCountsAttr().Get())
head = UsdGeom.Mesh(stage.GetPrimAtPath("/HelixHair/head"))
print("head", len(head.GetPointsAttr().Get()), len(head.GetFaceVertexCountsAttr().Get()))
for time in curves.GetPointsAttr().GetTimeSamples():
    print("frame", time)
    for p in curves.GetPointsAttr().Get(time):
        print("p", repr(p[0]), repr(p[1]), repr(p[2]))
    world = UsdGeom.Xformable(head.GetPrim()).ComputeLocalToWorldTransform(Usd.TimeCode(time))
    # The head's vertex 0 and the head's +Z axis, in the world.
    v = head.GetPointsAttr().Get()[0]
    q = world.Transform(v)
    print("v0", repr(q[0]), repr(q[1]), repr(q[2]))
"#;

/// The same lines as [`READ_WITH_PXR`], from the Alembic library: the
/// head's vertex 0 through its sampled `Xform`.
const READ_WITH_ALEMBIC: &str = r#"
import sys
import imath
from alembic3d.Abc import IArchive, ISampleSelector
from alembic3d.AbcGeom import ICurves, IPolyMesh, IXform
top = IArchive(sys.argv[1]).getTop()
schema = ICurves(top, "hair").getSchema()
times = schema.getTimeSampling()
moving = IXform.matches(top.getChild("head").getHeader())
mesh = IPolyMesh(top.getChild("head"), "headShape") if moving else IPolyMesh(top, "head")
mesh = mesh.getSchema().getValue()
print("counts", *schema.getValue().getCurvesNumVertices())
print("head", len(mesh.getPositions()), len(mesh.getFaceCounts()))
for index in range(schema.getNumSamples()):
    time = times.getSampleTime(index)
    print("frame", time)
    for p in schema.getValue(ISampleSelector(time)).getPositions():
        print("p", repr(p[0]), repr(p[1]), repr(p[2]))
    v = mesh.getPositions()[0]
    q = imath.V3d(v[0], v[1], v[2])
    if moving:
        q = q * IXform(top, "head").getSchema().getValue(ISampleSelector(time)).getMatrix()
    print("v0", repr(q[0]), repr(q[1]), repr(q[2]))
"#;

fn pixar_reads(path: &Path, ends: &[Vec<Vec<Vec3>>], head: &TriangleMesh) {
    if pxr_available() {
        library_reads("pxr", READ_WITH_PXR, path, ends, head);
    }
}

fn alembic_reads(path: &Path, ends: &[Vec<Vec<Vec3>>], head: &TriangleMesh) {
    if alembic_available() {
        library_reads("alembic", READ_WITH_ALEMBIC, path, ends, head);
    }
}

/// Runs a reading script of another library and checks every frame's
/// points and the head's vertex 0 against the simulation.
fn library_reads(
    library: &str,
    script: &str,
    path: &Path,
    ends: &[Vec<Vec<Vec3>>],
    head: &TriangleMesh,
) {
    let output = Command::new("python3")
        .args(["-c", script])
        .arg(path)
        .output()
        .expect("python3 runs");
    assert!(
        output.status.success(),
        "{library}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    let text = String::from_utf8_lossy(&output.stdout);
    let numbers = |line: &str| -> Vec<f64> {
        line.split_whitespace()
            .skip(1)
            .map(|w| w.parse().expect("a number"))
            .collect()
    };
    let mut frames: Vec<(Vec<Vec3>, Vec<f64>)> = Vec::new();
    for line in text.lines() {
        match line.split_whitespace().next() {
            Some("counts") => assert_eq!(numbers(line), vec![POINTS as f64; ends[0].len()]),
            Some("head") => {
                assert_eq!(
                    numbers(line),
                    [head.vertices_m.len() as f64, head.triangles.len() as f64]
                );
            }
            Some("frame") => frames.push((Vec::new(), Vec::new())),
            Some("p") => {
                let p = numbers(line);
                let frame = frames.last_mut().expect("a frame first");
                frame
                    .0
                    .push(Vec3::new(p[0] as f32, p[1] as f32, p[2] as f32));
            }
            Some("v0") => frames.last_mut().expect("a frame first").1 = numbers(line),
            _ => {}
        }
    }
    assert_eq!(frames.len(), STEPS + 1, "{library} sees every time sample");
    // The shake clip's head pose at each frame's time, from the clip itself.
    let clip = helixhair_app::motion::clip::Clip::Shake;
    let v0 = head.vertices_m[0].as_dvec3();
    for (frame, (points, head_v0)) in frames.iter().enumerate() {
        for (s, strand) in ends[frame].iter().enumerate() {
            for (k, want) in strand.iter().enumerate() {
                let d = points[s * POINTS + k].distance(*want);
                assert!(
                    d <= F32_ROUNDING_M,
                    "{library} frame {frame} strand {s} point {k}: {d} m"
                );
            }
        }
        let (rotation, offset) = clip.pose_at(frame as f64 / 60.0);
        let want = rotation * v0 + offset;
        let got = DVec3::new(head_v0[0], head_v0[1], head_v0[2]);
        assert!(
            got.distance(want) < 1e-6,
            "{library} frame {frame}: head vertex 0 at {got}, want {want}"
        );
    }
}
