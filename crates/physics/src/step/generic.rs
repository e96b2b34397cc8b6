//! The reference engine's Exact and Block-diagonal steps: the step's one
//! generic code ([`crate::batch::step`]) at f64, one strand wide.
//!
//! # Why this way
//!
//! The batch engine runs the step in f32 lanes; the same code instanced
//! at f64 reads the strand's own constants unrounded
//! ([`crate::batch::lane_model::Constants`] for [`StrandModel`]) and is the
//! reference's step to round-off (`tests/f64_instance.rs` measured 1.3e-10
//! of |Δv| against the assembled arrangement this replaced). So Exact and
//! Block-diagonal, explicit and velocity-implicit, are written once; the
//! reference keeps its assembled arrangement ([`crate::step::mass`],
//! [`crate::step::solve`]) only for Dense, the independent check, and for
//! Iterative and the own-element Block reading, which only it offers.
//!
//! # How it works
//!
//! [`ReferenceSamples`] is the forward sweep's hook
//! ([`crate::batch::forward::SampleHook`]) for one strand: at each
//! quadrature sample it adds the user's external force, the hair–hair
//! model's pull (its known part and the drag relative to the head's rigid
//! motion, whose rate joins the mass scale) and the head's implicit
//! contact ([`crate::collision::ContactInputs::implicit_force`]), the same
//! law and the same numbers as the batch engine's hooks. The strains and
//! rates are copied into the generic code's vectors and back: two copies
//! of 3N numbers, nothing next to the step's sweeps.
//!
//! The guard's measure of a strand ([`measure_strand`]) is the shared
//! measure ([`crate::batch::measure`]) at f64 with the same hook: the
//! force it counts is the force the step applied.

use glam::DVec3;

use crate::batch::forward::SampleHook;
use crate::batch::layout::{ElementData, RootMotion, StepEnv};
use crate::batch::measure::{MeasureInputs, MeasureScratch, Touching, measure_state};
use crate::batch::step::block_diagonal::step_block_diagonal_with;
use crate::batch::step::block_implicit::step_block_implicit;
use crate::batch::step::exact::{Elimination, step_exact_with};
use crate::batch::step::implicit::{Krylov, step_exact_implicit};
use crate::batch::vec::V3;
use crate::collision::ContactInputs;
use crate::frame_balance::{KineticEnergy, StrandMeasure};
use crate::model::StrandModel;
use crate::settings::{Method, StepScheme};
use crate::step::StepInputs;
use crate::step::forces::ForceInputs;

/// The generic step's buffers for one strand, sized on its first step.
#[derive(Clone, Debug)]
pub struct GenericBuffers {
    q: Vec<V3<f64>>,
    v: Vec<V3<f64>>,
    elements: Vec<ElementData<f64>>,
    elimination: Vec<Elimination<f64>>,
    krylov: Krylov<f64>,
    /// The element count and GMRES iterations the buffers were made for.
    made_for: (usize, usize),
}

impl Default for GenericBuffers {
    fn default() -> Self {
        Self::new(0, 0)
    }
}

impl GenericBuffers {
    fn new(n: usize, iterations: usize) -> Self {
        Self {
            q: vec![V3::zero(); n],
            v: vec![V3::zero(); n],
            elements: vec![ElementData::zero(); n],
            elimination: vec![Elimination::zero(); n],
            krylov: Krylov::new(n, iterations),
            made_for: (n, iterations),
        }
    }
}

/// Whether the reference steps `method` with the generic code.
pub fn is_generic(method: Method) -> bool {
    matches!(method, Method::Exact | Method::BlockDiagonal)
}

/// Advances `q`, `v` by one step of `inputs.h_secs` with `method` (Exact
/// or Block-diagonal, [`is_generic`]) under `scheme`.
pub fn step_generic(
    model: &StrandModel,
    method: Method,
    scheme: StepScheme,
    q: &mut [DVec3],
    v: &mut [DVec3],
    buffers: &mut GenericBuffers,
    inputs: &StepInputs,
) {
    let n = q.len();
    let iterations = match scheme {
        StepScheme::VelocityImplicit { corrections } => corrections as usize,
        StepScheme::VelocityExplicit => 0,
    };
    if buffers.made_for != (n, iterations) {
        *buffers = GenericBuffers::new(n, iterations);
    }
    let (h_secs, forces) = (inputs.h_secs, &inputs.forces);
    let env = StepEnv {
        h_secs,
        gravity_m_per_s2: forces.gravity_m_per_s2.to_array(),
        air_velocity_m_per_s: forces.air_velocity_m_per_s.to_array(),
    };
    let root = RootMotion::<f64>::gather(std::slice::from_ref(forces.root));
    let hook = ReferenceSamples {
        forces,
        h_secs,
        nodes: model.quadrature.len(),
        mass_per_length: model.mass_per_length,
    };
    let GenericBuffers {
        q: gq,
        v: gv,
        elements: el,
        elimination: elim,
        krylov: kr,
        made_for: _,
    } = buffers;
    copy_into(q, gq, |d| V3::new(d.x, d.y, d.z));
    copy_into(v, gv, |d| V3::new(d.x, d.y, d.z));
    let (env, root) = (&env, &root);
    match (method, iterations > 0) {
        (Method::BlockDiagonal, false) => {
            step_block_diagonal_with::<f64, true, _>(model, env, root, gq, gv, el, &hook);
        }
        (Method::BlockDiagonal, true) => {
            step_block_implicit(model, env, root, gq, gv, el, kr, &hook);
        }
        (_, false) => step_exact_with::<f64, true, _>(model, env, root, gq, gv, el, elim, &hook),
        (_, true) => {
            step_exact_implicit(model, env, root, gq, gv, el, elim, kr, &hook);
        }
    }
    copy_into(gq, q, |g| DVec3::new(g.x, g.y, g.z));
    copy_into(gv, v, |g| DVec3::new(g.x, g.y, g.z));
}

