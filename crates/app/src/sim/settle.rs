//! The start state of hair on a head: settled on it.
//!
//! A strand starts in its natural shape, which knows nothing of the head:
//! a 2.5 cm curl radius on a strand leaving the scalp at 15° dips the
//! curl's far side 5 cm into the skull (27% of the groomed wavy example's
//! points started inside the head), and the plain examples' listed roots
//! grow straight out from a 10 cm sphere, 30 cm spikes that fall onto the
//! head. Left so, the first frames are the contact throwing that hair out
//! or the hair landing: a pop an artist sees on every load, and an export
//! at frame 0 with a quarter of the hair in the head. Landing hair is
//! also the hardest contact Block-diagonal meets (docs/physics.md): on
//! the default head, unsettled, it handed 5–27 strand-frames of the
//! straight, wavy and curly examples to Exact on a still head; settled,
//! none.
//!
//! So before its first frame such a run settles: a copy of the engine
//! (on the CPU: the GPU engine's batch system) steps [`SETTLE_SECS`] (at
//! most [`SETTLE_FRAMES_MAX`] frames) on the still head (contact pushing
//! the hair out, gravity draping it), and the run starts from the copy's
//! shapes at rest (velocities zero). The run's own clock, guard record and head are
//! untouched: the settling is not part of the simulation the user plays,
//! only where it begins. Imported grooms are not settled: their rest
//! shapes were solved against the head's push already (`import`'s
//! sag-free solve).

use helixhair_physics::RigidMotion;
use helixhair_physics::engine::Engine;

use crate::style::Style;

/// Whether `style`'s hair settles on its head before its first frame:
/// every style but an imported groom, whose rest shapes were solved
/// against the head's push already (see the module docs).
pub fn settles_on_head(style: &Style) -> bool {
    style.groups.iter().all(|g| g.imported.is_none())
}

/// Seconds of still-head simulation a scalp-grown style settles for before
/// its first frame: 3 s. Measured on the groomed wavy example (points
/// inside the head at frame 0, roots and tips aside): 26.6% unsettled,
/// 1.6% after 1 s, 1.0% after 2 s, 0.8% after 3 s; the rest is the contact
/// law's resting depth (issue 33). Stopping each strand at its fastest
/// point (kinetic damping) settled it slower (1.2% after 2 s). 3 s costs
/// 180 frames: 1.5 to 2.7 s of load on two cores for the groomed examples
/// (100–400 simulated strands on the reference engine).
pub const SETTLE_SECS: f64 = 3.0;

/// Most frames a settling steps: 180, [`SETTLE_SECS`] at 60 Hz. A style
/// stepping finer settles for less than 3 s: settling is where a run
/// begins, and must not cost more than 3 s of a 60 Hz run. Uncapped, a
/// style of 1e-5 s frames (the window's test of values beyond every
/// slider) stepped 300,000 frames of 100-element strands before its
/// first: about 11 minutes on two cores, most of the app's unit tests'
/// time (2 s with the cap).
pub const SETTLE_FRAMES_MAX: usize = 180;

/// Settles `engine`'s strands on its collider (see the module docs);
/// nothing without a collider.
pub fn settle_on_head(engine: &mut Engine) {
    if engine.collider().is_none() {
        return;
    }
    // On the CPU whatever the engine: the GPU engine settles as the batch
    // engine does (the same arithmetic, so both start from one shape;
    // settled on the device, the two started up to 0.7 mm apart on the
    // straight example, after 180 frames of landing hair's contact).
    let mut probe = engine.cpu_copy();
    let frames = ((SETTLE_SECS / probe.settings().dt_secs).ceil() as usize).min(SETTLE_FRAMES_MAX);
    let still = RigidMotion::default();
    for _ in 0..frames {
        probe.step_frame(&still);
    }
    if !probe.is_finite() {
        return;
    }
    for index in 0..engine.strand_count() {
        let q = probe.q(index);
        let v = vec![glam::DVec3::ZERO; q.len()];
        engine.set_state(index, &q, &v);
    }
}
