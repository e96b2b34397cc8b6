//! The hair–hair model (`helixhair_physics::volume`) on the batch engine:
//! its known answers first (the friction in the step is air drag toward
//! the grid velocity, so relative motion decays with time constant 1/μ; a
//! compressed bundle is pushed apart; the rest pose feels nothing; the
//! guard counts the model's work), then its agreement with the f64
//! reference running the same model.

use crate::common;

use common::shake_scene::ShakeThenStill;
use common::volume_scene::{assert_calms_down, kinetic_after_shake, small_head};
use common::{Rng, max_diff, shake};
use glam::{DMat3, DVec3};
use helixhair_physics::batch::forward::NoContact;
use helixhair_physics::batch::layout::{BatchModel, ElementData, RootMotion, StepEnv};
use helixhair_physics::batch::step::exact::{Elimination, step_exact_with};
use helixhair_physics::batch::vec::V3;
use helixhair_physics::batch::volume::pull::{RootVelocity, SamplePull, WithPull, friction_rate};
use helixhair_physics::batch::{BatchSystem, LANES, LaneModel, Lanes, Real};
use helixhair_physics::engine::{Engine, EngineKind};
use helixhair_physics::motion::HeadTrajectory;
use helixhair_physics::volume::InteractionSettings;
use helixhair_physics::volume::pair_points::points_per_element;
use helixhair_physics::{
    HairSystem, Method, RigidMotion, RootPose, SimSettings, StepScheme, StrandModel, StrandParams,
};

fn lanes_of(values: &[DVec3]) -> V3<Lanes> {
    V3::new(
        Lanes::from_fn(|l| values[l].x as f32),
        Lanes::from_fn(|l| values[l].y as f32),
        Lanes::from_fn(|l| values[l].z as f32),
    )
}

fn lane(x: V3<Lanes>, l: usize) -> DVec3 {
    DVec3::new(x.x.lane(l).into(), x.y.lane(l).into(), x.z.lane(l).into())
}

/// Two f32 computations of one step, the pull's k − μρS (ṙ − c) against the
/// drag's −ν'(ṙ − v_air'), differ by the rounding of their terms: after
/// a second (60 steps), max |q_pull − q_drag| over the strain scale, and
/// the same for q̇ over max |q̇|. `batch_parity.rs` pins f32 against f64
/// after a second of shake at 2e-5 (TRAJECTORY_TOL); two f32 runs of one
/// equation sit within that.
const SAME_EQUATION_TOL: f64 = 2e-5;

