//! What the `.usda` reader takes from a layer: units, up axis,
//! interpolation, transforms, several prims, skipped prims, and warnings
//! for what it reads approximately.

use glam::Vec3;
use helixhair_formats::{Format, ReadOptions, StrandValue, UpAxis, read};

fn read_usda(text: &str) -> helixhair_formats::Imported {
    read(text.as_bytes(), Format::Usda, &ReadOptions::default()).expect("reads")
}

/// `f32` rounding after an `f64` transform: a few steps at a metre.
const TRANSFORM_TOLERANCE_M: f32 = 1e-6;

#[test]
fn centimetres_and_z_up_become_metres_and_y_up() {
    let text = r#"#usda 1.0
(
    doc = """A layer
    with "quotes" and lines"""
    metersPerUnit = 0.01
    upAxis = "Z"
)
def BasisCurves "hair" (
    kind = "component"
)
{
    uniform token type = "linear"
    int[] curveVertexCounts = [2]
    point3f[] points = [(0, 0, 0), (0, 0, 10)]
    float[] widths = [0.008] (interpolation = "constant")
}
"#;
    let groom = read_usda(text);
    assert_eq!(groom.curves.curves[0].points_m[1], Vec3::new(0.0, 0.1, 0.0));
    assert_eq!(
        groom.curves.curves[0].width_m,
        Some(StrandValue::PerStrand((0.008f64 * 0.01) as f32))
    );
    assert_eq!(groom.curves.metadata.file_up_axis, UpAxis::Z);
    assert_eq!(groom.curves.metadata.file_metres_per_unit, 0.01);
    assert!(groom.curves.metadata.declared_by_file);
}

#[test]
fn usd_fallback_unit_is_the_centimetre() {
    let text = "#usda 1.0\ndef BasisCurves \"h\" {\n  uniform token type = \"linear\"\n  int[] curveVertexCounts = [2]\n  point3f[] points = [(0,0,0), (0,100,0)]\n}\n";
    let imported = read_usda(text);
    assert_eq!(
        imported.curves.curves[0].points_m[1],
        Vec3::new(0.0, 1.0, 0.0)
    );
    // Not silently (issue #32, item 11: a 14 cm groom became 0.1 cm): the
    // reader says it assumed centimetres and how to say otherwise.
    assert!(
        imported
            .warnings
            .iter()
            .any(|w| w.contains("no metersPerUnit") && w.contains("centimetres")),
        "{:?}",
        imported.warnings
    );
    // A unit given by the caller is no assumption: no warning, the unit used.
    let options = ReadOptions {
        metres_per_unit: Some(1.0),
        ..ReadOptions::default()
    };
    let given = read(text.as_bytes(), Format::Usda, &options).expect("reads");
    assert_eq!(
        given.curves.curves[0].points_m[1],
        Vec3::new(0.0, 100.0, 0.0)
    );
    assert!(given.warnings.iter().all(|w| !w.contains("metersPerUnit")));
}

#[test]
fn transforms_of_the_prim_and_its_ancestors_apply() {
    // Known answer: the point (1, 0, 0) is scaled by 2, turned 90° about Z
    // (to (0, 2, 0)), moved by (0, 0, 1), then the parent adds (10, 0, 0).
    let text = r#"#usda 1.0
(
    metersPerUnit = 1
)
def Xform "root"
{
    double3 xformOp:translate = (10, 0, 0)
    uniform token[] xformOpOrder = ["xformOp:translate"]
    def BasisCurves "hair"
    {
        double3 xformOp:translate = (0, 0, 1)
        float3 xformOp:rotateXYZ = (0, 0, 90)
        float3 xformOp:scale = (2, 2, 2)
        uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:rotateXYZ", "xformOp:scale"]
        uniform token type = "linear"
        int[] curveVertexCounts = [2]
        point3f[] points = [(0, 0, 0), (1, 0, 0)]
    }
    def BasisCurves "reset"
    {
        matrix4d xformOp:transform = ( (1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0, 5, 0, 1) )
        uniform token[] xformOpOrder = ["!resetXformStack!", "xformOp:transform"]
        uniform token type = "linear"
        int[] curveVertexCounts = [2]
        point3f[] points = [(0, 0, 0), (1, 0, 0)]
    }
}
"#;
    let groom = read_usda(text);
    assert!(groom.warnings.is_empty(), "{:?}", groom.warnings);
    let hair = &groom.curves.curves[0].points_m;
    assert!(
        hair[0].abs_diff_eq(Vec3::new(10.0, 0.0, 1.0), TRANSFORM_TOLERANCE_M),
        "{}",
        hair[0]
    );
    assert!(
        hair[1].abs_diff_eq(Vec3::new(10.0, 2.0, 1.0), TRANSFORM_TOLERANCE_M),
        "{}",
        hair[1]
    );
    let reset = &groom.curves.curves[1].points_m;
    assert_eq!(reset[1], Vec3::new(1.0, 5.0, 0.0));
}

