//! The simulation behind the window: a [`HairSystem`] that follows the
//! style as it is edited, without a reset.
//!
//! The physics builds a strand's model (mass, stiffness, rest shape) once,
//! when the strand is added. A live edit therefore rebuilds the system from
//! the edited style and carries every strand's state over: strains q and
//! rates q̇ are copied when the element layout is unchanged, and resampled
//! by arc length ([`super::resample`]) when the element count or layout
//! changed, so the hair keeps its shape and motion and then relaxes towards
//! its new rest shape. A changed solver needs no rebuild at all
//! ([`HairSystem::set_method`] keeps shapes). Only a change in the number
//! of roots starts strands afresh, at their rest shape.
//!
//! Simulated time keeps running across rebuilds: the system's clock starts
//! at zero each time, so the head trajectory is read at the app's time
//! ([`LiveSim::now_secs`]) through a shifted view of it.

use std::sync::Arc;

use glam::DVec3;
use helixhair_physics::{
    Energies, GuardEvent, HairSystem, HeadTrajectory, Method, RigidMotion, StageTimes,
};
use helixhair_render::{HeadMesh, StrandBuffers};

use crate::groom::{grow_scalp_roots, needs_head};
use crate::style::Style;

use super::collision::HeadCollider;
use super::head_motion::FrameHead;
use super::resample::resample_per_element;

/// A hair system kept in step with an edited style.
#[derive(Clone, Debug)]
pub struct LiveSim {
    system: HairSystem,
    head: Arc<HeadMesh>,
    built: Style,
    built_grown: Style,
    method_override: Option<Method>,
    clock_offset_secs: f64,
    collider: Option<HeadCollider>,
}

/// A head trajectory read `offset_secs` later than asked.
struct Shifted<'a> {
    head: &'a FrameHead,
    offset_secs: f64,
}

impl HeadTrajectory for Shifted<'_> {
    fn motion_at(&self, t_secs: f64) -> RigidMotion {
        self.head.motion_at(t_secs + self.offset_secs)
    }
}

impl LiveSim {
    /// Builds the system of `style`, solved by `method_override` instead
    /// of the style's solver when given (the compare view's second run).
    /// Groups placed on the scalp (`scalp` in the style) grow their roots on
    /// `head`.
    pub fn new(
        style: &Style,
        head: Arc<HeadMesh>,
        method_override: Option<Method>,
    ) -> Result<Self, String> {
        let grown = grow(style, &head);
        let system = build(&grown, method_override)?;
        Ok(Self {
            system,
            head,
            built: style.clone(),
            built_grown: grown,
            method_override,
            clock_offset_secs: 0.0,
            collider: None,
        })
    }

    /// The hair system.
    pub fn system(&self) -> &HairSystem {
        &self.system
    }

    /// Simulated time since the app started, seconds.
    pub fn now_secs(&self) -> f64 {
        self.clock_offset_secs + self.system.time_secs()
    }

    /// The solver in use.
    pub fn method(&self) -> Method {
        self.system.settings().method
    }

    /// Sets the head collider (also kept across rebuilds).
    pub fn set_collider(&mut self, collider: Option<HeadCollider>) {
        if let Some(c) = &collider {
            c.attach(&mut self.system);
        }
        self.collider = collider;
    }

    /// Solves with `method` from now on (shapes are kept).
    pub fn set_method_override(&mut self, method: Option<Method>) {
        self.method_override = method;
        self.system
            .set_method(method.unwrap_or(self.built.sim.method));
    }

