//! Drawing the hair from the GPU engine's own buffers: where every drawn
//! strand is a simulated guide drawn as it is (an imported groom whose
//! strands are all guides), the physics writes the guides' curves on the
//! device ([`GpuEngine::write_curves`]) and the renderer builds and draws
//! the ribbons there ([`DeviceStrands`]): no curve comes back to the CPU
//! and none goes up again. Each frame still reads the state (q, q̇) back
//! once, for the guard's measure, which runs on the CPU.
//!
//! Other layouts (drawn strands blended between guides, clumped or
//! following them: every procedural group) are rebuilt on the CPU from
//! the guides' strains ([`crate::hair::drawn::drawn_hair`]), on any engine.
//!
//! The curves cut each element of a guide by its natural curl
//! ([`MAX_TURN_RAD`] between points, at most [`MAX_POINTS_PER_ELEMENT`]):
//! a device buffer keeps its size from frame to frame, where the CPU's
//! curves cut by the curl of the moment.

use glam::Mat4;
use helixhair_physics::engine::Engine;
use helixhair_physics::gpu::GpuEngine;
use helixhair_render::HairStrands;
use helixhair_render::gpu::device_hair::DeviceStrands;
use helixhair_render::head_shell::HeadShell;

use crate::hair::drawn::{HEAD_GAP_M, root_width_m};
use crate::hair::layout::DrawnLayout;
use crate::hair::strain_blend::{MAX_POINTS_PER_ELEMENT, MAX_TURN_RAD};

/// What the device draws: which guide each drawn strand is, its colour,
/// how finely each guide's curve is cut, and the ribbons' widths.
#[derive(Clone, Debug, PartialEq)]
pub struct DevicePlan {
    /// The guide (simulation index) each drawn strand is.
    pub guides: Vec<usize>,
    /// Each guide's pieces per element, for
    /// [`GpuEngine::write_curves`].
    pub sampling: Vec<u32>,
    /// The drawn strands' colours, their ribbon widths and, without
    /// points, what the picture's uniforms need of the hair.
    pub hair: HairStrands,
    /// The longest guide, metres (how far the hair reaches from the head).
    pub reach_m: f32,
}

impl DevicePlan {
    /// The plan for `layout` on `engine`'s guides, or `None` where a drawn
    /// strand is not a guide drawn as it is (module docs).
    pub fn new(layout: &DrawnLayout, engine: &Engine) -> Option<Self> {
        let guides: Vec<usize> = layout
            .strands
            .iter()
            .map(|s| {
                let g = s.own_guide()?;
                let same = g < engine.strand_count()
                    && *engine.root(g) == s.root
                    && same_lengths(&engine.strand_model(g).lengths_m, &s.lengths_m);
                same.then_some(g)
            })
            .collect::<Option<_>>()?;
        if guides.is_empty() {
            return None;
        }
        let sampling = (0..engine.strand_count())
            .map(|g| {
                natural_pieces(
                    &engine.strand_model(g).lengths_m,
                    &engine.strand_model(g).natural,
                )
            })
            .collect();
        let reach_m = (0..engine.strand_count())
            .map(|g| engine.strand_model(g).lengths_m.iter().sum::<f64>() as f32)
            .fold(0.0, f32::max);
        let width = root_width_m(guides.len());
        Some(Self {
            guides,
            sampling,
            hair: HairStrands {
                strands: Default::default(),
                colours: layout.colours.clone(),
                root_width_m: width,
                tip_width_m: 0.35 * width,
            },
            reach_m,
        })
    }

    /// The curves of `device` (whose strands are this plan's guides) as
    /// the renderer takes them, kept out of `shell`, posed by the head's
    /// `world_from_head`; the points stay on the device. `None` where the
    /// device holds other strands than the plan's guides (an edit not yet
    /// stepped) or could not write them: the CPU draws that frame.
    pub fn strands<'a>(
        &'a self,
        device: &'a mut GpuEngine,
        ranges: &'a mut Vec<std::ops::Range<usize>>,
        shell: &'a HeadShell,
        world_from_head: Mat4,
    ) -> Option<DeviceStrands<'a>> {
        if device.strand_count() != self.sampling.len() {
            return None;
        }
        let stage = device.write_curves(&self.sampling).ok()?;
        ranges.clear();
        ranges.extend(self.guides.iter().map(|&g| stage.ranges()[g].clone()));
        Some(DeviceStrands {
            points: stage.points(),
            ranges,
            colours: &self.hair.colours,
            shell: Some((shell, HEAD_GAP_M)),
            world_from_head,
            reach_m: self.reach_m,
        })
    }
}

