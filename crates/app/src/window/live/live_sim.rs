//! The simulation behind the window: an [`Engine`] (the f64 reference
//! `HairSystem` or the f32 batch path, [`helixhair_physics::engine`]) that follows the
//! style as it is edited, without a reset.
//!
//! The physics builds a strand's model (mass, stiffness, rest shape) once,
//! when the strand is added. A live edit therefore rebuilds the engine from
//! the edited style and carries every strand's state over: strains q and
//! rates q̇ are copied when the element layout is unchanged, and resampled
//! by arc length ([`crate::sim::carry`]) when the element count or layout
//! changed, so the hair keeps its shape and motion and then relaxes towards
//! its new rest shape. The same carrying-over moves the hair from one
//! engine to the other when the style's `engine` changes (the batch engine
//! rounds the state to f32). A changed solver on the reference engine needs
//! no rebuild at all (`HairSystem::set_method` keeps shapes); the batch
//! engine has one solver for all strands and is rebuilt. Only a change in
//! the number of roots starts strands afresh, at their rest shape.
//!
//! The compare view runs both sides on the reference engine, whatever the
//! style says ([`LiveSim::set_overrides`]): it compares solvers the batch
//! engine does not have.
//!
//! Simulated time keeps running across rebuilds: the engine's clock starts
//! at zero each time, so the head trajectory is read at the app's time
//! ([`LiveSim::now_secs`]) through a shifted view of it.

use std::sync::Arc;

use glam::DVec3;
use helixhair_physics::engine::{Engine, EngineKind};
use helixhair_physics::gpu::GpuContext;
use helixhair_physics::{Energies, GuardEvent, HeadTrajectory, Method, RigidMotion, StageTimes};
use helixhair_render::{HeadMesh, StrandBuffers};

use crate::head::groom::{grow_scalp_roots, needs_head};
use crate::style::Style;

use super::collision::HeadCollider;
use super::head_motion::FrameHead;
use crate::sim::build::{SimError, SimOverrides, build_sim};
use crate::sim::carry::{Carry, carry_state};
use crate::sim::settle::{settle_on_head, settles_on_head};
use crate::sim::strands::StyleStrand;

/// A hair system kept in step with an edited style.
#[derive(Clone, Debug)]
pub struct LiveSim {
    engine: Engine,
    head: Arc<HeadMesh>,
    built: Style,
    built_grown: Style,
    engine_override: Option<EngineKind>,
    method_override: Option<Method>,
    clock_offset_secs: f64,
    collider: Option<HeadCollider>,
    /// The engine's strands (group, number, base parameters of each).
    strands: Vec<StyleStrand>,
    /// The device the GPU engine steps on (the window's), handed to every
    /// engine this run makes before its first frame.
    gpu_context: Option<Box<GpuContext>>,
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
    /// Builds the engine of `style` (its `engine`, or `engine_override`),
    /// solved by `method_override` instead of the style's solver when
    /// given (the compare view's runs). Groups placed on the scalp
    /// (`scalp` in the style) grow their roots on `head`.
    pub fn new(
        style: &Style,
        head: Arc<HeadMesh>,
        engine_override: Option<EngineKind>,
        method_override: Option<Method>,
    ) -> Result<Self, SimError> {
        let grown = grow(style, &head);
        let (engine, strands) = build(&grown, engine_override, method_override)?;
        Ok(Self {
            engine,
            strands,
            head,
            built: style.clone(),
            built_grown: grown,
            engine_override,
            method_override,
            clock_offset_secs: 0.0,
            collider: None,
            gpu_context: None,
        })
    }

    /// The engine and its hair system.
    pub fn engine(&self) -> &Engine {
        &self.engine
    }

    /// Which engine runs.
    pub fn kind(&self) -> EngineKind {
        self.engine.kind()
    }

    /// Simulated time since the app started, seconds.
    pub fn now_secs(&self) -> f64 {
        self.clock_offset_secs + self.engine.time_secs()
    }

    /// The solver in use.
    pub fn method(&self) -> Method {
        self.engine.settings().method
    }

    /// Sets the head collider (also kept across rebuilds); hair grown on
    /// the scalp then settles on it (`LiveSim::settle_grown_hair`).
    pub fn set_collider(&mut self, collider: Option<HeadCollider>) {
        if let Some(c) = &collider {
            c.attach(&mut self.engine);
        }
        self.collider = collider;
        self.settle_grown_hair();
    }

    /// Starts the hair settled on the head, not in its natural shape
    /// through it or above it ([`settle_on_head`]); nothing for an
    /// imported groom ([`settles_on_head`]) or without a collider.
    fn settle_grown_hair(&mut self) {
        if self.collider.is_some() && settles_on_head(&self.built) {
            settle_on_head(&mut self.engine);
        }
    }

