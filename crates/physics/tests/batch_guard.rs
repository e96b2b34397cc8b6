//! The guard on the f32 batch path (`batch::guard`, `batch::retry`): the
//! Block-diagonal blow-up of `guards.rs` is caught and handed to Exact,
//! a frame no retry can pass resets the strand to its start at rest, a
//! strand that keeps failing is pinned once at its rest pose, and a
//! healthy run is bit-identical with and without the guard: the f64
//! guard's policy (`guards.rs`).

use crate::common;

use common::*;
use glam::DVec3;
use helixhair_physics::batch::{BatchSystem, FlatState, SubstepOffload};
use helixhair_physics::frame_balance::{KineticEnergy, StrandMeasure};
use helixhair_physics::guard::speed_bound_m_per_s;
use helixhair_physics::{
    Guard, GuardAction, Method, Oscillation, RigidMotion, RootPose, SimSettings, StepScheme,
    StrandParams,
};

/// Straight strands growing sideways from the origin, in a few directions.
fn straight_roots(count: usize) -> Vec<RootPose> {
    (0..count)
        .map(|i| {
            let a = i as f64;
            RootPose::from_direction(DVec3::ZERO, DVec3::new(a.cos(), 0.2, a.sin()), DVec3::Y)
        })
        .collect()
}

/// Three straight strands (indices 0..3), then two hanging curls (3..5),
/// stepped with `method` at 60 Hz, one substep, with the settings'
/// default (velocity-implicit) scheme.
fn mixed(method: Method, guard: Option<Guard>) -> BatchSystem {
    let settings = SimSettings {
        method,
        ..SimSettings::default()
    };
    let mut system = BatchSystem::new(settings).expect("valid settings");
    system.set_guard(guard);
    system
        .add_group(&StrandParams::default(), &straight_roots(3))
        .expect("valid params");
    system
        .add_group(&hanging_curl(10), &[horizontal_root(), horizontal_root()])
        .expect("valid params");
    system
}

/// A guard whose 1 mm/s speed limit fails every strand falling from rest.
fn strict() -> Guard {
    Guard {
        speed_limit_m_per_s: 1e-3,
        ..Guard::default()
    }
}

fn states(system: &BatchSystem, strands: std::ops::Range<usize>) -> Vec<(Vec<DVec3>, Vec<DVec3>)> {
    strands.map(|i| (system.q(i), system.v(i))).collect()
}

/// Block-diagonal with its own Lagrangian's velocity terms (the default
/// scheme) holds the hanging curl on a still head: finite, and the guard
/// never steps in.
#[test]
fn block_diagonal_with_its_own_terms_holds_the_hanging_curl() {
    let still = at_rest(glam::DMat3::IDENTITY);
    let mut guarded = mixed(Method::BlockDiagonal, Some(Guard::default()));
    for _ in 0..240 {
        guarded.step_frame(&still);
        assert!(guarded.is_finite());
        assert!(
            guarded.last_guard_events().is_empty(),
            "{:?}",
            guarded.last_guard_events()
        );
    }
}

/// Two hanging curls stepped with Block-diagonal and the whole system's
/// velocity terms (velocity-explicit), which blow them up.
fn exploding_curls(guard: Option<Guard>) -> BatchSystem {
    let settings = SimSettings {
        method: Method::BlockDiagonal,
        scheme: StepScheme::VelocityExplicit,
        ..SimSettings::default()
    };
    let mut system = BatchSystem::new(settings).expect("valid settings");
    system.set_guard(guard);
    system
        .add_group(&hanging_curl(10), &[horizontal_root(), horizontal_root()])
        .expect("valid params");
    system
}

/// With the whole system's velocity terms (velocity-explicit), which
/// belong to no Lagrangian of its truncated inertia, Block-diagonal blows
/// up on the hanging curl: judged by Block-diagonal's own energy
/// (`frame_balance::KineticEnergy`), the blow-up is still caught, and
/// handed to Exact as the f64 guard hands it (`guards.rs`), not reset.
#[test]
fn a_block_diagonal_blow_up_on_a_hanging_curl_is_handed_to_exact() {
    let still = at_rest(glam::DMat3::IDENTITY);
    // The curls alone: a straight strand's failures would keep its batch
    // on Exact, curls and all.
    let mut raw = exploding_curls(None);
    let blew_up = (0..120).any(|_| {
        raw.step_frame(&still);
        !raw.is_finite()
    });
    assert!(blew_up, "the raw f32 Block-diagonal should blow up");
    let guard = Guard::default();
    let mut guarded = exploding_curls(Some(guard));
    let curl_model = model(&hanging_curl(10), 4);
    let mut events = Vec::new();
    for _ in 0..240 {
        guarded.step_frame(&still);
        assert!(guarded.is_finite(), "the guarded run went non-finite");
        for i in 0..2 {
            let speed = speed_bound_m_per_s(&curl_model, &guarded.v(i));
            assert!(
                speed <= guard.speed_limit_m_per_s,
                "strand {i}: {speed} m/s"
            );
        }
        events.extend_from_slice(guarded.last_guard_events());
    }
    println!("{} events, the first: {:?}", events.len(), events.first());
    assert!(!events.is_empty(), "the guard never stepped in");
    let curl = &events[0];
    assert!(
        matches!(
            curl.action,
            GuardAction::Retried {
                method: Method::Exact,
                substeps: 1
            }
        ),
        "the first retry should hand the curl to Exact: {curl}"
    );
    assert!(
        events
            .iter()
            .all(|e| !matches!(e.action, GuardAction::Pinned))
    );
    assert_eq!(guarded.guard_event_count(), events.len());
}

