//! One linearly implicit step of one strand on the reference engine.
//!
//! Exact and Block-diagonal run the step's generic code at f64
//! ([`generic`]); the other methods (Dense, Iterative, the own-element
//! Block reading) run the assembled arrangement, the pipeline of named
//! stages below.
//!
//! 1. **reconstruct**: shape, velocities, free accelerations and Jacobians
//!    root to tip ([`crate::step::reconstruct`]).
//! 2. **forces**: generalized forces Q by suffix sums ([`crate::step::forces`]).
//! 3. **mass**: mass-matrix data by suffix moments ([`crate::step::mass`]).
//! 4. **solve**: (sM̃ + hγℓ + h²K) Δv = h[Q − K(q − qⁿ) − (γℓ + hK)v − (ν/ρS)Mv]
//!    with the chosen [`crate::step::solve::Solver`] and its mass matrix M̃;
//!    s = 1 + hν/ρS folds the implicit drag, C_drag = (ν/ρS)M, into the mass
//!    term. The right-hand side uses the exact M (matrix-free, O(N)) for
//!    every method, so methods differ only in the matrix they solve.
//! 5. **integrate**: v ← v + Δv, q ← q + h v (docs/physics.md section 5).
//!
//! M and Q are frozen at the start of the step; K and the damping are
//! implicit, so the elastic part is unconditionally stable. With the
//! default [`StepScheme::VelocityImplicit`], the derivative of Q with
//! respect to q̇ (centrifugal, Coriolis and root-rotation terms,
//! [`crate::step::velocity_terms`]) joins the step matrix too: Dense factors the
//! whole non-symmetric matrix, the O(N) solvers correct their answer by a
//! few GMRES iterations inside stage "solve". Stage "reconstruct" then
//! also gives the Jacobians' time derivatives, which make each product
//! G x three prefix sums and a projection.

pub mod forces;
pub mod generic;
pub mod mass;
pub mod reconstruct;
pub mod solve;
pub mod velocity_terms;

use std::time::Instant;

use glam::{DMat3, DVec3};

use crate::batch::vec::V3;
use crate::geometry::helix::outer;
use crate::gmres;
pub use crate::gmres::GMRES_TOLERANCE;
use crate::model::StrandModel;
use crate::settings::{Method, StepScheme};
use crate::step::forces::{ForceInputs, generalized_forces};
use crate::step::generic::{GenericBuffers, is_generic, step_generic};
use crate::step::mass::{MassData, add_sample_weights, mass_blocks, mass_times, scaled};
use crate::step::reconstruct::{Kinematics, reconstruct, reconstruct_with_rates};
use crate::step::solve::{Solver, StepSolver};
use crate::step::velocity_terms::{Derivative, VelocityTerms};

/// Wall time spent in each stage, seconds (summed over strands and steps).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StageTimes {
    /// Stage "reconstruct".
    pub reconstruct_secs: f64,
    /// Stage "forces".
    pub forces_secs: f64,
    /// Stage "mass".
    pub mass_secs: f64,
    /// Stage "solve"; for Exact and Block-diagonal the whole generic step,
    /// whose stages are fused into its sweeps ([`generic`]), the others
    /// then zero.
    pub solve_secs: f64,
    /// Stage "integrate".
    pub integrate_secs: f64,
}

impl StageTimes {
    /// Sum of all stages.
    pub fn total_secs(&self) -> f64 {
        self.reconstruct_secs
            + self.forces_secs
            + self.mass_secs
            + self.solve_secs
            + self.integrate_secs
    }

    /// Adds another record stage by stage.
    pub fn accumulate(&mut self, o: &StageTimes) {
        self.reconstruct_secs += o.reconstruct_secs;
        self.forces_secs += o.forces_secs;
        self.mass_secs += o.mass_secs;
        self.solve_secs += o.solve_secs;
        self.integrate_secs += o.integrate_secs;
    }
}