/// The friction in a batch step is exactly air drag toward the grid
/// velocity: 8 strands (one batch, each lane its own random state) on a
/// head that translates (so the head's velocity c is the same at every
/// sample), pulled with rate μ toward a uniform u_rel relative to the
/// head, step like the same strands with drag ν' = ν + μρS toward air of
/// (ν v_air + μρS (u_rel + c))/ν'. With it, the model's relative motion
/// decays as drag's does, (1 + hμ) per step, time constant 1/μ
/// (`tests/volume.rs` pins that law on the grid).
#[test]
fn friction_in_the_batch_step_is_air_drag_toward_the_target() {
    let mut params = common::curl(8);
    params.air_drag = 2e-5;
    let model = StrandModel::new(&params, 4).unwrap();
    let (mu, u, air) = (7.0, DVec3::new(0.1, -0.2, 0.05), DVec3::new(0.3, 0.0, 0.0));
    let rho_s = model.mass_per_length;
    let mut dragged = params.clone();
    dragged.air_drag = params.air_drag + mu * rho_s;
    let air_dragged =
        |head: DVec3| (params.air_drag * air + mu * rho_s * (u + head)) / dragged.air_drag;
    let pulled_model = BatchModel::new(&model);
    let dragged_model = BatchModel::new(&StrandModel::new(&dragged, 4).unwrap());
    let n = pulled_model.elements();
    let env = |air: DVec3| StepEnv {
        h_secs: 1.0 / 60.0,
        gravity_m_per_s2: [0.0, -9.81, 0.0],
        air_velocity_m_per_s: air.to_array(),
    };
    let known = vec![lanes_of(&[rho_s * mu * u; LANES]); n * points_per_element(4)];
    let pull = SamplePull {
        friction_per_s: mu as f32,
        rate: friction_rate(mu as f32, &LaneModel::splat(&pulled_model)),
        known: &known,
        nodes: 4,
    };
    let mut rng = Rng::new(5);
    let start: Vec<V3<Lanes>> = (0..n)
        .map(|e| {
            let lanes: Vec<DVec3> = (0..LANES)
                .map(|_| model.natural[e] + rng.vec3(3.0))
                .collect();
            lanes_of(&lanes)
        })
        .collect();
    let (mut q_pull, mut v_pull) = (start.clone(), vec![V3::zero(); n]);
    let (mut q_drag, mut v_drag) = (start, vec![V3::zero(); n]);
    let mut scratch = vec![ElementData::<Lanes>::zero(); n];
    let mut elimination = vec![Elimination::<Lanes>::zero(); n];
    let roots: Vec<RootPose> = (0..LANES).map(|_| common::horizontal_root()).collect();
    for k in 0..60 {
        let motion = common::side_to_side(k as f64 / 60.0);
        let motions: Vec<RigidMotion> = roots.iter().map(|r| motion.carry(r)).collect();
        let root = RootMotion::<Lanes>::gather(&motions);
        let hook = WithPull {
            inner: NoContact,
            pull,
            root: RootVelocity::of(&root),
        };
        step_exact_with::<_, true, _>(
            &pulled_model,
            &env(air),
            &root,
            &mut q_pull,
            &mut v_pull,
            &mut scratch,
            &mut elimination,
            &hook,
        );
        step_exact_with::<_, true, _>(
            &dragged_model,
            &env(air_dragged(motion.velocity_m_per_s)),
            &root,
            &mut q_drag,
            &mut v_drag,
            &mut scratch,
            &mut elimination,
            &NoContact,
        );
    }
    for l in 0..LANES {
        let pick = |x: &[V3<Lanes>]| x.iter().map(|x| lane(*x, l)).collect::<Vec<_>>();
        let (qp, qd, vp, vd) = (pick(&q_pull), pick(&q_drag), pick(&v_pull), pick(&v_drag));
        let strain_scale = max_diff(&qd, &model.natural);
        let rate_scale = vd.iter().map(|v| v.length()).fold(0.0, f64::max);
        assert!(rate_scale > 0.1, "lane {l} moved: |q̇| = {rate_scale}");
        let (eq, ev) = (
            max_diff(&qp, &qd) / strain_scale,
            max_diff(&vp, &vd) / rate_scale,
        );
        println!("lane {l}: q {eq:.2e}, q̇ {ev:.2e}");
        assert!(eq < SAME_EQUATION_TOL && ev < SAME_EQUATION_TOL, "lane {l}");
    }
}

fn interaction() -> InteractionSettings {
    InteractionSettings {
        enabled: true,
        ..InteractionSettings::default()
    }
}

fn batch(params: &StrandParams, roots: &[RootPose], settings: SimSettings) -> BatchSystem {
    let mut system = BatchSystem::new(settings).unwrap();
    system.add_group(params, roots).unwrap();
    system
}

/// The rest pose splats to its own rest density on the batch engine too:
/// no node is in excess, and with no gravity and a still (turned) head
/// nothing moves, model on. Exactly: with no excess and no motion every
/// force of the step is zero.
#[test]
fn the_rest_pose_feels_no_pressure_on_the_batch_engine() {
    let (params, roots) = small_head(12, 4);
    let mut settings = SimSettings {
        gravity_m_per_s2: DVec3::ZERO,
        ..SimSettings::default()
    };
    settings.interaction = interaction();
    let mut system = batch(&params, &roots, settings);
    let head = RigidMotion::at_rest(DVec3::new(0.1, 1.6, -0.2), DMat3::from_rotation_y(0.7));
    for _ in 0..10 {
        system.step_frame(&head);
    }
    let volume = system.volume().expect("model on");
    assert!(volume.state().field().excess().iter().all(|e| *e == 0.0));
    let natural = StrandModel::new(&params, 4).unwrap().natural;
    for i in 0..roots.len() {
        // The natural strains rounded to f32 once, kept exactly.
        let natural32: Vec<DVec3> = natural.iter().map(|k| k.as_vec3().as_dvec3()).collect();
        assert_eq!(system.q(i), natural32, "strand {i}");
        assert!(system.v(i).iter().all(|v| *v == DVec3::ZERO), "strand {i}");
    }
    assert_eq!(system.guard_reset_count(), 0);
}