/// A stand-in for the GPU engine: the same strands on an unguarded batch
/// system, stepped one substep at a time with the settings' own solver,
/// as the device steps them.
struct CpuOffload(BatchSystem, FlatState);

impl SubstepOffload for CpuOffload {
    fn keep_start(&mut self) {
        self.1 = self.0.state_flat();
    }
    fn download_start(&mut self) -> Result<FlatState, String> {
        Ok(self.1.clone())
    }
    fn upload(&mut self, q: &[[f32; 4]], v: &[[f32; 4]]) {
        self.0.set_state_flat(q, v);
    }
    fn substep(&mut self, motion: &RigidMotion) {
        // One substep a frame: the motion is the substep's (a still head).
        self.0.step_frame(motion);
    }
    fn download(&mut self) -> Result<FlatState, String> {
        Ok(self.0.state_flat())
    }
    fn measure(
        &mut self,
        head: &RigidMotion,
        judged_by: KineticEnergy,
    ) -> Result<Vec<(StrandMeasure, bool)>, String> {
        Ok(self.0.measure_strands(head, judged_by))
    }
}

/// The GPU engine's frame (`BatchSystem::step_frame_offloaded`) follows
/// the batch engine's guard to the bit, retries and holds included: a
/// batch the guard holds on Exact after a retry steps Exact on the CPU,
/// and what the device stepped for it with the settings' own solver is
/// dropped. (The device stepping a held batch with Block-diagonal, judged
/// by Exact's energy, drew 476 events on the straight example under the
/// jerk against the batch engine's 46.)
#[test]
fn the_offloaded_frame_follows_the_batch_guard_through_retries_and_holds() {
    let still = at_rest(glam::DMat3::IDENTITY);
    let mut own = exploding_curls(Some(Guard::default()));
    let mut offloaded = exploding_curls(Some(Guard::default()));
    let mut device = CpuOffload(exploding_curls(None), Default::default());
    let (mut upload, mut held_frames, mut elsewhere_frames) = (true, 0, 0);
    for frame in 0..240 {
        own.step_frame(&still);
        upload = offloaded
            .step_frame_offloaded(&still, &mut device, upload)
            .expect("the stand-in reads back");
        let (a, b) = (own.last_guard_events(), offloaded.last_guard_events());
        assert_eq!(format!("{a:?}"), format!("{b:?}"), "frame {frame}");
        // The state stays on the stand-in where no strand needed it here.
        let now = if offloaded.state_is_elsewhere() {
            elsewhere_frames += 1;
            &device.0
        } else {
            &offloaded
        };
        assert_eq!(states(&own, 0..2), states(now, 0..2), "frame {frame}");
        // An upload with no event: a held batch was stepped on the CPU.
        held_frames += usize::from(upload && b.is_empty());
    }
    assert!(own.guard_event_count() > 0, "the guard never stepped in");
    assert!(held_frames > 0, "no frame held a retry's step");
    assert!(elsewhere_frames > 0, "every frame read the state back");
    println!(
        "{} events; {held_frames} frames with a batch held on Exact; {elsewhere_frames} frames \
         left the state on the stand-in",
        own.guard_event_count()
    );
}

/// A guard whose 1 mm/s speed limit no retry can meet, with retries up to
/// 4 substeps.
fn strict_few_retries() -> Guard {
    Guard {
        max_substeps: 4,
        ..strict()
    }
}

/// No retry passes: the strand goes back to its shape at the frame's
/// start, at rest, as the f64 guard puts it (`guards.rs`).
#[test]
fn a_frame_no_retry_can_pass_resets_the_strand_to_its_start_at_rest() {
    let mut system = mixed(Method::Exact, None);
    let still = at_rest(glam::DMat3::IDENTITY);
    for _ in 0..10 {
        system.step_frame(&still);
    }
    let start = system.q(4);
    system.set_guard(Some(strict_few_retries()));
    system.step_frame(&still);
    assert_eq!(system.last_guard_resets(), &[0, 1, 2, 3, 4]);
    let events = system.last_guard_events();
    assert!(events.iter().all(|e| e.action == GuardAction::Reset));
    assert_eq!(system.q(4), start);
    assert!(system.v(4).iter().all(|v| *v == DVec3::ZERO));
}

