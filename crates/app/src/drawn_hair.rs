//! The drawn hair: the simulated guides' curves become the strands that
//! are drawn, group by group.
//!
//! A group without a `render` section draws its guides. Otherwise it draws
//! `render.count` strands interpolated from the guides
//! ([`helixhair_render::interpolate`]), with roots spread on its part of
//! the scalp (scalp groups) or scattered around the guides' roots (listed
//! roots). Each strand gets its own shade of the group's colour, and every
//! strand is draped over the head ([`drape_over`]): a drawn strand is its
//! guides' shapes moved to its own root, which can cut into the head
//! between guides even when the guides themselves rest on it (and the
//! `sim` command's guides do not collide at all).

use glam::Vec3;
use helixhair_render::head_shell::HeadShell;
use helixhair_render::interpolate::{Interpolation, InterpolationSpec, interpolate_strands};
use helixhair_render::rng::SplitMix64;
use helixhair_render::scalp_sampling::poisson_disk_on_scalp;
use helixhair_render::{HairStrands, HeadMesh, StrandBuffers};

use crate::groom::{Groom, placement_scalp};
use crate::style::StrandGroup;
use crate::style_groom::{RenderStrands, StrandInterpolation};

/// Seed offset of the drawn strands' roots, so they do not coincide with
/// the guides' (which use the placement's own seed).
const RENDER_SEED: u64 = 0x5EED_F00D_DA7A;

/// An sRGB component in [0, 1] as linear light.
fn srgb_to_linear(c: f64) -> f32 {
    let c = c.clamp(0.0, 1.0) as f32;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// `count` shades of `render`'s colour: brightness varies by up to
/// ±`colour_variation`, darker strands a little redder (more pheomelanin
/// shows), as in real hair.
fn strand_colours(render: &RenderStrands, count: usize, seed: u64) -> Vec<Vec3> {
    let base = Vec3::from_array(render.colour_srgb.to_array().map(srgb_to_linear));
    let amount = render.colour_variation as f32;
    let mut rng = SplitMix64::new(seed);
    (0..count)
        .map(|_| {
            let v = amount * (2.0 * rng.next_f32() - 1.0);
            let tint = Vec3::new(1.0 - 0.3 * v, 1.0, 1.0 + 0.3 * v);
            (base * (1.0 + v) * tint).clamp(Vec3::ZERO, Vec3::ONE)
        })
        .collect()
}

/// Roots scattered around the guides' roots (for groups that list roots):
/// each near a random guide, within half the distance to that guide's
/// nearest neighbour.
fn scattered_roots(guide_roots: &[Vec3], count: usize, seed: u64) -> Vec<Vec3> {
    let mut rng = SplitMix64::new(seed);
    let spacing = |i: usize| {
        guide_roots
            .iter()
            .enumerate()
            .filter(|&(j, _)| j != i)
            .map(|(_, q)| q.distance(guide_roots[i]))
            .fold(0.02f32, f32::min)
    };
    (0..count)
        .map(|_| {
            let i = rng.below(guide_roots.len());
            let offset = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) - 0.5;
            guide_roots[i] + offset * spacing(i)
        })
        .collect()
}

/// The strands drawn for one group, whose guides' curves are `guides`.
fn group_strands(
    group: &StrandGroup,
    head: &HeadMesh,
    guides: &StrandBuffers,
    seed: u64,
) -> (StrandBuffers, Vec<Vec3>) {
    let render = group.render.clone().unwrap_or_default();
    if render.count == 0 || guides.strand_count() == 0 {
        return (
            guides.clone(),
            strand_colours(&render, guides.strand_count(), seed),
        );
    }
    let count = render.count as usize;
    let roots: Vec<Vec3> = match &group.scalp {
        Some(placement) => poisson_disk_on_scalp(
            &placement_scalp(placement, head),
            count,
            placement.seed ^ RENDER_SEED,
        )
        .into_iter()
        .map(|s| s.position_m)
        .collect(),
        None => {
            let guide_roots: Vec<Vec3> = guides.iter().map(|g| g[0]).collect();
            scattered_roots(&guide_roots, count, seed)
        }
    };
    let spec = InterpolationSpec {
        method: match render.method {
            StrandInterpolation::Nearest => Interpolation::Nearest,
            StrandInterpolation::Blend3 => Interpolation::Blend3,
        },
        points_per_strand: guides.iter().map(<[Vec3]>::len).max().unwrap_or(2),
        length_variation: render.length_variation as f32,
        seed,
    };
    let strands = interpolate_strands(guides, &roots, &spec);
    let colours = strand_colours(&render, strands.strand_count(), seed);
    (strands, colours)
}

/// Keeps a strand (root first) out of the head, root to tip: each point
/// keeps its step from the previous one, and is pushed out to the shell
/// when that step would enter the head. A strand that the physics let fall
/// through the skull thus slides over the scalp the way it was heading,
/// instead of being projected onto whatever surface is nearest.
pub fn drape_over(points: &mut [Vec3], shell: &HeadShell) {
    let Some(&root) = points.first() else {
        return;
    };
    let (mut before, mut placed) = (root, root);
    for p in &mut points[1..] {
        let step = *p - before;
        before = *p;
        placed = shell.push_out(placed + step, HEAD_GAP_M);
        *p = placed;
    }
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

/// The drawn hair of `groom`, from `guides`: the curves of the strands
/// simulated for `groom.grown`, in group order.
pub fn drawn_hair(groom: &Groom, guides: &StrandBuffers) -> HairStrands {
    let mut strands = StrandBuffers::default();
    let mut colours = Vec::new();
    let mut first = 0;
    for (i, (group, grown)) in groom.groups().enumerate() {
        let end = (first + grown.simulated_count()).min(guides.strand_count());
        let mut own = StrandBuffers::default();
        for g in first..end {
            own.push_strand(guides.strand(g).iter().copied());
        }
        first = end;
        let (group_strands, group_colours) = group_strands(group, &groom.head, &own, i as u64 + 1);
        for s in group_strands.iter() {
            strands.push_strand(s.iter().copied());
        }
        colours.extend(group_colours);
    }
    for k in 0..strands.strand_count() {
        let range = strands.offsets[k] as usize..strands.offsets[k + 1] as usize;
        drape_over(&mut strands.points[range], &groom.shell);
    }
    let width = root_width_m(strands.strand_count());
    HairStrands {
        strands,
        colours,
        root_width_m: width,
        tip_width_m: 0.35 * width,
    }
}