    /// Runs on `engine` with `method` from now on instead of the style's
    /// (both `None`: the style's own), keeping every strand's shape and
    /// motion. Fails, changing nothing, if the engine cannot run the
    /// solver.
    pub fn set_overrides(
        &mut self,
        engine: Option<EngineKind>,
        method: Option<Method>,
    ) -> Result<(), SimError> {
        let kind = engine.unwrap_or(self.built.engine);
        let solver = method.unwrap_or(self.built.sim.method);
        if !kind.runs(solver) {
            return Err(SimError::Conflict {
                options: format!("the {} engine", kind.label()),
                message: format!("it cannot run the `{}` solver", solver.label()),
            });
        }
        let (old_engine, old_method) = (self.engine_override, self.method_override);
        self.engine_override = engine;
        self.method_override = method;
        if let (EngineKind::Reference, Engine::Reference(system)) = (kind, &mut self.engine) {
            system.set_method(solver);
            return Ok(());
        }
        let style = self.built.clone();
        self.rebuild(&style).inspect_err(|_| {
            self.engine_override = old_engine;
            self.method_override = old_method;
        })
    }

    /// Brings the engine in line with `style` (which must be valid),
    /// keeping the strands' state; returns whether anything changed.
    pub fn sync(&mut self, style: &Style) -> Result<bool, SimError> {
        if *style == self.built {
            return Ok(false);
        }
        let mut only_method = self.built.clone();
        only_method.sim.method = style.sim.method;
        if only_method == *style
            && let Engine::Reference(system) = &mut self.engine
        {
            self.built = style.clone();
            system.set_method(self.method_override.unwrap_or(style.sim.method));
            return Ok(true);
        }
        self.rebuild(style)?;
        Ok(true)
    }

    /// A new engine for `style`, every strand's state carried over from the
    /// current one when the root counts match (an edit of values, not of
    /// counts), stretched onto new elements where lengths changed.
    fn rebuild(&mut self, style: &Style) -> Result<(), SimError> {
        let grown = grow(style, &self.head);
        let (engine, strands) = build(&grown, self.engine_override, self.method_override)?;
        let counts = |s: &Style| {
            s.groups
                .iter()
                .map(|g| g.simulated_count())
                .collect::<Vec<_>>()
        };
        let carry = (counts(&grown) == counts(&self.built_grown)).then_some(Carry::Stretch);
        self.replace_engine(engine, strands, carry, &[]);
        self.built = style.clone();
        self.built_grown = grown;
        if carry.is_none() {
            // New strands (a new count): they start afresh, settled.
            self.settle_grown_hair();
        }
        Ok(())
    }

    /// A new engine from the grown style as the brush edited it
    /// ([`LiveSim::grown_style_mut`]), every strand's state carried by arc
    /// length (a cut strand keeps the rest of its shape), the strands in
    /// `at_rest` still; the style as written takes the same edits
    /// ([`LiveSim::built_style`]).
    pub fn rebuild_from_grown(&mut self, at_rest: &[usize]) -> Result<(), SimError> {
        let (engine, strands) = build(
            &self.built_grown,
            self.engine_override,
            self.method_override,
        )?;
        self.replace_engine(engine, strands, Some(Carry::ArcLength), at_rest);
        for (written, grown) in self.built.groups.iter_mut().zip(&self.built_grown.groups) {
            written.edits = grown.edits.clone();
        }
        Ok(())
    }

    /// Runs on `engine` from now on, the clock running on, the state
    /// carried as `carry` says (`None`: strands start afresh).
    fn replace_engine(
        &mut self,
        mut engine: Engine,
        strands: Vec<StyleStrand>,
        carry: Option<Carry>,
        at_rest: &[usize],
    ) {
        if let Some(how) = carry {
            carry_state(&self.engine, &mut engine, how, at_rest);
        }
        self.clock_offset_secs += self.engine.time_secs();
        self.engine = engine;
        self.strands = strands;
        if let Some(c) = &self.collider {
            c.attach(&mut self.engine);
        }
        self.hand_device();
    }

    /// Steps the GPU engine on `context` (the window's device, so that
    /// the hair can be drawn from the engine's buffers), this engine and
    /// every one the run makes later. Nothing happens where it already
    /// does (the window hands it every frame).
    pub fn set_gpu_context(&mut self, context: &GpuContext) {
        if self
            .gpu_context
            .as_deref()
            .is_some_and(|held| held.same_device(context))
        {
            return;
        }
        self.gpu_context = Some(Box::new(context.clone()));
        self.hand_device();
    }

