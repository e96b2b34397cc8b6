//! The step's generic code ([`helixhair_physics::batch`]) at f64, one
//! strand wide, against the reference's assembled arrangement
//! ([`helixhair_physics::step::solve`]): Dense's Cholesky of the whole
//! assembled matrix for Exact, the assembled matrix's diagonal blocks for
//! Block-diagonal. The same equations in two arrangements (frames carried
//! as angular velocities against matrix jets; suffix sums against
//! assembled blocks), so at f64 they must agree to round-off. This is what
//! lets the f64 instance of the generic step be the reference engine's
//! Exact and Block-diagonal ([`helixhair_physics::step::generic`]).

use crate::common::{Rng, moving_root, params, random_strains};
use glam::{DMat3, DVec3};
use helixhair_physics::batch::forward::NoContact;
use helixhair_physics::batch::layout::{ElementData, RootMotion, StepEnv};
use helixhair_physics::batch::step::block_diagonal::step_block_diagonal_with;
use helixhair_physics::batch::step::exact::{Elimination, step_exact_with};
use helixhair_physics::batch::step::implicit::{Krylov, step_exact_implicit};
use helixhair_physics::batch::vec::V3;
use helixhair_physics::{
    Method, NaturalShape, RigidMotion, RootPose, StepScheme, Strand, StrandModel, StrandParams,
};
use std::sync::Arc;

/// One step from the same state: max |Δv_generic − Δv_assembled| over
/// max |Δv_assembled|. Both run in f64; they differ in the order of
/// operations and in where the helix coefficients switch from series to
/// closed form (y = 4 against y = 16), each accurate to about 1e-15
/// relative, which the step matrix's conditioning (a straight strand's
/// twist rows carry almost no inertia) amplifies. Measured: at most 2e-13
/// (the 30 cm straight strand).
const ONE_STEP_TOL: f64 = 1e-9;
/// Exact's velocity-implicit step against Dense's direct solve of the
/// same non-symmetric matrix: GMRES stops at a residual of 1e-5 of the
/// right-hand side (`GMRES_TOLERANCE`), so the two differ by about that
/// much of |Δv| times the preconditioned matrix's conditioning. Measured:
/// at most 4.1e-5.
const GMRES_STOP_TOL: f64 = 1e-4;

const H_SECS: f64 = 1.0 / 60.0;
const GRAVITY: DVec3 = DVec3::new(0.0, -9.81, 0.0);
const AIR: DVec3 = DVec3::new(0.3, 0.0, -0.1);

fn shapes() -> Vec<(&'static str, StrandParams)> {
    let mut out = Vec::new();
    for (name, shape, length_m, elements) in [
        ("straight", NaturalShape::Straight, 0.3, 10),
        (
            "curl",
            NaturalShape::Uniform {
                twist_per_m: 5.0,
                curvature1_per_m: 40.0,
                curvature2_per_m: -10.0,
            },
            0.2,
            8,
        ),
        (
            "helix",
            NaturalShape::Helix {
                radius_m: 0.01,
                step_m: 0.02,
            },
            0.25,
            12,
        ),
    ] {
        let mut p = params(length_m, elements);
        p.natural_shape = shape;
        p.internal_friction = 2e-11;
        p.air_drag = 3e-5;
        out.push((name, p));
    }
    out
}

fn lanes(x: &[DVec3]) -> Vec<V3<f64>> {
    x.iter().map(|d| V3::new(d.x, d.y, d.z)).collect()
}

fn back(x: &[V3<f64>]) -> Vec<DVec3> {
    x.iter().map(|d| DVec3::new(d.x, d.y, d.z)).collect()
}

