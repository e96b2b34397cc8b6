//! Builders shared by the physics tests.
#![allow(dead_code, missing_docs)] // each test file uses a different subset

#[cfg(feature = "gpu")]
pub mod gpu;
pub mod shake_scene;
pub mod sphere;
pub mod volume_scene;

use std::sync::Arc;

use glam::{DMat3, DVec3};
use helixhair_physics::step::forces::{ForceInputs, generalized_forces};
use helixhair_physics::step::reconstruct::{Kinematics, reconstruct};
use helixhair_physics::{
    Method, NaturalShape, Oscillation, RigidMotion, RootPose, Strand, StrandModel, StrandParams,
};

/// A small deterministic generator (xorshift) so tests need no rand crate.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Self(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    /// Uniform in [-1, 1).
    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
    pub fn vec3(&mut self, scale: f64) -> DVec3 {
        DVec3::new(self.next(), self.next(), self.next()) * scale
    }
    pub fn rotation(&mut self) -> DMat3 {
        let axis = self.vec3(1.0).normalize();
        DMat3::from_axis_angle(axis, 3.0 * self.next())
    }
}

/// Default hair, `elements` elements of a `length_m` strand, no friction or
/// drag unless set later.
pub fn params(length_m: f64, elements: usize) -> StrandParams {
    StrandParams {
        length_m,
        elements,
        internal_friction: 0.0,
        air_drag: 0.0,
        ..StrandParams::default()
    }
}

/// A strand of `length_m` and `elements` whose elements grow 3:1 from
/// root to tip, 3 quadrature points each: the derivative checks' strand.
pub fn graded_model(length_m: f64, elements: usize) -> StrandModel {
    let mut p = params(length_m, elements);
    p.layout = helixhair_physics::ElementLayout::Graded {
        tip_to_root_ratio: 3.0,
    };
    model(&p, 3)
}

pub fn model(p: &StrandParams, quadrature_points: usize) -> StrandModel {
    StrandModel::new(p, quadrature_points).expect("valid test parameters")
}

pub fn strand(p: &StrandParams, method: Method) -> Strand {
    Strand::new(Arc::new(model(p, 4)), horizontal_root(), method)
}

/// Root at the origin growing along +x, n₁ = +y, n₂ = +z.
pub fn horizontal_root() -> RootPose {
    RootPose {
        position_m: DVec3::ZERO,
        head_from_root: DMat3::IDENTITY,
    }
}

pub fn at_rest(world_from_root: DMat3) -> RigidMotion {
    RigidMotion::at_rest(DVec3::ZERO, world_from_root)
}

pub fn kinematics(m: &StrandModel, q: &[DVec3], v: &[DVec3], root: &RigidMotion) -> Kinematics {
    let mut k = Kinematics::default();
    reconstruct(m, q, v, root, &mut k);
    k
}

/// The generalized forces Q (N·m²) on a strand in state (`q`, `v`) under
/// `gravity` alone (no wind, contact or hair volume).
pub fn forces_under_gravity(
    m: &StrandModel,
    q: &[DVec3],
    v: &[DVec3],
    root: &RigidMotion,
    gravity_m_per_s2: DVec3,
) -> Vec<DVec3> {
    let kin = kinematics(m, q, v, root);
    let inputs = ForceInputs {
        root,
        gravity_m_per_s2,
        air_velocity_m_per_s: DVec3::ZERO,
        external_n_per_m: &[],
        contact: None,
        volume: None,
    };
    let mut out = vec![DVec3::ZERO; q.len()];
    generalized_forces(m, &kin, &inputs, &mut out);
    out
}

/// A random state for the f64 reference and the f32 batch alike: strains
/// ±5 m⁻¹ off `natural`, rates ±20 m⁻¹/s, rounded to f32 first so both
/// start from the same numbers.
pub fn f32_random_state(rng: &mut Rng, natural: &[DVec3]) -> (Vec<DVec3>, Vec<DVec3>) {
    let q = natural
        .iter()
        .map(|k| (*k + rng.vec3(5.0)).as_vec3().as_dvec3())
        .collect();
    let v = natural
        .iter()
        .map(|_| rng.vec3(20.0).as_vec3().as_dvec3())
        .collect();
    (q, v)
}

pub fn random_strains(rng: &mut Rng, n: usize, scale_per_m: f64) -> Vec<DVec3> {
    (0..n).map(|_| rng.vec3(scale_per_m)).collect()
}

pub fn helix_shape() -> NaturalShape {
    NaturalShape::Helix {
        radius_m: 0.01,
        step_m: 0.02,
    }
}

/// Largest absolute difference of two vector lists.
pub fn max_diff(a: &[DVec3], b: &[DVec3]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (*x - *y).abs().max_element())
        .fold(0.0, f64::max)
}

/// Steps a strand with a fixed root until its strain rates fall below
/// `rate_tol` (m⁻¹/s), returning the steps taken; panics after `max_steps`.
pub fn settle(
    s: &mut Strand,
    root: &RigidMotion,
    gravity: DVec3,
    h: f64,
    rate_tol: f64,
    max_steps: usize,
) -> usize {
    for step in 0..max_steps {
        s.step(root, gravity, DVec3::ZERO, h);
        assert!(s.is_finite(), "non-finite state at step {step}");
        let rate = s
            .v()
            .iter()
            .map(|v| v.abs().max_element())
            .fold(0.0, f64::max);
        if rate < rate_tol {
            return step + 1;
        }
    }
    panic!("strand did not settle in {max_steps} steps");
}