/// A bundle of 10 cm straight strands hanging from a 5 × 5 grid of roots
/// 1 cm apart, squeezed (each bent toward the bundle's axis so its tip
/// moves in by 60% of its root's distance): the tips' cells are denser
/// than the rest pose's, and in the first frame the model pushes the outer
/// tips outward, faster than the strands' own elasticity alone does.
/// 25 straight 10 cm strands of 5 elements hanging from a 5 × 5 grid of
/// roots 1 cm apart, and for each the strains that bend it inward so that
/// its tip is drawn toward the axis by 60% of its root's distance (the
/// bend about whichever strain axis, either sign, draws the tips in: tip
/// displacement κL²/2 = 0.6 r).
fn squeezed_bundle() -> (StrandParams, Vec<RootPose>, Vec<Vec<DVec3>>) {
    let params = StrandParams {
        length_m: 0.1,
        elements: 5,
        ..StrandParams::default()
    };
    let roots: Vec<RootPose> = (0..25)
        .map(|i| {
            let p = DVec3::new((i % 5) as f64 - 2.0, 0.0, (i / 5) as f64 - 2.0) * 0.01;
            let outward = if p.length() > 0.0 { p } else { DVec3::X };
            RootPose::from_direction(p, -DVec3::Y, outward)
        })
        .collect();
    let natural = StrandModel::new(&params, 4).unwrap().natural;
    let mut probe = batch(&params, &roots, SimSettings::default());
    let bends = [
        DVec3::X,
        -DVec3::X,
        DVec3::Y,
        -DVec3::Y,
        DVec3::Z,
        -DVec3::Z,
    ];
    let radii: Vec<f64> = bends
        .iter()
        .map(|axis| {
            let q: Vec<DVec3> = natural.iter().map(|k| *k + 10.0 * *axis).collect();
            probe.set_state(24, &q, &vec![DVec3::ZERO; q.len()]);
            tip_radius(&probe, 24)
        })
        .collect();
    let inward = (0..bends.len())
        .min_by(|a, b| radii[*a].total_cmp(&radii[*b]))
        .map(|i| bends[i])
        .unwrap();
    let states = roots
        .iter()
        .map(|root| {
            let kappa = 1.2 * root.position_m.length() / (params.length_m * params.length_m);
            natural.iter().map(|k| *k + kappa * inward).collect()
        })
        .collect();
    (params, roots, states)
}

/// Distance of strand `i`'s tip from the vertical axis, metres.
fn tip_radius(system: &BatchSystem, i: usize) -> f64 {
    let tip = *system.boundary_points_world(i).last().unwrap();
    DVec3::new(tip.x.into(), 0.0, tip.z.into()).length()
}

#[test]
fn a_squeezed_bundle_is_pushed_apart_on_the_batch_engine() {
    let (params, roots, states) = squeezed_bundle();
    let squeezed = |on: bool| {
        let mut settings = SimSettings {
            gravity_m_per_s2: DVec3::ZERO,
            ..SimSettings::default()
        };
        settings.interaction.enabled = on;
        let mut system = batch(&params, &roots, settings);
        for (i, q) in states.iter().enumerate() {
            system.set_state(i, q, &vec![DVec3::ZERO; q.len()]);
        }
        let before: Vec<f64> = (0..roots.len()).map(|i| tip_radius(&system, i)).collect();
        system.step_frame(&RigidMotion::default());
        let after: Vec<f64> = (0..roots.len()).map(|i| tip_radius(&system, i)).collect();
        (system, before, after)
    };
    let (with, before, with_after) = squeezed(true);
    let (_, _, without_after) = squeezed(false);
    let excess = with.volume().unwrap().state().field().excess();
    // Measured 0.67 of the typical rest density over the threshold.
    let most = excess.iter().cloned().fold(0.0, f64::max);
    assert!(most > 0.25, "squeezed above the rest density: {most}");
    for (i, root) in roots.iter().enumerate() {
        if root.position_m.length() < 0.015 {
            continue;
        }
        let pushed = with_after[i] - before[i];
        let elastic = without_after[i] - before[i];
        assert!(
            pushed > elastic,
            "strand {i}: tip moved out {pushed:.3e} m with the model, {elastic:.3e} without"
        );
    }
}