    /// Brings the system in line with `style` (which must be valid),
    /// keeping the strands' state; returns whether anything changed.
    pub fn sync(&mut self, style: &Style) -> Result<bool, String> {
        if *style == self.built {
            return Ok(false);
        }
        let mut only_method = self.built.clone();
        only_method.sim.method = style.sim.method;
        if only_method == *style {
            self.built = style.clone();
            self.system
                .set_method(self.method_override.unwrap_or(style.sim.method));
            return Ok(true);
        }
        let grown = grow(style, &self.head);
        let mut system = build(&grown, self.method_override)?;
        let old = &self.built_grown;
        let same_roots = grown.groups.len() == old.groups.len()
            && grown
                .groups
                .iter()
                .zip(&old.groups)
                .all(|(a, b)| a.roots.len() == b.roots.len());
        if same_roots {
            let mut index = 0;
            for (new_group, old_group) in grown.groups.iter().zip(&old.groups) {
                let old_lengths = old_group.params.element_lengths();
                let new_lengths = new_group.params.element_lengths();
                for _ in &new_group.roots {
                    let old = &self.system.strands()[index];
                    let (q, v) = if old_lengths == new_lengths {
                        (old.q().to_vec(), old.v().to_vec())
                    } else {
                        (
                            resample_per_element(old.q(), &old_lengths, &new_lengths),
                            resample_per_element(old.v(), &old_lengths, &new_lengths),
                        )
                    };
                    system.strands_mut()[index].set_state(&q, &v);
                    index += 1;
                }
            }
        }
        self.clock_offset_secs += self.system.time_secs();
        self.system = system;
        if let Some(c) = &self.collider {
            c.attach(&mut self.system);
        }
        self.built = style.clone();
        self.built_grown = grown;
        Ok(true)
    }

    /// Steps one frame with the head moving as `head` says (read at the
    /// app's time).
    pub fn step(&mut self, head: &FrameHead) {
        let shifted = Shifted {
            head,
            offset_secs: self.clock_offset_secs,
        };
        self.system.step_frame(&shifted);
    }

    /// Stage times of the last frame.
    pub fn stage_times(&self) -> StageTimes {
        self.system.last_stage_times()
    }

    /// What the guard did in the last frame.
    pub fn guard_events(&self) -> &[GuardEvent] {
        self.system.last_guard_events()
    }

    /// Energies of the current state.
    pub fn energies(&self) -> Energies {
        self.system.energies()
    }

    /// Element steps one frame takes: elements × substeps.
    pub fn element_steps_per_frame(&self) -> usize {
        self.system.element_count() * self.system.settings().substeps as usize
    }

    /// Every strand's boundary points in world coordinates, as `f32`
    /// polylines for the renderer.
    pub fn strand_buffers(&self) -> StrandBuffers {
        let mut out = StrandBuffers::default();
        for i in 0..self.system.strands().len() {
            out.push_strand(
                self.system
                    .boundary_points_world(i)
                    .into_iter()
                    .map(|p| p.as_vec3()),
            );
        }
        out
    }

    /// Tip positions, world coordinates (for the compare view).
    pub fn tips_m(&self) -> Vec<DVec3> {
        (0..self.system.strands().len())
            .filter_map(|i| self.system.boundary_points_world(i).last().copied())
            .collect()
    }
}

/// Root mean square and largest distance between matching tips of two
/// runs, metres.
pub fn tip_difference_m(a: &[DVec3], b: &[DVec3]) -> (f64, f64) {
    let n = a.len().min(b.len());
    if n == 0 {
        return (0.0, 0.0);
    }
    let d: Vec<f64> = a.iter().zip(b).map(|(p, q)| (*p - *q).length()).collect();
    let rms = (d.iter().map(|x| x * x).sum::<f64>() / n as f64).sqrt();
    (rms, d.iter().copied().fold(0.0, f64::max))
}

/// `style` with scalp placements grown into roots on `head` (the style
/// itself when it has none).
fn grow(style: &Style, head: &HeadMesh) -> Style {
    if needs_head(style) {
        grow_scalp_roots(style, head)
    } else {
        style.clone()
    }
}

fn build(style: &Style, method_override: Option<Method>) -> Result<HairSystem, String> {
    let mut settings = style.sim.clone();
    if let Some(method) = method_override {
        settings.method = method;
    }
    let mut system = HairSystem::new(settings).map_err(|e| format!("sim: {e}"))?;
    for (i, group) in style.groups.iter().enumerate() {
        system
            .add_group(&group.params, &group.root_poses())
            .map_err(|e| format!("groups[{i}].params: {e}"))?;
    }
    Ok(system)
}