/// Parameters of a heavy elastica: `elements` elements, gravity magnitude
/// chosen so that α = ρS g L³/EI, strong friction so that it settles.
pub fn elastica(alpha: f64, elements: usize) -> (StrandParams, DVec3) {
    let mut p = params(0.1, elements);
    let ei = p.stiffness()[2];
    let g = alpha * ei / (p.mass_per_length() * p.length_m.powi(3));
    p.internal_friction = 2e-10;
    (p, DVec3::new(0.0, -g, 0.0))
}

/// Tip drop y/L, pull-in (L − x)/L and tip angle of a strand rooted at the
/// origin growing along +x.
pub fn tip_measures(s: &Strand) -> (f64, f64, f64) {
    let kin = s.kinematics(&at_rest(DMat3::IDENTITY));
    let l = s.model().params.length_m;
    let tip = *kin.points_m.last().expect("a strand has points");
    let n0 = kin.frames.last().expect("a strand has frames").col(0);
    (-tip.y / l, (l - tip.x) / l, (-n0.y).atan2(n0.x))
}

/// A 20 cm curl (radius 1 cm, step 2 cm), N = 12, default friction, on a
/// root 10 cm up and turned 0.8 rad about an oblique axis.
pub fn curl_on_oblique_root() -> (StrandParams, RigidMotion) {
    let mut p = params(0.2, 12);
    p.natural_shape = helix_shape();
    p.internal_friction = 2e-10;
    let root = RigidMotion::at_rest(
        DVec3::new(0.0, 0.1, 0.0),
        DMat3::from_axis_angle(DVec3::new(1.0, 2.0, 0.5).normalize(), 0.8),
    );
    (p, root)
}

/// `straight.ron`'s crown strand: 30 cm, 12 graded elements, 40 µm, the
/// example's moduli; and a root on a 10 cm head growing out of the vertical
/// plane through its centre, where f32 moments about the root failed
/// (`examples/f32_precision.rs`).
pub fn straight_strand_out_of_plane() -> (StrandParams, RootPose) {
    let params = StrandParams {
        length_m: 0.3,
        elements: 12,
        layout: helixhair_physics::params::ElementLayout::Graded {
            tip_to_root_ratio: 3.0,
        },
        radius_m: 40e-6,
        youngs_modulus_pa: 3.9e9,
        shear_modulus_pa: 0.9e9,
        ..StrandParams::default()
    };
    let direction = DVec3::new(0.7698, 0.5736, 0.2802);
    (
        params,
        RootPose::from_direction(direction * 0.1, direction, DVec3::Y),
    )
}

/// The hanging curl on which Block-diagonal blows up at 60 Hz from N = 8
/// (`guards.rs`): 20 cm, a 2 cm helix, little friction.
pub fn hanging_curl(n: usize) -> StrandParams {
    let mut p = params(0.2, n);
    p.natural_shape = NaturalShape::Helix {
        radius_m: 0.02,
        step_m: 0.05,
    };
    p.internal_friction = 2e-10;
    p.air_drag = 1e-5;
    p
}

/// Default strands with N elements curled into a 2 cm helix of 5 cm step.
pub fn curl(n: usize) -> StrandParams {
    StrandParams {
        elements: n,
        natural_shape: NaturalShape::Helix {
            radius_m: 0.02,
            step_m: 0.05,
        },
        ..StrandParams::default()
    }
}

/// The head shake of the parity tests: 0.5 rad at 1.5 Hz about a tilted
/// vertical axis.
/// A head that moves 5 cm side to side at 1.5 Hz without turning, at
/// `t_secs`: every point of it moves with one velocity.
pub fn side_to_side(t_secs: f64) -> RigidMotion {
    let (amplitude_m, rad_per_s) = (0.05, std::f64::consts::TAU * 1.5);
    let phase = rad_per_s * t_secs;
    RigidMotion {
        position_m: DVec3::X * amplitude_m * phase.sin(),
        velocity_m_per_s: DVec3::X * amplitude_m * rad_per_s * phase.cos(),
        acceleration_m_per_s2: DVec3::X * -amplitude_m * rad_per_s.powi(2) * phase.sin(),
        ..RigidMotion::default()
    }
}

pub fn shake() -> Oscillation {
    Oscillation {
        axis: DVec3::new(0.2, 1.0, 0.1),
        amplitude_rad: 0.5,
        frequency_hz: 1.5,
    }
}

/// `count` roots within 10 cm of the head's centre, growing roughly
/// outwards (seed 9).
pub fn outward_roots(count: usize) -> Vec<RootPose> {
    let mut rng = Rng::new(9);
    (0..count)
        .map(|_| {
            let p = rng.vec3(0.1);
            RootPose::from_direction(p, p.normalize() + rng.vec3(0.3), DVec3::Y)
        })
        .collect()
}

/// A random rigid motion of the head: position within 0.1 m, any
/// orientation, speeds up to 0.5 m/s and 4 rad/s, accelerations up to
/// 5 m/s² and 40 rad/s² per axis (a brisk head shake's order).
pub fn moving_root(rng: &mut Rng) -> RigidMotion {
    RigidMotion {
        position_m: rng.vec3(0.1),
        world_from_body: rng.rotation(),
        velocity_m_per_s: rng.vec3(0.5),
        angular_velocity_rad_per_s: rng.vec3(4.0),
        acceleration_m_per_s2: rng.vec3(5.0),
        angular_acceleration_rad_per_s2: rng.vec3(40.0),
    }
}
