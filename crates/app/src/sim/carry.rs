//! Moving the hair's state from one engine to a rebuilt one.
//!
//! The physics builds a strand's model (mass, stiffness, rest shape) once,
//! when the strand is added, so an edited style runs on a new engine. Its
//! strands start where the old ones were: strains q and rates q̇ are copied
//! where a strand's element layout is unchanged, and resampled
//! ([`crate::sim::resample`]) where it changed, in one of two ways:
//!
//! - [`Carry::Stretch`]: the old profile stretched over the new length (a
//!   length slider makes the whole strand longer: its curl stretches);
//! - [`Carry::ArcLength`]: by arc length from the root (a cut removes the
//!   tip and keeps the rest exactly; a grown strand continues its tip).

use glam::DVec3;
use helixhair_physics::engine::Engine;

use crate::sim::resample::{resample_by_arc_length, resample_per_element};

/// How a strand's state is carried onto new element lengths.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Carry {
    /// The old profile stretched over the new length.
    Stretch,
    /// By arc length from the root: cut at the tip, or continued past it.
    ArcLength,
}

/// Every strand of `new` that `old` also has starts in `old`'s state,
/// carried as `how` says where its elements changed; the strands in
/// `at_rest` (engine indices) start with no velocity.
pub fn carry_state(old: &Engine, new: &mut Engine, how: Carry, at_rest: &[usize]) {
    let mut still = vec![false; new.strand_count()];
    for &i in at_rest {
        if let Some(s) = still.get_mut(i) {
            *s = true;
        }
    }
    let shared = old.strand_count().min(new.strand_count());
    for (i, &start_still) in still.iter().enumerate().take(shared) {
        let old_lengths = &old.strand_model(i).lengths_m;
        let new_lengths = new.strand_model(i).lengths_m.clone();
        let carry = |x: Vec<DVec3>| {
            if *old_lengths == new_lengths {
                x
            } else {
                match how {
                    Carry::Stretch => resample_per_element(&x, old_lengths, &new_lengths),
                    Carry::ArcLength => resample_by_arc_length(&x, old_lengths, &new_lengths),
                }
            }
        };
        let q = carry(old.q(i));
        let v = if start_still {
            vec![DVec3::ZERO; q.len()]
        } else {
            carry(old.v(i))
        };
        new.set_state(i, &q, &v);
    }
}
