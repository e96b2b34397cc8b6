//! The drawn hair: the simulated guides become the strands that are
//! drawn, the same way in the window, in `render` pictures and in exports
//! (one path, so they agree).
//!
//! [`DrawnLayout`] says which strands are drawn and which guides each
//! follows (made once per style); every frame [`drawn_hair`] rebuilds each
//! from its guides' strains ([`crate::hair::strain_blend`]: curls keep their
//! radius, pitch and handedness instead of averaging out), gives it its
//! shade of the group's colour, and drapes it over the head
//! ([`drape_over`]): a drawn strand grows from its own root with its
//! guides' bending, which can cut into the head between guides even when
//! the guides themselves rest on it.

use glam::{DVec3, Vec3};
use helixhair_physics::engine::Engine;
use helixhair_render::head_shell::HeadShell;
use helixhair_render::interpolate::resampled_shape;
use helixhair_render::{HairStrands, StrandBuffers};

use crate::hair::curl_variation::{clump_curl_onto, clump_onto, curl_period_m, curl_variation};
use crate::hair::layout::DrawnLayout;
use crate::hair::strain_blend::{strand_curve, to_f32};
use crate::head::groom::Groom;
/// Points of the blended guide shape [`follow_guides`] pulls towards.
const FOLLOW_POINTS: usize = 32;

/// One frame's guide curves in head coordinates, each built the first time
/// a drawn strand asks for it (clumping, following) and then shared by
/// every strand that follows the same guide.
struct GuideCurves<'a> {
    engine: &'a Engine,
    q: &'a [Vec<DVec3>],
    /// Each guide's curve, root first.
    curves: Vec<Option<Vec<Vec3>>>,
    /// Each guide's curve as [`FOLLOW_POINTS`] offsets from its root,
    /// evenly spaced by arc length.
    shapes: Vec<Option<Vec<Vec3>>>,
}

impl<'a> GuideCurves<'a> {
    fn new(engine: &'a Engine, q: &'a [Vec<DVec3>]) -> Self {
        Self {
            engine,
            q,
            curves: vec![None; q.len()],
            shapes: vec![None; q.len()],
        }
    }

    /// Guide `g`'s curve.
    fn curve(&mut self, g: usize) -> &[Vec3] {
        let (engine, q) = (self.engine, self.q);
        self.curves[g].get_or_insert_with(|| {
            let model = engine.strand_model(g);
            to_f32(&strand_curve(engine.root(g), &model.lengths_m, &q[g])).collect()
        })
    }

    /// Guide `g`'s resampled shape.
    fn shape(&mut self, g: usize) -> &[Vec3] {
        if self.shapes[g].is_none() {
            let shape = resampled_shape(self.curve(g), FOLLOW_POINTS);
            self.shapes[g] = Some(shape);
        }
        self.shapes[g].as_deref().unwrap_or_default()
    }
}

/// The guides' shapes (each as offsets from its own root, resampled by arc
/// length) blended with their weights, moved to start at `root`.
fn blended_shape(follow: &[(usize, f64)], root: Vec3, guides: &mut GuideCurves) -> Vec<Vec3> {
    let mut blended = vec![root; FOLLOW_POINTS];
    for &(g, weight) in follow {
        for (b, s) in blended.iter_mut().zip(guides.shape(g)) {
            *b += weight as f32 * *s;
        }
    }
    blended
}

/// Pulls a straight or wavy drawn strand (root first) onto `blended`, its
/// guides' blended shape from its own root, fully at the tip and not at all
/// at the root ([`clump_onto`] with amount 1). Such hair takes its shape
/// from gravity and the head: a strand rebuilt from its guides' strains
/// alone, from a root whose frame differs from theirs, can carry their
/// bend over the skull into a direction that points away from the head
/// (stray strands shooting off the back of the straight style); the
/// guides' positions carry where the hair actually lies. Clumped curls do
/// not need it: clumping gathers them onto their guide.
pub fn follow_guides(strand: &mut [Vec3], blended: &[Vec3]) {
    clump_onto(strand, blended, 1.0);
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
    let mut guides = GuideCurves::new(engine, &q);
    let mut strands = StrandBuffers::default();
    let mut curve: Vec<Vec3> = Vec::new();
    for (index, strand) in layout.strands.iter().enumerate() {
        curve.clear();
        let strains = strand.strains(&q);
        // A clumped curl gets its own phase and radius around its clump's
        // axis (see `curl_variation`).
        let curl = strand
            .clump
            .and_then(|(g, amount)| Some((g, amount, curl_period_m(&q[g])?)));
        curve.extend(to_f32(&strand_curve(
            &strand.root,
            &strand.lengths_m,
            &strains,
        )));
        match (strand.clump, curl) {
            (_, Some((g, amount, period_m))) => {
                let variation = curl_variation(index);
                clump_curl_onto(
                    &mut curve,
                    guides.curve(g),
                    amount as f32,
                    period_m,
                    variation,
                );
            }
            (Some((g, amount)), None) => clump_onto(&mut curve, guides.curve(g), amount as f32),
            (None, None) => {}
        }
        if !strand.follow.is_empty() {
            let blended = blended_shape(&strand.follow, curve[0], &mut guides);
            follow_guides(&mut curve, &blended);
        }
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