/// Hair that rests away from its natural shape (an imported sag-free
/// groom rests in its groomed shape, which gravity holds) feels no
/// pressure there once told so (`Engine::set_rest_pose`): the squeezed
/// bundle, started and resting squeezed, has no node in excess in its
/// first frame, on either engine, where the same bundle resting in its
/// natural shape is well above its threshold.
#[test]
fn hair_resting_away_from_its_natural_shape_feels_no_pressure_there() {
    let (params, roots, states) = squeezed_bundle();
    let settings = SimSettings {
        gravity_m_per_s2: DVec3::ZERO,
        interaction: interaction(),
        ..SimSettings::default()
    };
    for kind in [EngineKind::Batch, EngineKind::Reference] {
        let most_excess = |told: bool| {
            let mut engine = Engine::new(kind, settings.clone()).unwrap();
            engine.add_group(&params, &roots).unwrap();
            for (i, q) in states.iter().enumerate() {
                engine.set_state(i, q, &vec![DVec3::ZERO; q.len()]);
                if told {
                    engine.set_rest_pose(i, q);
                }
            }
            engine.step_frame(&RigidMotion::default());
            let (_, field) = engine.volume_field().expect("the model ran");
            field.excess().iter().cloned().fold(0.0, f64::max)
        };
        assert_eq!(most_excess(true), 0.0, "{kind:?}: resting where it is");
        let natural = most_excess(false);
        assert!(
            natural > 0.25,
            "{kind:?}: resting in its natural shape: {natural}"
        );
    }
}

/// The batch engine with the model against the reference with the model,
/// after a second of head shake (48 curls, 6 batches), velocity-explicit
/// Exact on both (the scheme `batch_parity.rs` pins): max |q_batch −
/// q_ref| over the strain scale max |q_ref − qⁿ|, as `batch_parity.rs`
/// measures it.
///
/// Tolerance: `batch_parity.rs`'s TRAJECTORY_TOL, 2e-5, for f32 against
/// f64 after a second of shake without the model. The model adds no
/// arithmetic of its own to the batch engine beyond an f32 gather (the
/// grid's splat and read-back are the reference's f64 code), and the
/// gather's round-off (6e-8 of a position, against 2 cm cells) moves a
/// stencil weight by far less than the step's own f32 round-off. The
/// model's own effect on the trajectory (on against off, on the
/// reference) must be far larger than the tolerance, or the agreement
/// would say nothing.
const WITH_MODEL_TRAJECTORY_TOL: f64 = 2e-5;

#[test]
fn the_batch_engine_agrees_with_the_reference_with_the_model_on() {
    // Four quadrature nodes (two points per element) and three (a pair
    // and a lone node: `volume::pair_points`).
    for points in [4, 3] {
        let (agreement, effect) = agreement_with_the_model_on(points);
        println!(
            "{points} nodes: batch against reference, model on: {agreement:.2e}; model's effect {effect:.2e}"
        );
        assert!(effect > 100.0 * WITH_MODEL_TRAJECTORY_TOL, "{effect:.2e}");
        assert!(agreement < WITH_MODEL_TRAJECTORY_TOL, "{agreement:.2e}");
    }
}