fn relative_gap(a: &[DVec3], b: &[DVec3], v0: &[DVec3]) -> f64 {
    let scale = b
        .iter()
        .zip(v0)
        .map(|(x, y)| (*x - *y).abs().max_element())
        .fold(0.0, f64::max);
    let gap = a
        .iter()
        .zip(b)
        .map(|(x, y)| (*x - *y).abs().max_element())
        .fold(0.0, f64::max);
    gap / scale
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Step {
    Exact,
    ExactImplicit,
    BlockDiagonal,
}

/// The generic step at f64 on `model` from (q, v).
fn generic(
    model: &StrandModel,
    root: &RigidMotion,
    step: Step,
    q: &[DVec3],
    v: &[DVec3],
) -> Vec<DVec3> {
    let n = q.len();
    let env = StepEnv {
        h_secs: H_SECS,
        gravity_m_per_s2: GRAVITY.to_array(),
        air_velocity_m_per_s: AIR.to_array(),
    };
    let root = RootMotion::<f64>::gather(std::slice::from_ref(root));
    let (mut q, mut v) = (lanes(q), lanes(v));
    let mut scratch = vec![ElementData::<f64>::zero(); n];
    let mut elimination = vec![Elimination::<f64>::zero(); n];
    match step {
        Step::Exact => step_exact_with::<f64, true, _>(
            model,
            &env,
            &root,
            &mut q,
            &mut v,
            &mut scratch,
            &mut elimination,
            &NoContact,
        ),
        Step::ExactImplicit => {
            let mut krylov = Krylov::new(n, 8);
            step_exact_implicit(
                model,
                &env,
                &root,
                &mut q,
                &mut v,
                &mut scratch,
                &mut elimination,
                &mut krylov,
                &NoContact,
            );
        }
        Step::BlockDiagonal => step_block_diagonal_with::<f64, true, _>(
            model,
            &env,
            &root,
            &mut q,
            &mut v,
            &mut scratch,
            &NoContact,
        ),
    }
    back(&v)
}

/// The reference's step from (q, v).
fn reference(
    model: &Arc<StrandModel>,
    root: &RigidMotion,
    step: Step,
    q: &[DVec3],
    v: &[DVec3],
) -> Vec<DVec3> {
    let (method, scheme) = match step {
        Step::Exact => (Method::Dense, StepScheme::VelocityExplicit),
        // Dense factors the whole matrix, G included, whatever the count.
        Step::ExactImplicit => (
            Method::Dense,
            StepScheme::VelocityImplicit { corrections: 1 },
        ),
        Step::BlockDiagonal => (Method::BlockDiagonal, StepScheme::VelocityExplicit),
    };
    let pose = RootPose::from_direction(DVec3::ZERO, DVec3::X, DVec3::Y);
    let mut strand = Strand::new(model.clone(), pose, method);
    if step == Step::BlockDiagonal {
        strand.use_assembled_block_diagonal();
    }
    strand.set_scheme(scheme);
    strand.set_state(q, v);
    strand.step(root, GRAVITY, AIR, H_SECS);
    strand.v().to_vec()
}

#[test]
fn the_generic_step_at_f64_is_the_assembled_step() {
    let mut rng = Rng::new(33);
    let (mut worst, mut worst_implicit): (f64, f64) = (0.0, 0.0);
    for (name, p) in shapes() {
        let model = Arc::new(StrandModel::new(&p, 4).expect("valid"));
        for step in [Step::Exact, Step::ExactImplicit, Step::BlockDiagonal] {
            for trial in 0..3 {
                let n = model.elements();
                let q: Vec<DVec3> = model
                    .natural
                    .iter()
                    .zip(random_strains(&mut rng, n, 5.0))
                    .map(|(k, d)| *k + d)
                    .collect();
                let v = random_strains(&mut rng, n, 20.0);
                let root = if trial == 0 {
                    RigidMotion::at_rest(DVec3::ZERO, DMat3::IDENTITY)
                } else {
                    moving_root(&mut rng)
                };
                let a = generic(&model, &root, step, &q, &v);
                let b = reference(&model, &root, step, &q, &v);
                let gap = relative_gap(&a, &b, &v);
                eprintln!("{name} {step:?} trial {trial}: {gap:.2e} of |Δv|");
                if step == Step::ExactImplicit {
                    worst_implicit = worst_implicit.max(gap);
                } else {
                    worst = worst.max(gap);
                }
            }
        }
    }
    assert!(worst < ONE_STEP_TOL, "worst {worst:.2e}");
    assert!(
        worst_implicit < GMRES_STOP_TOL,
        "Exact, velocity-implicit: {worst_implicit:.2e}"
    );
}
