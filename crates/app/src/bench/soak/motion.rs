//! The soak's head motion: the window's clips (nod, shake, turn, jerk)
//! played one after another in a seeded random order, with random still
//! pauses between them, for as long as the soak runs.
//!
//! The schedule is made up front from a small xorshift generator, so a
//! soak is reproducible from its seed alone and needs no `rand` crate.
//! Looking up the motion at a time is a binary search over the schedule:
//! the soak asks a million times.

use helixhair_physics::{HeadTrajectory, RigidMotion};

use crate::motion::clip::{Clip, motion_from_pose};

/// Longest still pause between two clips, seconds: long enough for the
/// hair to settle partly, short enough that most of the soak moves.
pub const MAX_PAUSE_SECS: f64 = 1.0;

/// One clip of the schedule.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    /// When the clip starts, seconds from the soak's start.
    pub start_secs: f64,
    /// The clip.
    pub clip: Clip,
}

/// Clips at random, back to back with random pauses, covering a duration.
#[derive(Clone, Debug)]
pub struct SoakMotion {
    segments: Vec<Segment>,
}

impl SoakMotion {
    /// A schedule covering at least `duration_secs`, from `seed`.
    pub fn new(seed: u64, duration_secs: f64) -> Self {
        let mut state = seed.max(1);
        let mut next = move || {
            // xorshift64 (Marsaglia 2003): plenty for picking clips.
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let mut segments = Vec::new();
        let mut t = 0.0;
        while t < duration_secs {
            let clip = Clip::ALL[(next() % Clip::ALL.len() as u64) as usize];
            segments.push(Segment {
                start_secs: t,
                clip,
            });
            let pause = MAX_PAUSE_SECS * (next() >> 11) as f64 / (1u64 << 53) as f64;
            t += clip.duration_secs() + pause;
        }
        Self { segments }
    }

    /// The clips in order.
    pub fn segments(&self) -> &[Segment] {
        &self.segments
    }

    /// How many times each clip is played, in [`Clip::ALL`]'s order.
    pub fn clip_counts(&self) -> [usize; 4] {
        let mut counts = [0; 4];
        for segment in &self.segments {
            let i = Clip::ALL.iter().position(|&c| c == segment.clip);
            counts[i.unwrap_or(0)] += 1;
        }
        counts
    }
}

impl HeadTrajectory for SoakMotion {
    fn motion_at(&self, t_secs: f64) -> RigidMotion {
        // The last segment starting at or before t; the clip's own pose is
        // the identity outside its duration, so a pause is a still head.
        let after = self.segments.partition_point(|s| s.start_secs <= t_secs);
        match after.checked_sub(1).map(|i| self.segments[i]) {
            Some(Segment { start_secs, clip }) => {
                motion_from_pose(|t| clip.pose_at(t - start_secs), t_secs)
            }
            None => RigidMotion::default(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_schedule_covers_the_duration_with_every_clip() {
        let motion = SoakMotion::new(7, 600.0);
        let last = motion.segments().last().expect("not empty");
        assert!(last.start_secs < 600.0);
        assert!(last.start_secs + last.clip.duration_secs() + MAX_PAUSE_SECS >= 600.0);
        assert!(motion.clip_counts().iter().all(|&n| n > 10));
        // A pause is a still head.
        let first = motion.segments()[0];
        let quiet = first.start_secs + first.clip.duration_secs() + 1e-3;
        let gap = motion.segments()[1].start_secs - quiet;
        if gap > 2.0 * crate::motion::clip::DIFF_SECS {
            let still = motion.motion_at(quiet + gap / 2.0);
            assert_eq!(still.angular_velocity_rad_per_s.length(), 0.0);
        }
    }

    #[test]
    fn the_motion_inside_a_segment_is_its_clip_shifted() {
        let motion = SoakMotion::new(3, 60.0);
        let segment = motion.segments()[2];
        let t = segment.start_secs + 0.3;
        let expected = motion_from_pose(|s| segment.clip.pose_at(s), 0.3);
        let got = motion.motion_at(t);
        let same = got
            .world_from_body
            .abs_diff_eq(expected.world_from_body, 1e-12);
        assert!(same, "{got:?} against {expected:?}");
        assert!((got.position_m - expected.position_m).length() < 1e-12);
    }
}