/// The small head shaken 1 s on both engines with `points` quadrature
/// nodes, the model on: the batch engine's largest difference from the
/// reference and the model's own effect on the reference, both over the
/// strain scale.
fn agreement_with_the_model_on(points: usize) -> (f64, f64) {
    let (params, roots) = small_head(12, 4);
    let settings = |on: bool| {
        let mut s = SimSettings {
            method: Method::Exact,
            scheme: StepScheme::VelocityExplicit,
            quadrature_points: points,
            ..SimSettings::default()
        };
        // Stronger than the defaults, so that the model shapes the motion.
        s.interaction = InteractionSettings {
            enabled: on,
            friction_per_s: 20.0,
            pressure_m2_per_s2: 1.0,
            ..InteractionSettings::default()
        };
        s
    };
    let reference = |on: bool| {
        let mut system = HairSystem::new(settings(on)).unwrap();
        system.set_guard(None);
        system.add_group(&params, &roots).unwrap();
        system
    };
    let (mut with, mut without) = (reference(true), reference(false));
    let mut fast = batch(&params, &roots, settings(true));
    fast.set_guard(None);
    let head = shake();
    for _ in 0..60 {
        with.step_frame(&head);
        without.step_frame(&head);
        fast.step_frame(&head);
    }
    let (mut agreement, mut effect): (f64, f64) = (0.0, 0.0);
    for (i, s) in with.strands().iter().enumerate() {
        let scale = max_diff(s.q(), &s.model().natural);
        agreement = agreement.max(max_diff(&fast.q(i), s.q()) / scale);
        effect = effect.max(max_diff(without.strands()[i].q(), s.q()) / scale);
    }
    (agreement, effect)
}

/// The guard's energy balance counts the model's work on the batch engine
/// as on the reference (`volume::balance`): the small head shaken for 4¼
/// periods and then held still, model on, guard on, has no guard event,
/// and its kinetic energy after the shake falls every second and ends
/// below the run without the model.
#[test]
fn a_shake_with_the_model_calms_down_without_guard_events_on_the_batch_engine() {
    let (params, roots) = small_head(12, 4);
    let head = ShakeThenStill::ordinary();
    let kinetic_after = |on: bool| {
        let mut settings = SimSettings::default();
        settings.interaction.enabled = on;
        let mut engine = Engine::new(EngineKind::Batch, settings).unwrap();
        engine.add_group(&params, &roots).unwrap();
        let seconds = kinetic_after_shake(
            &mut engine,
            &head,
            |e, head| e.step_frame(head),
            |e| e.energies().kinetic_j,
        );
        let resets = engine.batch().map_or(0, |b| b.guard_reset_count());
        (seconds, resets)
    };
    let (with, resets) = kinetic_after(true);
    let (without, _) = kinetic_after(false);
    assert_eq!(resets, 0, "guard resets with the model");
    assert_calms_down(&with, &without);
}

/// With the model on, a serial and a parallel batch engine step bit for
/// bit alike: the splat is cut into fixed pieces whatever the thread
/// count (`volume::splat::SPLAT_PIECES`), and the rest is per batch.
#[test]
fn serial_and_parallel_are_bit_identical_with_the_model() {
    let (params, roots) = small_head(12, 4);
    let settings = SimSettings {
        interaction: InteractionSettings {
            enabled: true,
            friction_per_s: 20.0,
            pressure_m2_per_s2: 1.0,
            ..InteractionSettings::default()
        },
        ..SimSettings::default()
    };
    let mut parallel = batch(&params, &roots, settings.clone());
    let mut serial = batch(&params, &roots, settings);
    serial.set_parallel(false);
    let head = shake();
    for _ in 0..30 {
        parallel.step_frame(&head);
        serial.step_frame(&head);
    }
    for i in 0..roots.len() {
        assert_eq!(parallel.q(i), serial.q(i), "strand {i}");
        assert_eq!(parallel.v(i), serial.v(i), "strand {i}");
    }
}

/// Steps `kept` and `swept` (the same system) over `heads` frame by frame,
/// with `swept`'s state set to itself before each frame (exactly: f32 to
/// f64 and back), which marks its measures and kept samples stale, so its
/// gather sweeps every batch; returns, per frame, how many of `kept`'s
/// batches its gather took from kept samples, and of how many.
fn step_kept_and_swept(
    kept: &mut BatchSystem,
    swept: &mut BatchSystem,
    heads: &[&dyn HeadTrajectory],
) -> Vec<(usize, usize)> {
    let mut from_kept = Vec::new();
    for head in heads {
        let (q, v) = (swept.q(0), swept.v(0));
        swept.set_state(0, &q, &v);
        kept.step_frame(*head);
        swept.step_frame(*head);
        let of = |s: &BatchSystem| s.volume().expect("model on").gathered_from_kept();
        assert_eq!(of(swept).0, 0, "the swept system took kept samples");
        from_kept.push(of(kept));
    }
    from_kept
}

