//! Settings shared by every strand of a hair system: the solver, the time
//! step and the gravity.

use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::collision::ContactSettings;
use crate::error::ParamError;
use crate::error::check_range;
use crate::volume::InteractionSettings;

/// How the step matrix (M + hC + h²K) Δv = rhs is solved; see `docs/physics.md`
/// section 5 and [`crate::step::solve`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Method {
    /// The full 3N×3N mass matrix, Cholesky-factored: O(N³), the reference.
    Dense,
    /// The seed paper's method, "subtree" reading: keep only the diagonal
    /// 3×3 blocks of the true mass matrix (the inertia of everything element
    /// Q moves). O(N), each element independent.
    BlockDiagonal,
    /// The seed paper's method, "own element" reading: each block holds the
    /// inertia of the element's own mass only; forces still gather
    /// everything beyond.
    BlockDiagonalOwnElement,
    /// The true step matrix solved in O(N) by a tip-to-root recursion
    /// (Bertails 2009 style); equal to Dense to round-off.
    #[default]
    Exact,
    /// Conjugate gradients on the true step matrix, preconditioned by the
    /// Block-diagonal blocks: O(kN); 0 iterations is Block-diagonal.
    Iterative {
        /// CG iterations per step, 0..=1000.
        iterations: u32,
    },
}

/// Most CG iterations a style may ask for.
pub const MAX_ITERATIONS: u32 = 1000;

/// Iterations of `Method::Iterative` when a name gives none.
pub const DEFAULT_ITERATIONS: u32 = 4;

impl Method {
    /// One of each method (Iterative with its default count), for sweeps
    /// and help texts.
    pub const ALL: [Method; 5] = [
        Method::Dense,
        Method::BlockDiagonal,
        Method::BlockDiagonalOwnElement,
        Method::Exact,
        Method::Iterative {
            iterations: DEFAULT_ITERATIONS,
        },
    ];

    /// Short name of the method family, used on the command line and in
    /// output files; see [`Method::label`] for the full setting.
    pub fn name(self) -> &'static str {
        match self {
            Method::Dense => "dense",
            Method::BlockDiagonal => "block",
            Method::BlockDiagonalOwnElement => "block-own",
            Method::Exact => "exact",
            Method::Iterative { .. } => "iterative",
        }
    }

    /// The name with its setting: `iterative:4` for four CG iterations.
    pub fn label(self) -> String {
        match self {
            Method::Iterative { iterations } => format!("iterative:{iterations}"),
            other => other.name().to_owned(),
        }
    }

    /// Parses a [`Method::name`] or [`Method::label`] (`iterative` alone
    /// means [`DEFAULT_ITERATIONS`]).
    pub fn from_name(name: &str) -> Option<Method> {
        if let Some(count) = name.strip_prefix("iterative:") {
            let iterations = count.parse().ok().filter(|k| *k <= MAX_ITERATIONS)?;
            return Some(Method::Iterative { iterations });
        }
        Method::ALL.into_iter().find(|m| m.name() == name)
    }
}

/// Settings of the time integration, shared by all strands.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SimSettings {
    /// Solver for the step matrix. Default Exact: Dense's answer (to
    /// round-off) at O(N) cost, a little dearer than Block-diagonal per
    /// step and far cheaper than Dense as N grows, while Block-diagonal
    /// blows up on a hanging curl at 60 Hz from N = 8 (the measured costs
    /// and failures are in `docs/solvers.md`).
    pub method: Method,
    /// Frame time step in seconds, range [1e-6, 0.1]. Default 1/60 s: one
    /// display frame.
    pub dt_secs: f64,
    /// Substeps per frame, range 1..=64. Default 1: the linearly implicit
    /// step is stable at 60 Hz for the elastic part (`docs/physics.md` section 6).
    pub substeps: u32,
    /// Gravity in m/s², world coordinates (y up). Default (0, −9.81, 0).
    pub gravity_m_per_s2: DVec3,
    /// Velocity of the surrounding air, m/s; drag acts on the strand's
    /// velocity relative to it. Default zero (still air).
    pub air_velocity_m_per_s: DVec3,
    /// Gauss–Legendre points per element for the integrals of mass and
    /// force, range 1..=8. Default 4: exact for straight elements, and the
    /// mass matrix within 1e-4 (relative) of an 8-point rule while an
    /// element turns by up to 4 rad, e.g. a 5 mm coil on 2 cm elements
    /// (measured: 3 points give 8e-4 there, 5 points 3e-6). That is far
    /// below the O(1/N²) discretisation error.
    pub quadrature_points: usize,
    /// How the step treats the forces that depend on the strain rates.
    /// Default velocity-implicit with at most 8 GMRES iterations (see [`StepScheme`]).
    pub scheme: StepScheme,
    /// Hair–hair interaction through a volume grid ([`crate::volume`]).
    /// Default off.
    pub interaction: InteractionSettings,
    /// How hair meets the head's collider: the skin's thickness and the
    /// contact's stiffness ([`ContactSettings`], whose fields say why their
    /// defaults). Both CPU engines step with it.
    pub contact: ContactSettings,
}