#[cfg(test)]
mod tests {
    use helixhair_physics::NaturalShape;
    use helixhair_render::head_generate::default_head;

    use super::super::default_style::default_style;
    use super::super::head_motion::HeadDriver;
    use super::*;

    fn run(sim: &mut LiveSim, frames: usize) {
        let head = HeadDriver::default();
        for _ in 0..frames {
            sim.step(&head.frame(sim.now_secs()));
        }
    }

    #[test]
    fn edits_keep_the_state_and_the_clock() {
        let mut style = default_style(12);
        let mut sim = LiveSim::new(&style, Arc::new(default_head()), None).unwrap();
        run(&mut sim, 10);
        let before = sim.strand_buffers();
        let t = sim.now_secs();
        // A stiffness edit: same elements, so the shape carries over exactly.
        style.groups[0].params.youngs_modulus_pa *= 2.0;
        assert!(sim.sync(&style).unwrap());
        assert_eq!(sim.strand_buffers(), before);
        assert_eq!(sim.now_secs(), t);
        // Doubling the elements: the same curve, to round-off.
        style.groups[0].params.elements *= 2;
        sim.sync(&style).unwrap();
        let after = sim.strand_buffers();
        for s in 0..before.strand_count() {
            let (a, b) = (before.strand(s), after.strand(s));
            assert!((*a.last().unwrap() - *b.last().unwrap()).length() < 1e-5);
        }
        // A solver change needs no rebuild and keeps the shape.
        style.sim.method = Method::BlockDiagonal;
        sim.sync(&style).unwrap();
        assert_eq!(sim.method(), Method::BlockDiagonal);
        assert_eq!(sim.strand_buffers(), after);
        assert!(!sim.sync(&style).unwrap());
    }

    #[test]
    fn a_new_curl_is_reached_without_a_reset() {
        let mut style = default_style(4);
        style.groups[0].params.natural_shape = NaturalShape::Straight;
        let mut sim = LiveSim::new(&style, Arc::new(default_head()), None).unwrap();
        style.groups[0].params.natural_shape = NaturalShape::Helix {
            radius_m: 0.01,
            step_m: 0.02,
        };
        sim.sync(&style).unwrap();
        // Still straight right after the edit...
        let k0 = sim.system().strands()[0].q()[0];
        assert!(k0.length() < 1e-9);
        // ...and curling towards the helix's curvature R/(R² + c²) after.
        run(&mut sim, 120);
        let kappa = sim.system().strands()[0].q()[0].y;
        let c = 0.02 / std::f64::consts::TAU;
        let want = 0.01 / (0.01f64.powi(2) + c * c);
        assert!(kappa > 0.5 * want, "κ₁ = {kappa}, rest {want}");
    }

    #[test]
    fn scalp_placed_groups_grow_once_and_keep_their_state_on_edits() {
        let src = include_str!("../../../../assets/styles/groomed/curly.ron");
        let mut style = Style::from_ron(src, std::path::Path::new("curly.ron")).unwrap();
        let mut sim = LiveSim::new(&style, Arc::new(default_head()), None).unwrap();
        // The placements' counts, grown into strands (the file lists none).
        let placed: usize = style
            .groups
            .iter()
            .filter_map(|g| g.scalp.as_ref().map(|p| p.count as usize))
            .sum();
        assert_eq!(sim.system().strands().len(), placed);
        run(&mut sim, 5);
        let before = sim.strand_buffers();
        style.groups[0].params.air_drag *= 2.0;
        sim.sync(&style).unwrap();
        assert_eq!(sim.strand_buffers(), before);
    }

    #[test]
    fn tip_difference_is_rms_and_max() {
        let a = [DVec3::ZERO, DVec3::ZERO];
        let b = [DVec3::new(3.0, 0.0, 0.0), DVec3::new(0.0, 4.0, 0.0)];
        let (rms, max) = tip_difference_m(&a, &b);
        assert!((rms - (12.5f64).sqrt()).abs() < 1e-12 && max == 4.0);
    }
}