/// Buffers reused from step to step, so stepping allocates nothing.
#[derive(Clone, Debug)]
pub struct StepWorkspace {
    /// Output of stage "reconstruct" for the last step.
    pub kinematics: Kinematics,
    /// Output of stage "mass" for the last step.
    pub mass: MassData,
    /// Generalized forces of the last step.
    pub forces: Vec<DVec3>,
    /// The method the strand steps with.
    pub method: Method,
    /// The assembled arrangement's solver, with its factorisation of the
    /// last step: Dense, Iterative and the own-element Block reading
    /// (`None` for the methods the generic step runs, [`is_generic`]).
    pub solver: Option<Solver>,
    /// How the step treats the velocity-dependent forces.
    pub scheme: StepScheme,
    /// The generic step's buffers (Exact and Block-diagonal).
    generic: GenericBuffers,
    velocity_terms: VelocityTerms,
    gmres: GmresBridge,
    contact_weights: Vec<(usize, DMat3)>,
    step_mass: MassData,
    velocity_product: Vec<DVec3>,
    rhs: Vec<DVec3>,
    delta_v: Vec<DVec3>,
    mass_v: Vec<DVec3>,
    diagonal: Vec<DVec3>,
}

impl StepWorkspace {
    /// Empty buffers and a solver for `method`.
    pub fn new(method: Method) -> Self {
        Self {
            kinematics: Kinematics::default(),
            mass: MassData::default(),
            forces: Vec::new(),
            method,
            solver: if is_generic(method) {
                None
            } else {
                Solver::new(method)
            },
            scheme: StepScheme::default(),
            generic: GenericBuffers::default(),
            velocity_terms: VelocityTerms::default(),
            gmres: GmresBridge::default(),
            contact_weights: Vec::new(),
            step_mass: MassData::default(),
            velocity_product: Vec::new(),
            rhs: Vec::new(),
            delta_v: Vec::new(),
            mass_v: Vec::new(),
            diagonal: Vec::new(),
        }
    }
}

/// Everything outside the strand that a step needs.
#[derive(Clone, Copy, Debug)]
pub struct StepInputs<'a> {
    /// Step length h in seconds.
    pub h_secs: f64,
    /// Forces environment (root motion, gravity, air, external forces).
    pub forces: ForceInputs<'a>,
}