    fn hand_device(&mut self) {
        if let Some(side) = self.engine.gpu_side_mut() {
            side.use_context(self.gpu_context.as_deref().cloned());
        }
    }

    /// The engine, to set forces and states (the brush).
    pub fn engine_mut(&mut self) -> &mut Engine {
        &mut self.engine
    }

    /// The grown style, for the brush's per-strand edits; apply them with
    /// [`LiveSim::rebuild_from_grown`].
    pub fn grown_style_mut(&mut self) -> &mut Style {
        &mut self.built_grown
    }

    /// The style as written the engine was built from (with the brush's
    /// edits once rebuilt).
    pub fn built_style(&self) -> &Style {
        &self.built
    }

    /// The engine's strands: group, number and base parameters of each.
    pub fn strands(&self) -> &[StyleStrand] {
        &self.strands
    }

    /// Steps one frame with the head moving as `head` says (read at the
    /// app's time).
    pub fn step(&mut self, head: &FrameHead) {
        let shifted = Shifted {
            head,
            offset_secs: self.clock_offset_secs,
        };
        self.engine.step_frame(&shifted);
    }

    /// Stage times of the last frame; `None` on the batch engine, whose
    /// stages are fused into sweeps and not timed apart.
    pub fn stage_times(&self) -> Option<StageTimes> {
        self.engine.reference().map(|s| s.last_stage_times())
    }

    /// What the guard did in the last frame, on either engine.
    pub fn guard_events(&self) -> &[GuardEvent] {
        self.engine.last_guard_events()
    }

    /// Energies of the current state; `None` on the batch engine (they
    /// would cost about a reference frame each displayed frame).
    pub fn energies(&self) -> Option<Energies> {
        self.engine.reference().map(|s| s.energies())
    }

    /// Element steps one frame takes: elements × substeps.
    pub fn element_steps_per_frame(&self) -> usize {
        self.engine.element_count() * self.engine.settings().substeps as usize
    }

    /// Every strand's boundary points in world coordinates, as `f32`
    /// polylines for the renderer.
    pub fn strand_buffers(&self) -> StrandBuffers {
        let mut out = StrandBuffers::default();
        for i in 0..self.engine.strand_count() {
            out.push_strand(
                self.engine
                    .boundary_points_world(i)
                    .into_iter()
                    .map(|p| p.as_vec3()),
            );
        }
        out
    }

    /// The style the engine was built from, scalp placements grown into
    /// roots (strand i of the engine is the i-th root or imported guide).
    pub fn grown_style(&self) -> &Style {
        &self.built_grown
    }

    /// The head collider, if set.
    pub fn collider(&self) -> Option<&HeadCollider> {
        self.collider.as_ref()
    }

    /// Stops every strand where it is: shapes kept, rates set to zero.
    pub fn stop(&mut self) {
        for i in 0..self.engine.strand_count() {
            let q = self.engine.q(i);
            let rest = vec![DVec3::ZERO; q.len()];
            self.engine.set_state(i, &q, &rest);
        }
    }

