//! Tests of the drawn strands of imported grooms: the strands that are
//! not simulated (`--guides K`) are drawn, following their guides.

use std::path::Path;

use glam::DVec3;
use helixhair_render::head_generate::default_head;

use crate::hair::drawn::drawn_hair;
use crate::hair::layout::DrawnLayout;
use crate::hair::strain_blend::strand_curve;
use crate::head::groom::Groom;
use crate::sim::build::SimOverrides;
use crate::sim::headless::HeadlessSim;
use crate::style::Style;

/// Three straight imported strands of 4 elements of 2 cm, growing along
/// +x from roots 1 cm apart beside the head; the middle one is no guide.
const STYLE: &str = r#"(version: 1, name: "imported",
    sim: (gravity_m_per_s2: (0.0, 0.0, 0.0)),
    groups: [(name: "groom", imported: (source: "g.tfx", strands: [
        (root: (position_m: (0.3, 0.0, 0.00), direction: (1.0, 0.0, 0.0)), element_length_m: 0.02,
         strains: [(0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)],
         natural: [(0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)]),
        (root: (position_m: (0.3, 0.0, 0.01), direction: (1.0, 0.0, 0.0)), element_length_m: 0.02,
         strains: [(0.0, 5.0, 0.0), (0.0, 5.0, 0.0), (0.0, 5.0, 0.0), (0.0, 5.0, 0.0)],
         natural: [(0.0, 5.0, 0.0), (0.0, 5.0, 0.0), (0.0, 5.0, 0.0), (0.0, 5.0, 0.0)], guide: false),
        (root: (position_m: (0.3, 0.0, 0.02), direction: (1.0, 0.0, 0.0)), element_length_m: 0.02,
         strains: [(0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)],
         natural: [(0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)]),
    ]))])"#;

/// `--guides K` simulated K strands and drew only those: every imported
/// strand is drawn, the others as their own imported shape, bent as their
/// guides bend.
#[test]
fn imported_strands_that_are_not_guides_are_drawn_following_their_guides() {
    let style = Style::from_ron(STYLE, Path::new("i.ron")).unwrap_or_else(|e| panic!("{e}"));
    let groom = Groom::new(style, default_head());
    let mut sim = HeadlessSim::new(&groom.grown, SimOverrides::default()).expect("builds");
    assert_eq!(sim.engine().strand_count(), 2, "two guides simulated");
    let layout = DrawnLayout::new(&groom, sim.engine(), usize::MAX);
    let hair = drawn_hair(&groom, &layout, sim.engine());
    assert_eq!(hair.strands.strand_count(), 3, "all three drawn");
    // At the imported shape, the middle strand is its own arc (κ = 5 m⁻¹),
    // not the guides' straight lines.
    let own = strand_curve(
        &layout.strands[1].root,
        &[0.02; 4],
        &[DVec3::new(0.0, 5.0, 0.0); 4],
    );
    let drawn = hair.strands.strand(1);
    let tip = drawn[drawn.len() - 1].as_dvec3();
    assert!(
        tip.distance(own[own.len() - 1]) < 1e-6,
        "{tip} {}",
        own[own.len() - 1]
    );
    // Both guides bend by δκ₂ = 3 m⁻¹: the middle strand's strains are its
    // own plus the same change, (0, 5, 3) m⁻¹ on every element.
    let bent = vec![DVec3::new(0.0, 0.0, 3.0); 4];
    for g in 0..2 {
        sim.engine_mut().set_state(g, &bent, &[DVec3::ZERO; 4]);
    }
    let hair = drawn_hair(&groom, &layout, sim.engine());
    let want = strand_curve(
        &layout.strands[1].root,
        &[0.02; 4],
        &[DVec3::new(0.0, 5.0, 3.0); 4],
    );
    let drawn = hair.strands.strand(1);
    assert_eq!(drawn.len(), want.len());
    for (p, w) in drawn.iter().zip(&want) {
        assert!(p.as_dvec3().distance(*w) < 1e-6, "{p} not {w}");
    }
    // The guides are drawn as simulated.
    let guide_tip = hair.strands.strand(0).last().expect("points").as_dvec3();
    let simulated_tip = *sim
        .engine()
        .boundary_points_world(0)
        .last()
        .expect("points");
    assert!(guide_tip.distance(simulated_tip) < 1e-6);
}