#[test]
fn uniform_colours_several_prims_and_skipped_prims() {
    let text = r#"#usda 1.0
(
    metersPerUnit = 1
)
def Xform "groom" (
    prepend apiSchemas = ["SomeAPI"]
    customData = { dictionary d = { string s = "}" } }
)
{
    rel material:binding = </Looks/Hair>
    variantSet "density" = {
        "low" { }
        "high" ( doc = "more" ) { }
    }
    def BasisCurves "a"
    {
        uniform token type = "linear"
        int[] curveVertexCounts = [2, 2]
        point3f[] points = [(0, 0, 0), (0, 1, 0), (1, 0, 0), (1, 1, 0)]
        color3f[] primvars:displayColor = [(1, 0, 0), (0, 1, 0)] (
            interpolation = "uniform"
        )
    }
    def BasisCurves "inactive" ( active = false )
    {
        uniform token type = "linear"
        int[] curveVertexCounts = [2]
        point3f[] points = [(9, 9, 9), (9, 8, 9)]
    }
    class BasisCurves "template"
    {
        int[] curveVertexCounts = [2]
        point3f[] points = [(7, 7, 7), (7, 8, 7)]
    }
    def BasisCurves "b"
    {
        uniform token type = "cubic"
        uniform token basis = "bspline"
        int[] curveVertexCounts = [4]
        point3f[] points = [(2, 0, 0), (2, 1, 0), (2, 2, 0), (2, 3, 0)]
        float[] widths = [1, 2, 3]
    }
}
"#;
    let groom = read_usda(text);
    println!("{:#?}", groom.warnings);
    assert_eq!(groom.curves.curves.len(), 3);
    assert_eq!(
        groom.curves.curves[1].colour,
        Some(StrandValue::PerStrand([0.0, 1.0, 0.0]))
    );
    assert_eq!(groom.curves.curves[2].points_m[3], Vec3::new(2.0, 3.0, 0.0));
    assert_eq!(
        groom.curves.curves[2].width_m, None,
        "3 widths fit neither 1 curve nor 4 points"
    );
    let warnings = groom.warnings.join("\n");
    assert!(warnings.contains("variant set"), "{warnings}");
    assert!(
        warnings.contains("cubic curves (basis bspline) are read as their control polylines"),
        "{warnings}"
    );
    assert!(warnings.contains("widths has 3 values"), "{warnings}");
}

#[test]
fn blocked_samples_are_skipped_and_time_codes_per_second_read() {
    let text = r#"#usda 1.0
(
    metersPerUnit = 1
    timeCodesPerSecond = 30
)
def BasisCurves "hair"
{
    uniform token type = "linear"
    int[] curveVertexCounts = [2]
    point3f[] points.timeSamples = {
        2: [(0, 0, 0), (0, 1, 0)],
        1: None,
        0: [(0, 0, 0), (1, 0, 0)],
    }
}
"#;
    let groom = read_usda(text);
    let animation = groom.animation.expect("frames");
    assert_eq!(animation.time_codes_per_second, 30.0);
    let times: Vec<f64> = animation.frames.iter().map(|f| f.time_code).collect();
    assert_eq!(times, [0.0, 2.0], "sorted, the blocked one skipped");
    assert_eq!(
        groom.curves.curves[0].points_m[1],
        Vec3::X,
        "the curves are the earliest sample"
    );
}
