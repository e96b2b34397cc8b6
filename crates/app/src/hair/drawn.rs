//! The drawn hair: the simulated guides become the strands that are
//! drawn, the same way in the window, in `render` pictures and in exports
//! (one path, so they agree).
//!
//! [`DrawnLayout`] says which strands are drawn and which guides each
//! follows (made once per style); every frame [`drawn_hair`] rebuilds each
//! from its guides' strains ([`crate::hair::strain_blend`]: curls keep their
//! radius, pitch and handedness instead of averaging out), shapes it by its
//! guides (clumping and following,
//! [`helixhair_render::strand_shape`]), gives it its shade of the group's
//! colour, and drapes it over the head ([`drape_over`]): a drawn strand
//! grows from its own root with its guides' bending, which can cut into
//! the head between guides even when the guides themselves rest on it.

use glam::{DVec3, Vec3};
use helixhair_physics::engine::Engine;
use helixhair_render::head_shell::HeadShell;
use helixhair_render::strand_shape::{GuideShape, stage_guide_shapes, stage_shape};
use helixhair_render::{HairStrands, StrandBuffers};

use crate::hair::layout::DrawnLayout;
use crate::hair::strain_blend::{strand_curve, to_f32};
use crate::head::groom::Groom;

/// The mean magnitude of strains `q` over their elements, m⁻¹ (how curled
/// a strand is now; [`helixhair_render::strand_shape::curl_period_m`]).
pub fn mean_strain_per_m(q: &[DVec3]) -> f32 {
    (q.iter().map(|k| k.length()).sum::<f64>() / q.len().max(1) as f64) as f32
}

/// Keeps a strand (root first) out of the head ([`HeadShell::drape`] with
/// [`HEAD_GAP_M`]): the same rule the device's ribbon pass applies.
pub fn drape_over(points: &mut [Vec3], shell: &HeadShell) {
    shell.drape(points, HEAD_GAP_M);
}

/// Ribbon width at the root for `drawn` strands, metres: a real fibre is
/// about 80 µm and a head has about 100,000, so each drawn strand stands
/// for several; widening by the square root of that keeps a head looking
/// full without drawing spaghetti. Clamped to [80 µm, 400 µm].
pub fn root_width_m(drawn: usize) -> f32 {
    let ratio = 100_000.0 / drawn.max(1) as f32;
    (80e-6 * ratio.sqrt()).clamp(80e-6, 400e-6)
}

/// Gap kept between drawn hair and the head, metres.
pub const HEAD_GAP_M: f32 = 0.0015;

/// The drawn hair of `groom`, whose grown style `engine` simulates: every
/// strand of `layout` rebuilt from the guides' strains now, draped over
/// the head, in world coordinates (carried by the head's pose).
pub fn drawn_hair(groom: &Groom, layout: &DrawnLayout, engine: &Engine) -> HairStrands {
    let q: Vec<_> = (0..engine.strand_count()).map(|g| engine.q(g)).collect();
    let head = engine.head();
    let (rotation, position) = (head.world_from_body.as_mat3(), head.position_m.as_vec3());
    let guides: Vec<GuideShape> = layout
        .shape_guides
        .iter()
        .map(|&g| {
            let model = engine.strand_model(g);
            let curve = to_f32(&strand_curve(engine.root(g), &model.lengths_m, &q[g])).collect();
            stage_guide_shapes(curve, mean_strain_per_m(&q[g]))
        })
        .collect();
    let mut strands = StrandBuffers::default();
    let mut curve: Vec<Vec3> = Vec::new();
    for (strand, shaping) in layout.strands.iter().zip(&layout.shapings) {
        curve.clear();
        let strains = strand.strains(&q);
        curve.extend(to_f32(&strand_curve(
            &strand.root,
            &strand.lengths_m,
            &strains,
        )));
        stage_shape(&mut curve, shaping, &guides);
        drape_over(&mut curve, &groom.shell);
        strands.push_strand(curve.iter().map(|&p| rotation * p + position));
    }
    let width = root_width_m(strands.strand_count());
    HairStrands {
        strands,
        colours: layout.colours.clone(),
        root_width_m: width,
        tip_width_m: 0.35 * width,
    }
}

/// [`drawn_hair`] with every strand the style asks for: what `render` and
/// `export` draw.
pub fn drawn_hair_full(groom: &Groom, engine: &Engine) -> HairStrands {
    drawn_hair(groom, &DrawnLayout::new(groom, engine, usize::MAX), engine)
}
