//! An independent reader: Pixar's own USD library (`usd-core` from PyPI,
//! imported as `pxr`) opens what `write_usda` wrote and reads the same
//! points at every time sample, the same counts, widths and head; and it
//! composes transforms as our reader does.
//!
//! Skips with a message where `python3 -c "import pxr"` fails, unless
//! `HELIXHAIR_REQUIRE_USD=1` (as CI sets), which makes it fail instead.

use crate::common;
use crate::pxr;

use pxr::pxr_available;

use std::path::PathBuf;
use std::process::Command;

use glam::Vec3;
use helixhair_formats::{Animation, Format, Frame, ReadOptions, TriangleMesh, read, write_usda};

/// Transforms are composed in `f64` by both sides, then rounded to `f32`.
const TRANSFORM_TOLERANCE_M: f32 = 2e-6;

fn temp_path(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("helixhair-formats-{}-{name}", std::process::id()))
}

/// Runs a Python script with pxr over a layer and returns its stdout lines.
fn run_python(script: &str, layer: &PathBuf) -> Vec<String> {
    let output = Command::new("python3")
        .args(["-c", script])
        .arg(layer)
        .output()
        .expect("python3 runs");
    assert!(
        output.status.success(),
        "pxr script failed:\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8_lossy(&output.stdout)
        .lines()
        .map(str::to_string)
        .collect()
}

fn numbers(line: &str) -> Vec<f64> {
    line.split_whitespace()
        .skip(1)
        .map(|word| word.parse().expect("a number"))
        .collect()
}

const READ_CURVES: &str = r#"
import sys
from pxr import Usd, UsdGeom
stage = Usd.Stage.Open(sys.argv[1])
print("meters", UsdGeom.GetStageMetersPerUnit(stage))
print("up", 1 if UsdGeom.GetStageUpAxis(stage) == UsdGeom.Tokens.y else 0)
print("tcps", stage.GetTimeCodesPerSecond())
curves = UsdGeom.BasisCurves(stage.GetPrimAtPath("/HelixHair/hair"))
print("type", 1 if curves.GetTypeAttr().Get() == "linear" else 0)
print("counts", *curves.GetCurveVertexCountsAttr().Get())
print("widths", *curves.GetWidthsAttr().Get())
for time in curves.GetPointsAttr().GetTimeSamples():
    print("frame", time)
    for p in curves.GetPointsAttr().Get(time):
        print("p", repr(p[0]), repr(p[1]), repr(p[2]))
head = UsdGeom.Mesh(stage.GetPrimAtPath("/HelixHair/head"))
print("head", len(head.GetPointsAttr().Get()), len(head.GetFaceVertexCountsAttr().Get()))
"#;

#[test]
fn a_still_frame_carries_the_simulation_rate_to_pixar_usd() {
    // Issue 32, item 11: a one-frame `.usda` said USD's fallback of 24 time
    // codes per second while the animations said 60.
    if !pxr_available() {
        return;
    }
    let curves = common::groom(3, 5, 6, false, false);
    let still = Animation {
        time_codes_per_second: 60.0,
        frames: Vec::new(),
    };
    let path = temp_path("still.usda");
    let mut bytes = Vec::new();
    write_usda(&mut bytes, &curves, Some(&still), None).expect("writes");
    std::fs::write(&path, &bytes).expect("temp file");
    let script = "import sys\nfrom pxr import Usd\nstage = Usd.Stage.Open(sys.argv[1])\nprint('tcps', stage.GetTimeCodesPerSecond())\n";
    let lines = run_python(script, &path);
    let _ = std::fs::remove_file(&path);
    assert_eq!(lines, ["tcps 60.0"]);
    // And our own reader reads the still frame as a still groom.
    let back = read(&bytes, Format::Usda, &ReadOptions::default()).expect("reads back");
    assert_eq!(back.curves.curves.len(), curves.curves.len());
    assert!(back.animation.is_none());
}

#[test]
fn pixar_usd_reads_what_we_write() {
    if !pxr_available() {
        return;
    }
    let curves = common::groom(21, 12, 6, true, true);
    let frames: Vec<Frame> = (0..4)
        .map(|k| {
            let mut frame = Frame::from_curves(k as f64 * 2.0, &curves);
            for (index, point) in frame.points_m.iter_mut().enumerate() {
                point.y -= 0.0007 * (k * index) as f32;
            }
            frame
        })
        .collect();
    let animation = Animation {
        time_codes_per_second: 48.0,
        frames,
    };
    let head = TriangleMesh {
        vertices_m: vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
    };
    let path = temp_path("written.usda");
    let mut bytes = Vec::new();
    write_usda(&mut bytes, &curves, Some(&animation), Some(&head)).expect("writes");
    std::fs::write(&path, &bytes).expect("temp file");
    let lines = run_python(READ_CURVES, &path);
    let _ = std::fs::remove_file(&path);

    let value = |key: &str| {
        numbers(
            lines
                .iter()
                .find(|l| l.starts_with(&format!("{key} ")))
                .expect(key),
        )
    };
    assert_eq!(value("meters"), [1.0]);
    assert_eq!(value("up"), [1.0]);
    assert_eq!(value("tcps"), [48.0]);
    assert_eq!(value("type"), [1.0]);
    assert_eq!(value("counts"), vec![6.0; 12]);
    let widths: Vec<f32> = value("widths").iter().map(|&w| w as f32).collect();
    let expected_widths: Vec<f32> = curves
        .curves
        .iter()
        .flat_map(|c| (0..6).map(|i| c.width_m.as_ref().and_then(|w| w.at(i)).expect("width")))
        .collect();
    assert_eq!(widths, expected_widths);
    assert_eq!(value("head"), [4.0, 2.0]);

    let mut pxr_frames: Vec<(f64, Vec<Vec3>)> = Vec::new();
    for line in &lines {
        if line.starts_with("frame ") {
            pxr_frames.push((numbers(line)[0], Vec::new()));
        } else if line.starts_with("p ") {
            let p = numbers(line);
            let frame = pxr_frames.last_mut().expect("a frame first");
            frame
                .1
                .push(Vec3::new(p[0] as f32, p[1] as f32, p[2] as f32));
        }
    }
    assert_eq!(pxr_frames.len(), 4);
    for ((time, points), frame) in pxr_frames.iter().zip(&animation.frames) {
        assert_eq!(*time, frame.time_code);
        common::assert_points_equal(points, &frame.points_m, &format!("pxr frame {time}"));
    }
}

const WORLD_POINTS: &str = r#"
import sys
from pxr import Usd, UsdGeom
stage = Usd.Stage.Open(sys.argv[1])
cache = UsdGeom.XformCache(Usd.TimeCode.Default())
for prim in stage.Traverse():
    if prim.IsA(UsdGeom.BasisCurves):
        world = cache.GetLocalToWorldTransform(prim)
        for p in UsdGeom.BasisCurves(prim).GetPointsAttr().Get():
            q = world.Transform(p)
            print("p", repr(q[0]), repr(q[1]), repr(q[2]))
"#;

const TRANSFORMED: &str = r#"#usda 1.0
(
    metersPerUnit = 0.01
    upAxis = "Z"
)
def Xform "root"
{
    double3 xformOp:translate = (10, -3, 2)
    float3 xformOp:rotateZYX = (15, 30, -45)
    float3 xformOp:scale = (2, 1, 0.5)
    uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:rotateZYX", "xformOp:scale"]
    def Xform "mid"
    {
        quatf xformOp:orient = (0.9238795, 0, 0.3826834, 0)
        double3 xformOp:translate:pivot = (1, 2, 3)
        float xformOp:rotateX = 20
        uniform token[] xformOpOrder = ["xformOp:translate:pivot", "xformOp:orient", "xformOp:rotateX", "!invert!xformOp:translate:pivot"]
        def BasisCurves "a"
        {
            float3 xformOp:rotateXYZ = (10, 20, 30)
            float3 xformOp:rotateYXZ = (-5, 40, 12)
            uniform token[] xformOpOrder = ["xformOp:rotateXYZ", "xformOp:rotateYXZ"]
            uniform token type = "linear"
            int[] curveVertexCounts = [3]
            point3f[] points = [(0, 0, 0), (1, 2, 3), (-4, 5, 6)]
        }
    }
    def BasisCurves "b"
    {
        matrix4d xformOp:transform = ( (0, 1, 0, 0), (-1, 0, 0, 0), (0, 0, 1, 0), (7, 8, 9, 1) )
        float3 xformOp:rotateXZY = (33, -21, 8)
        float3 xformOp:rotateYZX = (3, 6, 9)
        float3 xformOp:rotateZXY = (-12, 24, 48)
        uniform token[] xformOpOrder = ["xformOp:transform", "xformOp:rotateXZY", "xformOp:rotateYZX", "xformOp:rotateZXY"]
        uniform token type = "linear"
        int[] curveVertexCounts = [2]
        point3f[] points = [(1, 0, 0), (0, 1, 1)]
    }
    def BasisCurves "c"
    {
        double3 xformOp:translate = (100, 0, 0)
        uniform token[] xformOpOrder = ["!resetXformStack!", "xformOp:translate"]
        uniform token type = "linear"
        int[] curveVertexCounts = [2]
        point3f[] points = [(1, 0, 0), (0, 1, 1)]
    }
}
"#;

#[test]
fn pixar_usd_composes_transforms_as_we_do() {
    if !pxr_available() {
        return;
    }
    let path = temp_path("transformed.usda");
    std::fs::write(&path, TRANSFORMED).expect("temp file");
    let lines = run_python(WORLD_POINTS, &path);
    let _ = std::fs::remove_file(&path);
    let groom = read(
        TRANSFORMED.as_bytes(),
        Format::Usda,
        &ReadOptions::default(),
    )
    .expect("reads");
    assert!(groom.warnings.is_empty(), "{:?}", groom.warnings);
    let ours: Vec<Vec3> = groom
        .curves
        .curves
        .iter()
        .flat_map(|c| c.points_m.iter().copied())
        .collect();
    let theirs: Vec<Vec3> = lines
        .iter()
        .filter(|l| l.starts_with("p "))
        .map(|line| {
            let p = numbers(line);
            // Centimetres, Z up → metres, Y up, as our reader does.
            Vec3::new(0.01 * p[0] as f32, 0.01 * p[2] as f32, -0.01 * p[1] as f32)
        })
        .collect();
    assert_eq!(ours.len(), theirs.len());
    for (index, (a, b)) in ours.iter().zip(&theirs).enumerate() {
        assert!(
            a.abs_diff_eq(*b, TRANSFORM_TOLERANCE_M),
            "point {index}: ours {a}, pxr {b}"
        );
    }
}