/// Whether two strands' element lengths agree to round-off (an imported
/// strand's model derives its lengths from the groom's by arithmetic that
/// can land one unit in the last place away).
fn same_lengths(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(x, y)| (x - y).abs() <= 1e-12 * x.abs().max(y.abs()))
}

/// Pieces per element for a strand of `lengths_m` with natural strains
/// `natural`: enough that its most curled element turns at most
/// [`MAX_TURN_RAD`] between points, as the CPU's curves are cut.
pub fn natural_pieces(lengths_m: &[f64], natural: &[glam::DVec3]) -> u32 {
    lengths_m
        .iter()
        .zip(natural)
        .map(|(&l, k)| {
            ((l * k.length() / MAX_TURN_RAD).ceil() as usize).clamp(1, MAX_POINTS_PER_ELEMENT)
        })
        .max()
        .unwrap_or(1) as u32
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;

    #[test]
    fn straight_elements_take_one_piece_and_curls_as_many_as_they_turn() {
        assert_eq!(natural_pieces(&[0.02; 3], &[DVec3::ZERO; 3]), 1);
        // 0.02 m at 50 rad/m turns 1 rad: three pieces of 0.33 rad.
        let curled = [DVec3::ZERO, DVec3::new(0.0, 50.0, 0.0)];
        assert_eq!(natural_pieces(&[0.02; 2], &curled), 3);
        assert_eq!(
            natural_pieces(&[1.0], &[DVec3::new(0.0, 1e3, 0.0)]),
            MAX_POINTS_PER_ELEMENT as u32
        );
    }

    /// Sintel's groom's strands are all guides: the window draws it from
    /// the device. The straight example's drawn strands blend guides: it
    /// is drawn on the CPU.
    #[test]
    fn only_layouts_of_guides_drawn_as_they_are_draw_from_the_device() {
        use std::path::Path;

        use crate::sim::build::SimOverrides;
        use crate::sim::grown::grown_sim;

        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../assets/styles/straight.ron"
        );
        let (groom, sim) =
            grown_sim(Path::new(path), None, SimOverrides::default()).expect("grows");
        let layout = DrawnLayout::new(&groom, sim.engine(), usize::MAX);
        assert!(DevicePlan::new(&layout, sim.engine()).is_none());
    }

    /// An imported groom of curled guides only: every drawn strand is its
    /// guide; one strand that is not a guide sends the groom to the CPU.
    #[test]
    fn a_groom_of_guides_only_draws_from_the_device() {
        use helixhair_render::head_generate::default_head;

        use crate::head::groom::Groom;
        use crate::sim::build::{SimOverrides, build_sim};
        use crate::style::imported::{ImportedStrand, ImportedStrands};
        use crate::window::state::default_style::default_style;

        let groom_of = |guides: [bool; 3]| {
            let mut style = default_style(1);
            let root = style.groups[0].roots[0];
            style.groups[0].roots.clear();
            let curl = DVec3::new(0.0, 40.0, 5.0);
            style.groups[0].imported = Some(ImportedStrands {
                source: "g.obj".into(),
                head: None,
                collider: None,
                strands: guides
                    .iter()
                    .map(|&guide| ImportedStrand {
                        root,
                        element_length_m: 0.02,
                        // A strand that is not a guide has its own shape
                        // (what it adds to its guides' is drawn on the CPU).
                        strains: vec![if guide { curl } else { 0.5 * curl }; 6],
                        natural: vec![curl; 6],
                        guide,
                        stiffness_scale: 1.0,
                    })
                    .collect(),
            });
            Groom::new(style, default_head())
        };
        let groom = groom_of([true; 3]);
        let built = build_sim(&groom.grown, SimOverrides::default()).expect("builds");
        let layout = DrawnLayout::new(&groom, &built.engine, usize::MAX);
        let plan = DevicePlan::new(&layout, &built.engine).expect("guides only");
        assert_eq!(plan.guides, [0, 1, 2]);
        // 0.02 m at 40.3 rad/m turns 0.81 rad: two pieces.
        assert_eq!(plan.sampling, [2, 2, 2]);
        assert_eq!(plan.hair.colours.len(), 3);

        let groom = groom_of([true, true, false]);
        let built = build_sim(&groom.grown, SimOverrides::default()).expect("builds");
        let layout = DrawnLayout::new(&groom, &built.engine, usize::MAX);
        assert!(DevicePlan::new(&layout, &built.engine).is_none());
    }
}