/// The model's gather takes the samples the guard's end-of-frame measure
/// kept instead of sweeping the strands again (`batch::volume::KeptSamples`):
/// the same sweep on the same state, so the same bits. Under a shake, a
/// system that takes them from the second frame on steps bit for bit as
/// one that sweeps every frame. And a head that jumps between frames (each
/// frame's trajectory starts where the last one's did not end: turned by
/// 0.3 rad about the vertical, every other frame) is swept, since samples
/// relative to their roots turn with the head: again the same bits.
#[test]
fn the_gather_takes_the_measures_samples_with_the_same_bits() {
    let (params, roots) = small_head(12, 4);
    let settings = SimSettings {
        interaction: interaction(),
        ..SimSettings::default()
    };
    let shake = shake();
    let heads: Vec<&dyn HeadTrajectory> = vec![&shake; 30];
    let mut kept = batch(&params, &roots, settings.clone());
    let mut swept = batch(&params, &roots, settings.clone());
    let from_kept = step_kept_and_swept(&mut kept, &mut swept, &heads);
    assert_eq!(from_kept[0].0, 0, "nothing kept before the first frame");
    assert!(from_kept[0].1 > 1, "more than one batch");
    assert!(
        from_kept[1..].iter().all(|(k, all)| k == all),
        "kept samples not taken: {from_kept:?}"
    );
    let same = |a: &BatchSystem, b: &BatchSystem| {
        for i in 0..roots.len() {
            assert_eq!(a.q(i), b.q(i), "strand {i}");
            assert_eq!(a.v(i), b.v(i), "strand {i}");
        }
        assert_eq!(a.guard_reset_count(), 0);
        assert_eq!(b.guard_reset_count(), 0);
    };
    same(&kept, &swept);

    let straight = RigidMotion::at_rest(DVec3::ZERO, DMat3::IDENTITY);
    let turned = RigidMotion::at_rest(DVec3::ZERO, DMat3::from_rotation_y(0.3));
    let heads: Vec<&dyn HeadTrajectory> = (0..20)
        .map(|k| -> &dyn HeadTrajectory {
            if k % 2 == 0 { &straight } else { &turned }
        })
        .collect();
    let mut kept = batch(&params, &roots, settings.clone());
    let mut swept = batch(&params, &roots, settings);
    let from_kept = step_kept_and_swept(&mut kept, &mut swept, &heads);
    assert!(
        from_kept.iter().all(|(k, _)| *k == 0),
        "samples kept at another head were taken: {from_kept:?}"
    );
    same(&kept, &swept);
}

/// A group added with no strands (an imported groom can have one) takes
/// no part in the model: the small head shaken 30 frames, model and guard
/// on, steps exactly as without it, on either engine. (It panicked on the
/// batch engine, cutting its empty buffers into chunks of zero.)
#[test]
fn a_group_without_strands_changes_nothing_with_the_model_on() {
    let (params, roots) = small_head(12, 4);
    let empty = StrandParams {
        elements: 5,
        ..params.clone()
    };
    let settings = SimSettings {
        method: Method::Exact,
        interaction: interaction(),
        ..SimSettings::default()
    };
    for kind in [EngineKind::Batch, EngineKind::Reference] {
        let run = |with_empty: bool| {
            let mut engine = Engine::new(kind, settings.clone()).unwrap();
            if with_empty {
                engine.add_group(&empty, &[]).unwrap();
            }
            engine.add_group(&params, &roots).unwrap();
            let head = shake();
            for _ in 0..30 {
                engine.step_frame(&head);
            }
            (0..engine.strand_count())
                .map(|i| engine.q(i))
                .collect::<Vec<_>>()
        };
        assert_eq!(run(true), run(false), "{kind:?}");
    }
}