/// Advances `q`, `v` by one step of `inputs.h_secs`.
pub fn step_strand(
    model: &StrandModel,
    q: &mut [DVec3],
    v: &mut [DVec3],
    ws: &mut StepWorkspace,
    inputs: &StepInputs,
) -> StageTimes {
    let n = model.elements();
    let h = inputs.h_secs;
    let mut times = StageTimes::default();
    let Some(mut solver) = ws.solver.take() else {
        // Exact and Block-diagonal: the generic step, whose stages are
        // fused into two sweeps; its time counts as stage "solve".
        let t = Instant::now();
        step_generic(model, ws.method, ws.scheme, q, v, &mut ws.generic, inputs);
        times.solve_secs = t.elapsed().as_secs_f64();
        return times;
    };

    let corrections = match ws.scheme {
        StepScheme::VelocityExplicit => 0,
        StepScheme::VelocityImplicit { corrections } => corrections,
    };
    // The velocity terms' products need the Jacobians' rates; the "own
    // element" Block reading keeps the whole system's terms, explicit.
    let implicit_velocity = corrections > 0 && !matches!(solver, Solver::BlockDiagonal(_));
    let t = Instant::now();
    if implicit_velocity {
        reconstruct_with_rates(model, q, v, inputs.forces.root, &mut ws.kinematics);
    } else {
        reconstruct(model, q, v, inputs.forces.root, &mut ws.kinematics);
    }
    times.reconstruct_secs = t.elapsed().as_secs_f64();

    let t = Instant::now();
    ws.forces.resize(n, DVec3::ZERO);
    generalized_forces(model, &ws.kinematics, &inputs.forces, &mut ws.forces);
    times.forces_secs = t.elapsed().as_secs_f64();

    let t = Instant::now();
    mass_blocks(model, &ws.kinematics, &mut ws.mass);
    times.mass_secs = t.elapsed().as_secs_f64();

    let t = Instant::now();
    // The hair–hair friction is a drag too (crate::volume::friction).
    let volume_rate = inputs.forces.volume.map_or(0.0, |v| v.friction_per_s);
    let drag_rate = model.air_drag / model.mass_per_length + volume_rate;
    ws.diagonal.clear();
    ws.diagonal
        .extend((0..n).map(|e| DVec3::splat(h * model.friction[e]) + h * h * model.stiffness[e]));
    let root = inputs.forces.root;
    let mass_scale = 1.0 + h * drag_rate;
    // Implicit contact: h (h k + c) Jᵀ n nᵀ J joins s M in the step matrix.
    contact_weights(model, &ws.kinematics, inputs, &mut ws.contact_weights);
    let in_contact = !ws.contact_weights.is_empty();
    if in_contact {
        scaled(&ws.mass, mass_scale, &mut ws.step_mass);
        add_sample_weights(
            model,
            &ws.kinematics,
            &ws.contact_weights,
            &mut ws.step_mass,
        );
    }
    let (matrix, scale) = if in_contact {
        (&ws.step_mass, 1.0)
    } else {
        (&ws.mass, mass_scale)
    };
    match &mut solver {
        Solver::Dense(dense) if implicit_velocity => {
            // The reference: h G assembled column by column (3N products,
            // O(N²)) and the whole non-symmetric matrix LU-factored.
            let velocity =
                dense_velocity_matrix(model, &ws.kinematics, q, v, root, &mut ws.velocity_terms, h);
            dense.prepare_with(&ws.kinematics, matrix, scale, &ws.diagonal, Some(velocity));
        }
        solver => solver.prepare(&ws.kinematics, matrix, scale, &ws.diagonal),
    }
    ws.mass_v.resize(n, DVec3::ZERO);
    mass_times(&ws.kinematics, &ws.mass, v, &mut ws.mass_v);
    ws.rhs.clear();
    ws.rhs.extend((0..n).map(|e| {
        let k = model.stiffness[e];
        let elastic = k * (q[e] - model.natural[e]);
        let damping = (DVec3::splat(model.friction[e]) + h * k) * v[e] + drag_rate * ws.mass_v[e];
        h * (ws.forces[e] - elastic - damping)
    }));
    ws.delta_v.resize(n, DVec3::ZERO);
    let matrix = if in_contact { &ws.step_mass } else { &ws.mass };
    solver.solve(&ws.kinematics, matrix, &ws.rhs, &mut ws.delta_v);
    // Iterative corrects by GMRES (Dense factored hG in above).
    if implicit_velocity && !matches!(solver, Solver::Dense(_)) {
        velocity_corrections(
            model,
            q,
            v,
            root,
            h,
            corrections,
            in_contact,
            &mut solver,
            ws,
        );
    }
    ws.solver = Some(solver);
    times.solve_secs = t.elapsed().as_secs_f64();

    let t = Instant::now();
    for ((q, v), dv) in q.iter_mut().zip(v.iter_mut()).zip(&ws.delta_v) {
        *v += *dv;
        *q += h * *v;
    }
    times.integrate_secs = t.elapsed().as_secs_f64();
    times
}

/// h G as a dense 3N×3N matrix, column by column from the matrix-free
/// product (O(N²)): Dense's share of the velocity-implicit step.
fn dense_velocity_matrix(
    model: &StrandModel,
    kin: &Kinematics,
    q: &[DVec3],
    v: &[DVec3],
    root: &crate::motion::RigidMotion,
    terms: &mut VelocityTerms,
    h: f64,
) -> nalgebra::DMatrix<f64> {
    let n = model.elements();
    let mut matrix = nalgebra::DMatrix::zeros(3 * n, 3 * n);
    let mut unit = vec![DVec3::ZERO; n];
    let mut column = vec![DVec3::ZERO; n];
    for j in 0..3 * n {
        unit[j / 3][j % 3] = 1.0;
        terms.apply(
            Derivative::JacobianRates,
            model,
            kin,
            q,
            v,
            root,
            &unit,
            &mut column,
        );
        unit[j / 3][j % 3] = 0.0;
        for (e, c) in column.iter().enumerate() {
            for i in 0..3 {
                matrix[(3 * e + i, j)] = h * c[i];
            }
        }
    }
    matrix
}

