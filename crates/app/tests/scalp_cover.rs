//! The groomed examples cover their scalp (issue 32, item 10): between the
//! fringe, combed forward, and the long hair, combed back, the regions
//! met edge to edge and the two combs opened a bare band of scalp there.
//!
//! Checked as a viewer sees it: from each scalp triangle's centre, looking
//! straight out (along the direction from the head's origin, the scalp
//! being near a sphere there), is there hair within the first 3 cm, closer
//! than 1.5 mm to that line? Every drawn strand is exported at rest
//! (`export --strands drawn`, `.obj`) and read back with the formats crate.
//! On the band where the regions meet (34° to 46° from the regions' axis)
//! the share of bare triangles was 14% (straight) and 9% (curly), against
//! under 1% on the rest of the scalp.

use std::path::PathBuf;
use std::process::Command;

use glam::DVec3;
use helixhair_formats::{Format, ReadOptions, read};
use helixhair_render::head_generate::default_head;

/// The axis of the examples' regions (`towards`), head coordinates.
const REGION_AXIS: DVec3 = DVec3::new(0.0, 0.35, 1.0);
/// Where the long hair's region starts, degrees from the axis.
const MEETING_DEG: f64 = 40.0;
/// Half the band's width around it, degrees.
const BAND_HALF_DEG: f64 = 6.0;
/// How far out from the scalp hair is looked for, metres.
const LOOK_OUT_M: f64 = 0.03;
/// How close to the line of sight a hair point counts as covering it,
/// metres.
const COVER_RADIUS_M: f64 = 0.0015;
/// Largest share of the band's triangles that may be bare.
const MOST_BARE: f64 = 0.02;

fn exported_points(style: &str, out: &PathBuf) -> Vec<DVec3> {
    let output = Command::new(env!("CARGO_BIN_EXE_helixhair"))
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .args(["export", "--style", style, "--strands", "drawn", "--out"])
        .arg(out)
        .output()
        .expect("helixhair starts");
    assert!(
        output.status.success(),
        "{style}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    let bytes = std::fs::read(out).expect("the export reads");
    let groom = read(&bytes, Format::Obj, &ReadOptions::default()).expect("parses");
    groom
        .curves
        .curves
        .iter()
        .flat_map(|c| c.points_m.iter().map(|p| p.as_dvec3()))
        .collect()
}

/// Whether any of `hair` lies within [`COVER_RADIUS_M`] of the line from
/// `centre` outwards along `out`, no farther out than [`LOOK_OUT_M`].
fn covered(centre: DVec3, out: DVec3, hair: &[DVec3]) -> bool {
    hair.iter().any(|p| {
        let r = *p - centre;
        let along = r.dot(out);
        along > 0.0 && along < LOOK_OUT_M && (r - along * out).length() < COVER_RADIUS_M
    })
}

#[test]
fn groomed_examples_leave_no_bare_band_where_fringe_and_long_hair_meet() {
    let head = default_head();
    let axis = REGION_AXIS.normalize();
    let band: Vec<DVec3> = head
        .scalp_triangles
        .iter()
        .map(|&t| {
            let corners = &head.mesh.indices[3 * t as usize..3 * t as usize + 3];
            corners
                .iter()
                .map(|&i| head.mesh.positions[i as usize].as_dvec3())
                .sum::<DVec3>()
                / 3.0
        })
        .filter(|c| {
            let deg = c.normalize().dot(axis).clamp(-1.0, 1.0).acos().to_degrees();
            (deg - MEETING_DEG).abs() < BAND_HALF_DEG
        })
        .collect();
    assert!(band.len() > 100, "{} triangles in the band", band.len());
    let dir = std::env::temp_dir().join(format!("helixhair-scalp-cover-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch folder");
    for name in ["straight", "curly"] {
        let hair = exported_points(
            &format!("assets/styles/groomed/{name}.ron"),
            &dir.join(format!("{name}.obj")),
        );
        let bare = band
            .iter()
            .filter(|c| !covered(**c, c.normalize(), &hair))
            .count();
        let share = bare as f64 / band.len() as f64;
        assert!(
            share < MOST_BARE,
            "{name}: {bare} of {} triangles where the regions meet are bare ({:.1}%)",
            band.len(),
            100.0 * share
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
