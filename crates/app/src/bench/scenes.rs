//! The scenes the accuracy and stability studies run, and how a run is
//! recorded and compared.
//!
//! Every scene is one 20 cm strand on a head, run for a few seconds in
//! frames of 1/60 s; the tip's world position is recorded after every
//! frame. A run's **error** against a reference run is the RMS over frames
//! of the tip-position difference, as a fraction of the strand's length
//! ([`tip_rms_error`]); its **cost** is the CPU time of its steps per
//! simulated second.
//!
//! | scene | strand | root motion |
//! | --- | --- | --- |
//! | swing | straight, root horizontal | still: falls from straight and swings under gravity |
//! | bounce-CLASS | natural shape of CLASS, root 45° below horizontal | bounces 1.5 cm up and down at 2 Hz |
//! | shake | wavy, root on the side of the head | head shake, 0.5 rad at 1.5 Hz |
//!
//! The curl classes match the example styles: wavy R = 2.5 cm, step 12 cm;
//! curly R = 1.2 cm, step 3 cm; coily R = 5 mm, step 8 mm.

use std::sync::Arc;
use std::time::Instant;

use glam::DVec3;
use helixhair_physics::{
    Bounce, HairSystem, HeadTrajectory, Method, NaturalShape, Oscillation, RigidMotion, RootPose,
    SimSettings, Strand, StrandModel, StrandParams,
};

/// Frame length of every scene, seconds.
pub const FRAME_SECS: f64 = 1.0 / 60.0;
/// Strand length of every scene, metres.
pub const SCENE_LENGTH_M: f64 = 0.2;

/// Natural curl of a strand, as in the example styles.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CurlClass {
    /// No curl.
    Straight,
    /// Helix of radius 2.5 cm and step 12 cm.
    Wavy,
    /// Helix of radius 1.2 cm and step 3 cm.
    Curly,
    /// Helix of radius 5 mm and step 8 mm.
    Coily,
}

impl CurlClass {
    /// Every class, loosest first.
    pub const ALL: [CurlClass; 4] = [Self::Straight, Self::Wavy, Self::Curly, Self::Coily];

    /// The class's name in files.
    pub fn name(self) -> &'static str {
        match self {
            Self::Straight => "straight",
            Self::Wavy => "wavy",
            Self::Curly => "curly",
            Self::Coily => "coily",
        }
    }

    /// The natural shape.
    pub fn shape(self) -> NaturalShape {
        let helix = |radius_m, step_m| NaturalShape::Helix { radius_m, step_m };
        match self {
            Self::Straight => NaturalShape::Straight,
            Self::Wavy => helix(0.025, 0.12),
            Self::Curly => helix(0.012, 0.03),
            Self::Coily => helix(0.005, 0.008),
        }
    }
}

/// How the head moves during a scene.
#[derive(Clone, Copy, Debug)]
pub enum SceneMotion {
    /// The head stays still.
    Still,
    /// The head bounces.
    Bounce(Bounce),
    /// The head turns back and forth.
    Shake(Oscillation),
}

impl HeadTrajectory for SceneMotion {
    fn motion_at(&self, t_secs: f64) -> RigidMotion {
        match self {
            Self::Still => RigidMotion::default(),
            Self::Bounce(b) => b.motion_at(t_secs),
            Self::Shake(s) => s.motion_at(t_secs),
        }
    }
}

/// A strand, where it grows, how the head moves, for how long.
#[derive(Clone, Debug)]
pub struct Scene {
    /// Name in files and charts.
    pub name: String,
    /// Strand parameters; `elements` is set by each run.
    pub params: StrandParams,
    /// The root on the head.
    pub root: RootPose,
    /// The head's motion.
    pub motion: SceneMotion,
    /// Simulated seconds.
    pub duration_secs: f64,
    /// Frame length, seconds ([`FRAME_SECS`] unless a study changes it).
    pub frame_secs: f64,
}

impl Scene {
    /// A straight strand released horizontally: falls and swings.
    pub fn swing(duration_secs: f64) -> Self {
        Self {
            name: "swing".into(),
            params: StrandParams {
                length_m: SCENE_LENGTH_M,
                ..StrandParams::default()
            },
            root: RootPose::from_direction(DVec3::ZERO, DVec3::X, DVec3::Y),
            motion: SceneMotion::Still,
            duration_secs,
            frame_secs: FRAME_SECS,
        }
    }

    /// A strand of `class` growing 45° below the horizontal from a root
    /// bouncing 1.5 cm at 2 Hz: gravity bends it, so straight hair moves too.
    pub fn bounce(class: CurlClass, duration_secs: f64) -> Self {
        Self {
            name: format!("bounce-{}", class.name()),
            params: StrandParams {
                length_m: SCENE_LENGTH_M,
                natural_shape: class.shape(),
                ..StrandParams::default()
            },
            root: RootPose::from_direction(DVec3::ZERO, DVec3::new(1.0, -1.0, 0.0), DVec3::Z),
            motion: SceneMotion::Bounce(Bounce {
                direction: DVec3::Y,
                amplitude_m: 0.015,
                frequency_hz: 2.0,
            }),
            duration_secs,
            frame_secs: FRAME_SECS,
        }
    }