/// The velocity-implicit solve (P + hG) Δv = rhs for the O(N) solvers:
/// [`crate::gmres`] (the GMRES the batch engine runs too, here on one f64
/// lane), right-preconditioned by the solver's own P = s M̃ + D
/// (+ contact), matrix-free, at most `corrections` iterations, from
/// Δv₀ = P⁻¹ rhs in `ws.delta_v`, which it corrects.
#[allow(clippy::too_many_arguments)] // the step's state, named as the step names it
fn velocity_corrections(
    model: &StrandModel,
    q: &[DVec3],
    v: &[DVec3],
    root: &crate::motion::RigidMotion,
    h: f64,
    corrections: u32,
    in_contact: bool,
    solver: &mut Solver,
    ws: &mut StepWorkspace,
) {
    let StepWorkspace {
        kinematics,
        mass,
        velocity_terms,
        gmres: bridge,
        step_mass,
        velocity_product,
        rhs,
        delta_v,
        ..
    } = ws;
    let matrix = if in_contact { &*step_mass } else { &*mass };
    let rhs_norm = rhs.iter().map(|r| r.length_squared()).sum::<f64>().sqrt();
    let n = q.len();
    let GmresBridge {
        krylov,
        delta_v: lane_delta_v,
        solve_in,
        solve_out,
        product_in,
    } = bridge;
    lane_delta_v.clear();
    lane_delta_v.extend(delta_v.iter().map(|d| V3::new(d.x, d.y, d.z)));
    for buffer in [
        &mut *solve_in,
        &mut *solve_out,
        &mut *product_in,
        &mut *velocity_product,
    ] {
        buffer.resize(n, DVec3::ZERO);
    }
    gmres::correct(
        corrections as usize,
        h,
        rhs_norm,
        lane_delta_v,
        krylov,
        |b, z| {
            to_dvec3(b, solve_in);
            solver.solve(kinematics, matrix, solve_in, solve_out);
            from_dvec3(solve_out, z);
        },
        |x, out| {
            to_dvec3(x, product_in);
            velocity_terms.apply(
                Derivative::JacobianRates,
                model,
                kinematics,
                q,
                v,
                root,
                product_in,
                velocity_product,
            );
            from_dvec3(velocity_product, out);
        },
    );
    to_dvec3(lane_delta_v, delta_v);
}

/// What the reference's f64 vectors need to run [`gmres::correct`], which
/// works on [`V3`]: its Krylov vectors and Δv in that form, and the f64
/// vectors the solver and the product read and write, kept from step to
/// step so that stepping allocates nothing.
#[derive(Clone, Debug, Default)]
struct GmresBridge {
    krylov: gmres::Krylov<f64>,
    delta_v: Vec<V3<f64>>,
    solve_in: Vec<DVec3>,
    solve_out: Vec<DVec3>,
    product_in: Vec<DVec3>,
}

fn to_dvec3(from: &[V3<f64>], to: &mut [DVec3]) {
    for (t, f) in to.iter_mut().zip(from) {
        *t = DVec3::new(f.x, f.y, f.z);
    }
}

fn from_dvec3(from: &[DVec3], to: &mut [V3<f64>]) {
    for (t, f) in to.iter_mut().zip(from) {
        *t = V3::new(f.x, f.y, f.z);
    }
}

/// The implicit contact's per-sample weights w h (h k + c) n nᵀ, in sample
/// order (empty without a collider or out of contact).
fn contact_weights(
    model: &StrandModel,
    kin: &Kinematics,
    inputs: &StepInputs,
    out: &mut Vec<(usize, DMat3)>,
) {
    out.clear();
    let Some(contact) = &inputs.forces.contact else {
        return;
    };
    let origin = inputs.forces.root.position_m;
    for (i, s) in kin.samples.iter().enumerate() {
        if let Some(push) = contact.implicit_force(
            origin + s.position_m,
            s.velocity_m_per_s,
            model.mass_per_length,
        ) {
            let w = s.weight_m * inputs.h_secs * push.gain;
            out.push((i, outer(push.normal, push.normal) * w));
        }
    }
}