/// A strand that keeps failing is pinned once, held at rest in its rest
/// pose: an imported sag-free strand's is its groomed shape
/// (`BatchSystem::set_rest_pose`), which gravity holds, not its natural
/// strains, from which it would swing back into its pose.
#[test]
fn a_pinned_strand_is_held_at_its_rest_pose() {
    let mut system = mixed(Method::Exact, Some(strict_few_retries()));
    let natural = model(&hanging_curl(10), 4).natural;
    let pose: Vec<DVec3> = natural
        .iter()
        .enumerate()
        .map(|(e, k)| *k + DVec3::new(1.0, -2.0, 3.0) * (e as f64 + 1.0))
        .collect();
    system.set_rest_pose(4, &pose);
    let mut actions = Vec::new();
    for _ in 0..120 {
        system.step_frame(&at_rest(glam::DMat3::IDENTITY));
        actions.extend(
            system
                .last_guard_events()
                .iter()
                .filter(|e| e.strand == 4)
                .map(|e| e.action),
        );
    }
    assert_eq!(
        actions,
        [GuardAction::Reset, GuardAction::Reset, GuardAction::Pinned]
    );
    let pose_f32: Vec<DVec3> = pose.iter().map(|k| k.as_vec3().as_dvec3()).collect();
    let natural_f32: Vec<DVec3> = natural.iter().map(|k| k.as_vec3().as_dvec3()).collect();
    assert_eq!(system.q(4), pose_f32);
    assert!(system.v(4).iter().all(|v| *v == DVec3::ZERO));
    // Its batch-mate, told nothing, is pinned at its natural shape.
    assert_eq!(system.q(3), natural_f32);
}

#[test]
fn a_healthy_run_is_left_alone_and_matches_the_unguarded_one() {
    // Exact on the hanging curl and straight strands under a head shake at
    // 60 Hz is finite and slow: the guard must not step in, nor change a bit.
    let shake = Oscillation {
        axis: DVec3::new(0.2, 1.0, 0.1),
        amplitude_rad: 0.3,
        frequency_hz: 1.0,
    };
    let mut guarded = mixed(Method::Exact, Some(Guard::default()));
    let mut unguarded = mixed(Method::Exact, None);
    assert!(unguarded.guard().is_none());
    for _ in 0..120 {
        guarded.step_frame(&shake);
        unguarded.step_frame(&shake);
        assert!(guarded.last_guard_resets().is_empty());
    }
    assert_eq!(guarded.guard_reset_count(), 0);
    assert_eq!(states(&guarded, 0..5), states(&unguarded, 0..5));
}

#[test]
fn a_guard_switched_back_on_judges_the_frame_it_sees_not_one_it_missed() {
    // The same healthy shake as above, its guard off for 45 frames in the
    // middle: switched back on, it judges the frames it sees, from the
    // state it starts from, and steps in no more than when it was on
    // throughout (nothing).
    let shake = Oscillation {
        axis: DVec3::new(0.2, 1.0, 0.1),
        amplitude_rad: 0.3,
        frequency_hz: 1.0,
    };
    let mut system = mixed(Method::Exact, Some(Guard::default()));
    for frame in 0..150 {
        match frame {
            30 => system.set_guard(None),
            75 => system.set_guard(Some(Guard::default())),
            _ => {}
        }
        system.step_frame(&shake);
        assert!(
            system.last_guard_events().is_empty(),
            "frame {frame}: {:?}",
            system.last_guard_events()
        );
    }
    assert_eq!(system.guard_reset_count(), 0);
}

/// The GPU engine's device holds the frame's end the engine reports, the
/// guard's recoveries included (a renderer draws from it,
/// `gpu::curves`): after every frame of the Block-diagonal blow-up, the
/// device's state is the batch system's, bit for bit.
#[cfg(feature = "gpu")]
#[test]
fn the_gpu_engine_device_holds_the_state_the_guard_left() {
    use std::sync::Arc;

    use helixhair_physics::StrandModel;
    use helixhair_physics::engine::GpuSide;

    if helixhair_gpu::context_or_skip("the GPU engine's device after the guard").is_none() {
        return;
    }
    let still = at_rest(glam::DMat3::IDENTITY);
    let mut system = exploding_curls(Some(Guard::default()));
    let model = Arc::new(
        StrandModel::new(&hanging_curl(10), system.settings().quadrature_points)
            .expect("valid params"),
    );
    let strands = vec![
        (model.clone(), horizontal_root()),
        (model, horizontal_root()),
    ];
    let mut side = GpuSide::new();
    let (mut event_frames, mut elsewhere_frames) = (0, 0);
    for frame in 0..120 {
        side.step_frame(&mut system, &strands, &still);
        event_frames += usize::from(!system.last_guard_events().is_empty());
        elsewhere_frames += usize::from(system.state_is_elsewhere());
        let device = side.device().expect("the device builds");
        let (q, v) = device.read_state().expect("reads back");
        // After a frame the guard changed, the state it left is here and on
        // the device; otherwise only on the device, where readers find it.
        if !system.last_guard_events().is_empty() {
            assert!(
                !system.state_is_elsewhere(),
                "frame {frame}: the retry's state"
            );
        }
        assert_eq!((q, v), side.current(&system).state_flat(), "frame {frame}");
    }
    assert!(event_frames > 0, "the guard never stepped in");
    assert!(elsewhere_frames > 0, "every frame read the state back");
}