    /// Tip positions, world coordinates (for the compare view).
    pub fn tips_m(&self) -> Vec<DVec3> {
        (0..self.engine.strand_count())
            .filter_map(|i| self.engine.boundary_points_world(i).last().copied())
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

/// The engine of the grown `style` through the one builder
/// ([`build_sim`]), with the window's engine and solver overrides. The
/// window runs the solver and element counts the style names: it switches
/// solvers in place ([`LiveSim::sync`], the compare view), which a
/// per-strand automatic choice would not survive, so an accuracy target is
/// left to `sim`, `render` and `export`.
fn build(
    style: &Style,
    engine: Option<EngineKind>,
    method: Option<Method>,
) -> Result<(Engine, Vec<StyleStrand>), SimError> {
    let without_target;
    let style = if style.accuracy_target.is_some() {
        without_target = Style {
            accuracy_target: None,
            ..style.clone()
        };
        &without_target
    } else {
        style
    };
    let overrides = SimOverrides {
        engine,
        method,
        ..SimOverrides::default()
    };
    let built = build_sim(style, overrides)?;
    Ok((built.engine, built.strands))
}

#[cfg(test)]
mod tests {
    use helixhair_physics::NaturalShape;
    use helixhair_render::head_generate::default_head;

    use super::super::head_motion::HeadDriver;
    use super::*;
    use crate::window::state::default_style::default_style;

    fn run(sim: &mut LiveSim, frames: usize) {
        let head = HeadDriver::default();
        for _ in 0..frames {
            sim.step(&head.frame(sim.now_secs()));
        }
    }

    #[test]
    fn edits_keep_the_state_and_the_clock() {
        let mut style = default_style(12);
        let mut sim = LiveSim::new(&style, Arc::new(default_head()), None, None).unwrap();
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
        let mut sim = LiveSim::new(&style, Arc::new(default_head()), None, None).unwrap();
        style.groups[0].params.natural_shape = NaturalShape::Helix {
            radius_m: 0.01,
            step_m: 0.02,
        };
        sim.sync(&style).unwrap();
        // Still straight right after the edit...
        let k0 = sim.engine().q(0)[0];
        assert!(k0.length() < 1e-9);
        // ...and curling towards the helix's curvature R/(R² + c²) after.
        run(&mut sim, 120);
        let kappa = sim.engine().q(0)[0].y;
        let c = 0.02 / std::f64::consts::TAU;
        let want = 0.01 / (0.01f64.powi(2) + c * c);
        assert!(kappa > 0.5 * want, "κ₁ = {kappa}, rest {want}");
    }

    #[test]
    fn scalp_placed_groups_grow_once_and_keep_their_state_on_edits() {
        let src = include_str!("../../../../../assets/styles/groomed/curly.ron");
        let mut style = Style::from_ron(src, std::path::Path::new("curly.ron")).unwrap();
        let mut sim = LiveSim::new(&style, Arc::new(default_head()), None, None).unwrap();
        // The placements' counts, grown into strands (the file lists none).
        let placed: usize = style
            .groups
            .iter()
            .filter_map(|g| g.scalp.as_ref().map(|p| p.count as usize))
            .sum();
        assert_eq!(sim.engine().strand_count(), placed);
        run(&mut sim, 5);
        let before = sim.strand_buffers();
        style.groups[0].params.air_drag *= 2.0;
        sim.sync(&style).unwrap();
        assert_eq!(sim.strand_buffers(), before);
    }

    /// Moving the hair between engines rounds its state to f32 and back:
    /// tips move by at most this, metres (f32 round-off on 20 cm strands is
    /// about 1e-8 m per element; a reset would move them centimetres).
    const ENGINE_SWITCH_TOL_M: f64 = 1e-6;

    #[test]
    fn switching_engines_keeps_the_shape_and_the_compare_view_runs_the_reference() {
        let mut style = default_style(10);
        let mut sim = LiveSim::new(&style, Arc::new(default_head()), None, None).unwrap();
        run(&mut sim, 10);
        let before = sim.tips_m();
        let t = sim.now_secs();
        style.engine = EngineKind::Batch;
        assert!(sim.sync(&style).unwrap());
        assert_eq!(sim.kind(), EngineKind::Batch);
        assert_eq!(sim.now_secs(), t);
        let (_, max) = tip_difference_m(&before, &sim.tips_m());
        assert!(max < ENGINE_SWITCH_TOL_M, "tips moved {max} m");
        assert!(sim.stage_times().is_none() && sim.energies().is_none());
        run(&mut sim, 10);
        assert!(sim.engine().is_finite());
        // The batch engine's solver change rebuilds, keeping the shape.
        let before = sim.tips_m();
        style.sim.method = Method::BlockDiagonal;
        sim.sync(&style).unwrap();
        assert_eq!(
            (sim.kind(), sim.method()),
            (EngineKind::Batch, Method::BlockDiagonal)
        );
        assert!(tip_difference_m(&before, &sim.tips_m()).1 < ENGINE_SWITCH_TOL_M);
        // The compare view's override: the reference engine with Dense...
        sim.set_overrides(Some(EngineKind::Reference), Some(Method::Dense))
            .unwrap();
        assert_eq!(
            (sim.kind(), sim.method()),
            (EngineKind::Reference, Method::Dense)
        );
        assert!(tip_difference_m(&before, &sim.tips_m()).1 < ENGINE_SWITCH_TOL_M);
        // ...and back to the style's own.
        sim.set_overrides(None, None).unwrap();
        assert_eq!(sim.kind(), EngineKind::Batch);
        // The batch engine cannot run Dense: refused, nothing changes.
        assert!(sim.set_overrides(None, Some(Method::Dense)).is_err());
        assert_eq!(
            (sim.kind(), sim.method()),
            (EngineKind::Batch, Method::BlockDiagonal)
        );
    }

    #[test]
    fn tip_difference_is_rms_and_max() {
        let a = [DVec3::ZERO, DVec3::ZERO];
        let b = [DVec3::new(3.0, 0.0, 0.0), DVec3::new(0.0, 4.0, 0.0)];
        let (rms, max) = tip_difference_m(&a, &b);
        assert!((rms - (12.5f64).sqrt()).abs() < 1e-12 && max == 4.0);
    }
}