    /// A wavy strand on the side of a head shaking 0.5 rad at 1.5 Hz.
    pub fn shake(duration_secs: f64) -> Self {
        Self {
            name: "shake".into(),
            params: StrandParams {
                length_m: SCENE_LENGTH_M,
                natural_shape: CurlClass::Wavy.shape(),
                ..StrandParams::default()
            },
            root: RootPose::from_direction(
                DVec3::new(0.09, 0.03, 0.0),
                DVec3::new(1.0, 0.3, 0.0),
                DVec3::Z,
            ),
            motion: SceneMotion::Shake(Oscillation {
                axis: DVec3::Y,
                amplitude_rad: 0.5,
                frequency_hz: 1.5,
            }),
            duration_secs,
            frame_secs: FRAME_SECS,
        }
    }
}

/// A lone strand with `params` on a horizontal root at the origin (growing
/// along +x, n₁ = +y), solved with `method` and the default quadrature:
/// the cantilever the cost and modes studies time and shake.
pub fn horizontal_strand(params: &StrandParams, method: Method) -> Strand {
    let quadrature = SimSettings::default().quadrature_points;
    let model = StrandModel::new(params, quadrature).expect("bench parameters are valid");
    let root = RootPose::from_direction(DVec3::ZERO, DVec3::X, DVec3::Y);
    Strand::new(Arc::new(model), root, method)
}

/// How a scene is run: solver, elements and substeps per 1/60 s frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunSetting {
    /// Solver.
    pub method: Method,
    /// Elements per strand.
    pub elements: usize,
    /// Substeps per frame: the step is h = (1/60 s) / substeps.
    pub substeps: u32,
}

/// What a run recorded.
#[derive(Clone, Debug)]
pub struct Trajectory {
    /// Tip position after every frame, world coordinates, metres.
    pub tips_m: Vec<DVec3>,
    /// Root position after every frame, world coordinates, metres.
    pub roots_m: Vec<DVec3>,
    /// CPU seconds spent stepping.
    pub step_secs: f64,
    /// Whether the state stayed finite to the end.
    pub finite: bool,
    /// Fastest frame-to-frame speed of the tip relative to the root, m/s.
    pub max_relative_tip_speed_m_per_s: f64,
}

/// Runs `scene` with `setting`, serially (one strand, one thread), with
/// the guard off: the studies measure the solvers themselves.
pub fn run_scene(scene: &Scene, setting: RunSetting) -> Trajectory {
    run_scene_with(scene, setting, |s| s.set_guard(None))
}

/// Runs `scene` with `setting` after `prepare` has adjusted the system.
pub fn run_scene_with(
    scene: &Scene,
    setting: RunSetting,
    prepare: impl FnOnce(&mut HairSystem),
) -> Trajectory {
    let settings = SimSettings {
        method: setting.method,
        dt_secs: scene.frame_secs,
        substeps: setting.substeps,
        ..SimSettings::default()
    };
    let params = StrandParams {
        elements: setting.elements,
        ..scene.params.clone()
    };
    let mut system = HairSystem::new(settings).expect("scene settings are valid");
    system
        .add_group(&params, &[scene.root])
        .expect("scene parameters are valid");
    system.set_parallel(false);
    prepare(&mut system);
    let frames = (scene.duration_secs / scene.frame_secs).round() as usize;
    let mut trajectory = Trajectory {
        tips_m: Vec::with_capacity(frames),
        roots_m: Vec::with_capacity(frames),
        step_secs: 0.0,
        finite: true,
        max_relative_tip_speed_m_per_s: 0.0,
    };
    for _ in 0..frames {
        let start = Instant::now();
        system.step_frame(&scene.motion);
        trajectory.step_secs += start.elapsed().as_secs_f64();
        if !system.is_finite() {
            trajectory.finite = false;
            break;
        }
        let points = system.boundary_points_world(0);
        let (tip, root) = (points[points.len() - 1], points[0]);
        if let (Some(t), Some(r)) = (trajectory.tips_m.last(), trajectory.roots_m.last()) {
            let speed = ((tip - root) - (*t - *r)).length() / scene.frame_secs;
            trajectory.max_relative_tip_speed_m_per_s =
                trajectory.max_relative_tip_speed_m_per_s.max(speed);
        }
        trajectory.tips_m.push(tip);
        trajectory.roots_m.push(root);
    }
    trajectory
}

/// RMS over frames of the tip distance between `run` and `reference`, as a
/// fraction of `length_m`; infinite if `run` stopped early (not finite).
pub fn tip_rms_error(run: &Trajectory, reference: &Trajectory, length_m: f64) -> f64 {
    if !run.finite || run.tips_m.len() != reference.tips_m.len() || run.tips_m.is_empty() {
        return f64::INFINITY;
    }
    let sum: f64 = run
        .tips_m
        .iter()
        .zip(&reference.tips_m)
        .map(|(a, b)| a.distance_squared(*b))
        .sum();
    (sum / run.tips_m.len() as f64).sqrt() / length_m
}

/// RMS over frames of the tip's distance from its mean position relative
/// to the root: how much the strand moves in a run, metres.
pub fn tip_motion_rms(run: &Trajectory) -> f64 {
    let rel: Vec<DVec3> = run
        .tips_m
        .iter()
        .zip(&run.roots_m)
        .map(|(t, r)| *t - *r)
        .collect();
    if rel.is_empty() {
        return 0.0;
    }
    let mean = rel.iter().copied().sum::<DVec3>() / rel.len() as f64;
    (rel.iter().map(|p| p.distance_squared(mean)).sum::<f64>() / rel.len() as f64).sqrt()
}
