//! The head-shake scene of the stable-step tests (both engines): the
//! straight example's 30 cm strands on two roots of a 10 cm head, and a
//! shake that stops. The probes `examples/shake_probe.rs` and
//! `examples/batch_shake_probe.rs` include this file too, so the tests
//! and the probes measure one scene.

use glam::DVec3;
use helixhair_physics::motion::HeadTrajectory;
use helixhair_physics::{
    ElementLayout, NaturalShape, Oscillation, RigidMotion, RootPose, StrandParams,
};

/// The straight example's long strands (`assets/styles/straight.ron`).
pub fn straight_30_cm() -> StrandParams {
    StrandParams {
        length_m: 0.3,
        elements: 12,
        layout: ElementLayout::Graded {
            tip_to_root_ratio: 3.0,
        },
        radius_m: 40e-6,
        ..StrandParams::default()
    }
}

/// The wavy example's long strands: [`straight_30_cm`] with a 2.5 cm
/// curl radius and a 12 cm helix step.
pub fn wavy_30_cm() -> StrandParams {
    StrandParams {
        natural_shape: NaturalShape::Helix {
            radius_m: 0.025,
            step_m: 0.12,
        },
        ..straight_30_cm()
    }
}

/// The probes' strands by name: `wavy`, `curly`, or straight for
/// anything else.
pub fn strands_named(shape: &str) -> StrandParams {
    match shape {
        "wavy" => wavy_30_cm(),
        "curly" => curly_25_cm(),
        _ => straight_30_cm(),
    }
}

/// `assets/styles/curly.ron`'s crown: 25 cm curls of 15 elements.
pub fn curly_25_cm() -> StrandParams {
    StrandParams {
        length_m: 0.25,
        elements: 15,
        ellipticity: 1.35,
        natural_shape: NaturalShape::Helix {
            radius_m: 0.012,
            step_m: 0.03,
        },
        ..StrandParams::default()
    }
}

/// Roots on the side and the crown of a 10 cm head, growing outward.
pub fn head_roots() -> Vec<RootPose> {
    vec![
        RootPose::from_direction(
            DVec3::new(0.0966, 0.0259, 0.0),
            DVec3::new(0.9659, 0.2588, 0.0),
            DVec3::Z,
        ),
        RootPose::from_direction(
            DVec3::new(0.0, 0.0866, 0.05),
            DVec3::new(0.0, 0.866, 0.5),
            DVec3::X,
        ),
    ]
}

/// The ordinary head shake: 0.5 rad at 1.5 Hz about the vertical.
pub fn ordinary_shake() -> Oscillation {
    Oscillation {
        axis: DVec3::Y,
        amplitude_rad: 0.5,
        frequency_hz: 1.5,
    }
}

/// A head shake that stops after `shake_secs` (a whole number of periods
/// and a quarter, where the head's angular velocity is zero) and then
/// holds still.
pub struct ShakeThenStill {
    pub shake: Oscillation,
    pub shake_secs: f64,
}

impl ShakeThenStill {
    /// [`ordinary_shake`] for 4¼ periods.
    pub fn ordinary() -> Self {
        Self {
            shake: ordinary_shake(),
            shake_secs: 4.25 / 1.5,
        }
    }
}

impl HeadTrajectory for ShakeThenStill {
    fn motion_at(&self, t_secs: f64) -> RigidMotion {
        if t_secs < self.shake_secs {
            self.shake.motion_at(t_secs)
        } else {
            self.shake.motion_at(self.shake_secs).motion_at(t_secs)
        }
    }
}
