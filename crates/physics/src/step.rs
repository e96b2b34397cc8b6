//! One linearly implicit step of one strand: the pipeline of named stages.
//!
//! 1. **reconstruct**: shape, velocities, free accelerations and Jacobians
//!    root to tip ([`crate::reconstruct`]).
//! 2. **forces**: generalized forces Q by suffix sums ([`crate::forces`]).
//! 3. **mass**: mass-matrix data by suffix moments ([`crate::mass`]).
//! 4. **solve**: (sM̃ + hγℓ + h²K) Δv = h[Q − K(q − qⁿ) − (γℓ + hK)v − (ν/ρS)Mv]
//!    with the chosen [`crate::solve::Solver`] and its mass matrix M̃;
//!    s = 1 + hν/ρS folds the implicit drag, C_drag = (ν/ρS)M, into the mass
//!    term. The right-hand side uses the exact M (matrix-free, O(N)) for
//!    every method, so methods differ only in the matrix they solve.
//! 5. **integrate**: v ← v + Δv, q ← q + h v (PHYSICS.md section 5).
//!
//! M and Q are frozen at the start of the step; K and the damping are
//! implicit, so the elastic part is unconditionally stable.

use std::time::Instant;

use glam::DVec3;

use crate::forces::{ForceInputs, generalized_forces};
use crate::mass::{MassData, mass_blocks, mass_times};
use crate::model::StrandModel;
use crate::reconstruct::{Kinematics, reconstruct};
use crate::settings::Method;
use crate::solve::{Solver, StepSolver};

/// Wall time spent in each stage, seconds (summed over strands and steps).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StageTimes {
    /// Stage "reconstruct".
    pub reconstruct_secs: f64,
    /// Stage "forces".
    pub forces_secs: f64,
    /// Stage "mass".
    pub mass_secs: f64,
    /// Stage "solve".
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
    /// The solver, with its factorisation of the last step.
    pub solver: Solver,
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
            solver: Solver::new(method),
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

    let t = Instant::now();
    reconstruct(model, q, v, inputs.forces.root, &mut ws.kinematics);
    times.reconstruct_secs = t.elapsed().as_secs_f64();

    let t = Instant::now();
    ws.forces.resize(n, DVec3::ZERO);
    generalized_forces(model, &ws.kinematics, &inputs.forces, &mut ws.forces);
    times.forces_secs = t.elapsed().as_secs_f64();

    let t = Instant::now();
    mass_blocks(model, &ws.kinematics, &mut ws.mass);
    times.mass_secs = t.elapsed().as_secs_f64();

    let t = Instant::now();
    let drag_rate = model.air_drag / model.mass_per_length;
    ws.diagonal.clear();
    ws.diagonal
        .extend((0..n).map(|e| DVec3::splat(h * model.friction[e]) + h * h * model.stiffness[e]));
    ws.solver
        .prepare(&ws.kinematics, &ws.mass, 1.0 + h * drag_rate, &ws.diagonal);
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
    ws.solver
        .solve(&ws.kinematics, &ws.mass, &ws.rhs, &mut ws.delta_v);
    times.solve_secs = t.elapsed().as_secs_f64();

    let t = Instant::now();
    for ((q, v), dv) in q.iter_mut().zip(v.iter_mut()).zip(&ws.delta_v) {
        *v += *dv;
        *q += h * *v;
    }
    times.integrate_secs = t.elapsed().as_secs_f64();
    times
}
