//! Drawing the hair from the GPU engine's own buffers: the physics sweeps
//! every drawn strand's curve on the device from the strains there
//! ([`GpuEngine::write_curves`], each drawn strand's elements blending its
//! guides' elements as [`crate::hair::strain_blend`] does on the CPU), and
//! the renderer shapes them by their guides (clumping, curls of their own,
//! following: [`helixhair_render::strand_shape`]) and builds and draws the
//! ribbons there ([`DeviceStrands`]): no curve comes back to the CPU and
//! none goes up again. Each frame still reads the state (q, q̇) back once,
//! for the guard's measure, which runs on the CPU.
//!
//! An imported groom whose drawn strands are all its guides drawn as they
//! are (Sintel's) sweeps just the engine's strands. Any other layout
//! sweeps one curve per guide that strands clump onto or follow, then one
//! per drawn strand.
//!
//! The curves cut each element by its natural curl ([`MAX_TURN_RAD`]
//! between points, at most [`MAX_POINTS_PER_ELEMENT`]): a device buffer
//! keeps its size from frame to frame, where the CPU's curves cut by the
//! curl of the moment.

use std::ops::Range;

use glam::{DVec3, Mat4};
use helixhair_physics::engine::Engine;
use helixhair_physics::gpu::GpuEngine;
use helixhair_physics::gpu::curves::{BlendElement, CurveBlend};
use helixhair_render::HairStrands;
use helixhair_render::gpu::device_hair::DeviceStrands;
use helixhair_render::gpu::device_shape::{DeviceShaping, shape_table};
use helixhair_render::head_shell::HeadShell;
use helixhair_render::strand_shape::Shaping;

use crate::hair::drawn::{HEAD_GAP_M, root_width_m};
use crate::hair::layout::DrawnLayout;
use crate::hair::strain_blend::{MAX_POINTS_PER_ELEMENT, MAX_TURN_RAD};

/// What the device draws: the curves the physics sweeps, which of them
/// are drawn and how they are shaped, and the ribbons' colours and widths.
#[derive(Clone, Debug, PartialEq)]
pub struct DevicePlan {
    /// The curves, for [`GpuEngine::write_curves`].
    pub blend: CurveBlend,
    /// The curve each drawn strand is, in the layout's order.
    pub drawn: Vec<usize>,
    /// The curves of the guides strands clump onto or follow (the
    /// layout's `shape_guides`, in order).
    pub guides: Vec<usize>,
    /// How each drawn strand is shaped (the layout's); empty where none
    /// is.
    pub shapings: Vec<Shaping>,
    /// The engine's strand and element counts the curves read.
    engine_size: (usize, usize),
    /// The drawn strands' colours, their ribbon widths and, without
    /// points, what the picture's uniforms need of the hair.
    pub hair: HairStrands,
    /// The longest drawn strand, metres (how far the hair reaches from the
    /// head).
    pub reach_m: f32,
}

impl DevicePlan {
    /// The plan for `layout` on `engine`'s guides, or `None` where the
    /// layout has nothing to draw or a shaping the device cannot hold.
    pub fn new(layout: &DrawnLayout, engine: &Engine) -> Option<Self> {
        if layout.strands.is_empty() {
            return None;
        }
        let n = engine.strand_count();
        let mut first_element = Vec::with_capacity(n);
        let mut elements = 0usize;
        for g in 0..n {
            first_element.push(elements as u32);
            elements += engine.strand_model(g).elements();
        }
        let guide_lengths = |g: usize| engine.strand_model(g).lengths_m.as_slice();
        let guide_natural = |g: usize| engine.strand_model(g).natural.as_slice();
        let all_guides: Option<Vec<usize>> = layout
            .strands
            .iter()
            .map(|s| {
                let g = s.own_guide()?;
                let same = g < n
                    && *engine.root(g) == s.root
                    && same_lengths(guide_lengths(g), &s.lengths_m);
                same.then_some(g)
            })
            .collect();
        let (blend, drawn, guides, shapings) = match all_guides {
            Some(drawn) => {
                let roots: Vec<_> = (0..n).map(|g| *engine.root(g)).collect();
                let lengths: Vec<&[f64]> = (0..n).map(guide_lengths).collect();
                let sampling: Vec<u32> = (0..n)
                    .map(|g| natural_pieces(guide_lengths(g), guide_natural(g)))
                    .collect();
                let blend = CurveBlend::engine_strands(&roots, &lengths, &sampling);
                (blend, drawn, Vec::new(), Vec::new())
            }
            None => {
                let mut blend = CurveBlend::default();
                let mut guides = Vec::with_capacity(layout.shape_guides.len());
                for &g in &layout.shape_guides {
                    let samples = natural_pieces(guide_lengths(g), guide_natural(g));
                    let root = engine.root(g);
                    guides.push(blend.push_strand(
                        root,
                        guide_lengths(g),
                        samples,
                        first_element[g],
                    ));
                }
                // Every guide's natural strains, which a drawn strand
                // blends as it blends their strains (for how finely it
                // is cut).
                let naturals: Vec<Vec<DVec3>> = (0..n).map(|g| guide_natural(g).to_vec()).collect();
                let mut drawn = Vec::with_capacity(layout.strands.len());
                for strand in &layout.strands {
                    if strand.sources.iter().flatten().any(|s| {
                        s.guide >= n || s.element >= engine.strand_model(s.guide).elements()
                    }) {
                        return None;
                    }
                    let natural = strand.strains(&naturals);
                    let samples = natural_pieces(&strand.lengths_m, &natural);
                    let elements = strand
                        .lengths_m
                        .iter()
                        .zip(&strand.base)
                        .zip(&strand.sources)
                        .map(|((&length_m, &base), sources)| BlendElement {
                            length_m,
                            base,
                            sources: sources
                                .iter()
                                .map(|s| {
                                    (first_element[s.guide] + s.element as u32, s.weight as f32)
                                })
                                .collect::<Vec<_>>(),
                        });
                    drawn.push(blend.push(&strand.root, samples, elements));
                }
                (blend, drawn, guides, layout.shapings.clone())
            }
        };
        let reach_m = layout
            .strands
            .iter()
            .map(|s| s.lengths_m.iter().sum::<f64>() as f32)
            .fold(0.0, f32::max);
        let width = root_width_m(drawn.len());
        let plan = Self {
            blend,
            drawn,
            guides,
            shapings,
            engine_size: (n, elements),
            hair: HairStrands {
                strands: Default::default(),
                colours: layout.colours.clone(),
                root_width_m: width,
                tip_width_m: 0.35 * width,
            },
            reach_m,
        };
        // A shaping the device pass cannot hold draws on the CPU.
        let curve_count = plan.blend.len();
        shape_table(curve_count, &plan.guides, &plan.drawn, &plan.shapings).ok()?;
        Some(plan)
    }