/// How a step treats the generalized forces that depend on the strain rates
/// q̇: the centrifugal and Coriolis terms (quadratic in q̇) and the terms
/// linear in q̇ from the root's rotation (`crate::step::velocity_terms`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum StepScheme {
    /// Frozen at the start of the step (Bertails 2006): explicit in q̇.
    /// Kept for comparison: a 30 cm strand under a head shake blows up at
    /// 1/60 s with every solver.
    VelocityExplicit,
    /// Their derivative G = −∂Q/∂q̇ joins the step matrix. Dense factors
    /// the whole non-symmetric matrix (LU); Exact and Iterative keep their
    /// own symmetric matrix P = s M̃ + D and run at most `corrections`
    /// GMRES iterations preconditioned by it, matrix-free (each one product
    /// G x, a jet sweep, and one solve with the factors they already have),
    /// stopping once the residual is below 1e-5 of the right-hand side
    /// (`gmres::GMRES_TOLERANCE`).
    /// Block-diagonal runs the same GMRES with its own P = s M_bd + D and
    /// the derivative of its own Lagrangian's velocity terms
    /// (`batch::block_terms`), on both engines.
    VelocityImplicit {
        /// Most GMRES iterations per step, range 0..=8 (0 is the explicit
        /// answer). Default 8: a 0.66 m curl needs up to 8 to stop gaining
        /// energy (with 1–3 it gained some on a few frames); most steps stop
        /// after 1 or 2.
        corrections: u32,
    },
}

impl Default for StepScheme {
    fn default() -> Self {
        StepScheme::VelocityImplicit { corrections: 8 }
    }
}

/// Largest number of velocity corrections a step may run.
pub const MAX_VELOCITY_CORRECTIONS: u32 = 8;

impl Default for SimSettings {
    fn default() -> Self {
        Self {
            method: Method::default(),
            dt_secs: 1.0 / 60.0,
            substeps: 1,
            gravity_m_per_s2: DVec3::new(0.0, -9.81, 0.0),
            air_velocity_m_per_s: DVec3::ZERO,
            quadrature_points: 4,
            scheme: StepScheme::default(),
            interaction: InteractionSettings::default(),
            contact: ContactSettings::default(),
        }
    }
}

impl SimSettings {
    /// Checks every field; the error names the offending field.
    pub fn validate(&self) -> Result<(), ParamError> {
        check_range("dt_secs", self.dt_secs, 1e-6, 0.1)?;
        if let Method::Iterative { iterations } = self.method
            && iterations > MAX_ITERATIONS
        {
            return Err(ParamError::new(
                "method.iterations",
                f64::from(iterations),
                format!("must lie in 0..={MAX_ITERATIONS}"),
            ));
        }
        if self.substeps == 0 || self.substeps > 64 {
            return Err(ParamError::new(
                "substeps",
                f64::from(self.substeps),
                "must lie in 1..=64",
            ));
        }
        for (i, g) in self.gravity_m_per_s2.to_array().into_iter().enumerate() {
            check_range(&format!("gravity_m_per_s2[{i}]"), g, -1000.0, 1000.0)?;
        }
        for (i, a) in self.air_velocity_m_per_s.to_array().into_iter().enumerate() {
            check_range(&format!("air_velocity_m_per_s[{i}]"), a, -100.0, 100.0)?;
        }
        if self.quadrature_points == 0 || self.quadrature_points > 8 {
            return Err(ParamError::new(
                "quadrature_points",
                self.quadrature_points as f64,
                "must lie in 1..=8",
            ));
        }
        if let StepScheme::VelocityImplicit { corrections } = self.scheme
            && corrections > MAX_VELOCITY_CORRECTIONS
        {
            return Err(ParamError::new(
                "scheme.corrections",
                f64::from(corrections),
                format!("must lie in 0..={MAX_VELOCITY_CORRECTIONS}"),
            ));
        }
        self.interaction.validate()?;
        self.contact.validate()
    }

    /// Substep length h in seconds.
    pub fn substep_secs(&self) -> f64 {
        self.dt_secs / f64::from(self.substeps)
    }
}