/// The guard's measure of a strand of `model` in state (`q`, `v`) under
/// `forces` (root, gravity, air, the external hook and the hair–hair
/// model's pull; its contact is not read), in contact where `contact`'s
/// implicit push acts. Block-diagonal's own kinetic energy is always
/// summed: the strand may be judged by it whatever it steps with now.
pub fn measure_strand(
    model: &StrandModel,
    q: &[DVec3],
    v: &[DVec3],
    forces: &ForceInputs,
    contact: Option<&ContactInputs>,
) -> StrandMeasure {
    let gq: Vec<V3<f64>> = q.iter().map(|d| v3(*d)).collect();
    let gv: Vec<V3<f64>> = v.iter().map(|d| v3(*d)).collect();
    let env = StepEnv {
        h_secs: 0.0,
        gravity_m_per_s2: forces.gravity_m_per_s2.to_array(),
        air_velocity_m_per_s: forces.air_velocity_m_per_s.to_array(),
    };
    let motions = std::slice::from_ref(forces.root);
    let root = RootMotion::<f64>::gather(motions);
    let hook = ReferenceSamples {
        forces,
        h_secs: 0.0,
        nodes: model.quadrature.len(),
        mass_per_length: model.mass_per_length,
    };
    let (origin, rho_s) = (forces.root.position_m, model.mass_per_length);
    let touching = contact.map(|contact| {
        move |points: &[(V3<f64>, V3<f64>)]| {
            u32::from(points.iter().any(|(r, velocity)| {
                contact
                    .implicit_force(origin + dvec(*r), dvec(*velocity), rho_s)
                    .is_some_and(|push| push.force_n_per_m != DVec3::ZERO)
            }))
        }
    });
    let inputs = MeasureInputs {
        env: &env,
        root: &root,
        motions,
        touching: touching.as_ref().map(|t| t as Touching<'_, f64>),
        judged_by: KineticEnergy::BlockDiagonal,
    };
    let mut scratch = MeasureScratch::default();
    measure_state(model, &gq, &gv, &inputs, &hook, None, &mut scratch).strand(0)
}

/// `to[i] = convert(from[i])`: the strains and rates between the
/// reference's vectors and the generic code's.
fn copy_into<A: Copy, B>(from: &[A], to: &mut [B], convert: impl Fn(A) -> B) {
    for (t, f) in to.iter_mut().zip(from) {
        *t = convert(*f);
    }
}

/// One strand's forces at its quadrature samples beyond gravity, inertia
/// and the air, for the generic step's forward sweep.
struct ReferenceSamples<'a> {
    forces: &'a ForceInputs<'a>,
    h_secs: f64,
    nodes: usize,
    mass_per_length: f64,
}

fn dvec(x: V3<f64>) -> DVec3 {
    DVec3::new(x.x, x.y, x.z)
}

fn v3(x: DVec3) -> V3<f64> {
    V3::new(x.x, x.y, x.z)
}

impl SampleHook<f64> for ReferenceSamples<'_> {
    const SAMPLE_FORCES: bool = true;

    const SAMPLE_CONTACT: bool = true;

    fn sample_contact(
        &self,
        _e: usize,
        _j: usize,
        r: V3<f64>,
        velocity: V3<f64>,
    ) -> Option<(V3<f64>, V3<f64>)> {
        let contact = self.forces.contact.as_ref()?;
        let world = self.forces.root.position_m + dvec(r);
        let push = contact.implicit_force(world, dvec(velocity), self.mass_per_length)?;
        let axis = push.normal * (self.h_secs * push.gain).sqrt();
        Some((v3(push.force_n_per_m), v3(axis)))
    }

    fn drag_rate_per_s(&self) -> f64 {
        self.forces.volume.map_or(0.0, |pull| pull.friction_per_s)
    }

    fn sample_force(&self, e: usize, j: usize, r: V3<f64>, velocity: V3<f64>) -> V3<f64> {
        let i = e * self.nodes + j;
        let mut f = self
            .forces
            .external_n_per_m
            .get(i)
            .copied()
            .unwrap_or(DVec3::ZERO);
        if let Some(pull) = &self.forces.volume {
            let carried = self.forces.root.velocity_at(dvec(r));
            f += pull.force_n_per_m(i, dvec(velocity), carried, self.mass_per_length);
        }
        v3(f)
    }
}