    /// How many strands it draws.
    pub fn drawn_count(&self) -> usize {
        self.drawn.len()
    }

    /// The shaping of the drawn strands over `curves` with the curves'
    /// `strains`; `None` where nothing is shaped.
    fn shaping<'a>(
        &'a self,
        curves: &'a [Range<usize>],
        strains: &'a wgpu::Buffer,
    ) -> Option<DeviceShaping<'a>> {
        let shaped = !self.shapings.iter().all(Shaping::is_none);
        shaped.then_some(DeviceShaping {
            strains,
            curves,
            guides: &self.guides,
            strands: &self.drawn,
            shapings: &self.shapings,
        })
    }

    /// The curves of `device` (whose strands are the ones this plan was
    /// made for) as the renderer takes them, kept out of `shell`, posed by
    /// the head's `world_from_head`; the points stay on the device.
    /// `ranges` holds the drawn strands' ranges. `None` where the device
    /// holds other strands than the plan's (an edit not yet stepped) or
    /// could not write them: the CPU draws that frame.
    pub fn strands<'a>(
        &'a self,
        device: &'a mut GpuEngine,
        ranges: &'a mut Vec<Range<usize>>,
        shell: &'a HeadShell,
        world_from_head: Mat4,
    ) -> Option<DeviceStrands<'a>> {
        let (n, elements) = self.engine_size;
        if device.strand_count() != n || (n > 0 && device.elements_of(n - 1).end != elements) {
            return None;
        }
        let stage = device.write_curves(&self.blend).ok()?;
        ranges.clear();
        ranges.extend(self.drawn.iter().map(|&c| stage.ranges()[c].clone()));
        let shaping = self.shaping(stage.ranges(), stage.strains());
        Some(DeviceStrands {
            points: stage.points(),
            ranges,
            colours: &self.hair.colours,
            shell: Some((shell, HEAD_GAP_M)),
            world_from_head,
            reach_m: self.reach_m,
            shaping,
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

    /// The straight example's drawn strands blend and follow its guides:
    /// the device sweeps one curve per guide they follow, then one per
    /// drawn strand, and shapes them as the layout says.
    #[test]
    fn a_layout_of_blended_strands_sweeps_its_guides_then_its_strands() {
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
        let plan = DevicePlan::new(&layout, sim.engine()).expect("drawn from the device");
        let guides = layout.shape_guides.len();
        assert!(guides > 0 && guides <= sim.engine().strand_count());
        assert_eq!(plan.guides, (0..guides).collect::<Vec<_>>());
        assert_eq!(plan.drawn_count(), layout.strands.len());
        assert_eq!(plan.drawn[0], guides);
        assert_eq!(plan.blend.len(), guides + layout.strands.len());
        assert_eq!(plan.shapings, layout.shapings);
        // Straight hair follows its guides and does not clump.
        assert!(
            plan.shapings
                .iter()
                .all(|s| !s.follow.is_empty() && s.clump.is_none())
        );
    }

    /// An imported groom of curled guides only: every drawn strand is its
    /// guide, and the device sweeps the engine's strands as they are. One
    /// strand that is not a guide (its own shape bent as its guides bend)
    /// makes every drawn strand a curve of its own.
    #[test]
    fn a_groom_of_guides_only_sweeps_the_engines_strands() {
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
        assert_eq!(plan.drawn, [0, 1, 2]);
        // 0.02 m at 40.3 rad/m turns 0.81 rad: two pieces, 6 × 2 + 1 points.
        let counts: Vec<usize> = plan.blend.ranges().iter().map(|r| r.len()).collect();
        assert_eq!(counts, [13, 13, 13]);
        assert_eq!(plan.hair.colours.len(), 3);
        assert!(plan.guides.is_empty() && plan.shapings.iter().all(Shaping::is_none));

        let groom = groom_of([true, true, false]);
        let built = build_sim(&groom.grown, SimOverrides::default()).expect("builds");
        let layout = DrawnLayout::new(&groom, &built.engine, usize::MAX);
        let plan = DevicePlan::new(&layout, &built.engine).expect("drawn from the device");
        assert_eq!(plan.drawn_count(), 3);
        // Its natural curl is its guides' 40.3 rad/m plus its own imported
        // shape's difference from theirs (−20.2 rad/m): one piece.
        let counts: Vec<usize> = plan.blend.ranges().iter().map(|r| r.len()).collect();
        assert_eq!(counts, [13, 13, 7]);
    }

    /// Drawn from the device, the groomed curly example (ringlets clumped
    /// onto their guides with curls of their own, a fringe) draws the
    /// picture the CPU's drawn hair draws from the same engine, on the same
    /// device: the strains blended and swept on the device, shaped there,
    /// draped and built into ribbons there. The two differ only where the
    /// CPU cuts an element by its curl of the moment and the device by its
    /// natural curl, and in f32 round-off.
    #[test]
    fn the_device_draws_the_groomed_curls_the_cpu_draws() {
        use std::path::Path;

        use helixhair_physics::engine::EngineKind;
        use helixhair_render::{Light, OffscreenRenderer, OrbitCamera, RenderSettings, Scene};

        use crate::hair::drawn::drawn_hair;
        use crate::sim::build::SimOverrides;
        use crate::sim::grown::grown_sim;

        /// Mean difference per channel, 8-bit levels: the device path
        /// against the CPU's, measured on lavapipe at 0.98 levels (scattered
        /// pixels where sub-pixel ribbons cover other MSAA samples; the
        /// pictures are the same hair).
        const PICTURE_TOL_LEVELS: f64 = 1.5;

        let Some(ctx) = helixhair_gpu::context_or_skip("device-drawn groomed curls") else {
            return;
        };
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../assets/styles/groomed/curly.ron"
        );
        let overrides = SimOverrides {
            engine: Some(EngineKind::Gpu),
            ..SimOverrides::default()
        };
        let (groom, mut sim) = grown_sim(Path::new(path), None, overrides).expect("grows");
        sim.engine_mut()
            .gpu_side_mut()
            .expect("the GPU engine")
            .use_context(Some(ctx.clone()));
        sim.run(10).expect("finite");
        let layout = DrawnLayout::new(&groom, sim.engine(), 600);
        let cpu_hair = drawn_hair(&groom, &layout, sim.engine());
        let plan = DevicePlan::new(&layout, sim.engine()).expect("drawn from the device");
        assert!(
            plan.shapings.iter().any(|s| s.clump.is_some()),
            "curls clump"
        );
        let head = sim.engine().head();
        let (rotation, position) = (head.world_from_body.as_mat3(), head.position_m.as_vec3());
        let world_from_head = Mat4::from_translation(position) * Mat4::from_mat3(rotation);
        let posed_head = groom.head.posed(rotation, position);

        let mut settings = RenderSettings::new(160, 160);
        settings.shadows = false;
        let mut renderer = OffscreenRenderer::new(ctx, settings).expect("renderer");
        let camera = OrbitCamera {
            yaw_rad: 0.6,
            pitch_rad: 0.1,
            ..OrbitCamera::default()
        };
        let scene = |hair| Scene {
            hair,
            head: &posed_head,
            camera,
            light: Light::default(),
        };
        let from_cpu = renderer.render(&scene(&cpu_hair)).expect("cpu picture");
        let device = sim
            .engine_mut()
            .gpu_side_mut()
            .and_then(|side| side.device_mut())
            .expect("the device");
        let mut ranges = Vec::new();
        let strands = plan
            .strands(device, &mut ranges, &groom.shell, world_from_head)
            .expect("device strands");
        assert!(strands.shaping.is_some());
        let from_device = renderer
            .render_device(&scene(&plan.hair), &strands)
            .expect("device picture");
        let (mean_difference, differing) = from_device.difference(&from_cpu, 8);
        eprintln!(
            "groomed curls: device vs CPU picture {mean_difference:.2} levels on average, \
             {differing} pixels by more than 8"
        );
        assert!(
            mean_difference < PICTURE_TOL_LEVELS,
            "pictures differ by {mean_difference} levels"
        );
    }
}
