//! The CPU twin of the GPU engine's one stage, `stage_step`
//! (`shaders/physics/engine.wgsl`): the batch engine's step at f32, one
//! strand wide, with the head's implicit contact ([`LaneContact`]) where
//! there is a collider: Exact ([`step_exact_implicit`], with no GMRES
//! iterations the velocity-explicit step) or Block-diagonal
//! ([`step_block_implicit`]; velocity-explicit,
//! [`step_block_diagonal_with`]), picked as the batch engine picks them.
//! Not a second copy of the step: the very code the batch engine runs in
//! SIMD lanes, instanced at `f32`.

use crate::batch::contact::{LaneContact, NearCells, SkinTest};
use crate::batch::forward::{NoContact, SampleHook};
use crate::batch::layout::{BatchModel, ElementData, RootMotion, StepEnv};
use crate::batch::step::block_diagonal::step_block_diagonal_with;
use crate::batch::step::block_implicit::step_block_implicit;
use crate::batch::step::exact::Elimination;
use crate::batch::step::implicit::{Krylov, step_exact_implicit};
use crate::batch::vec::V3;
use crate::batch::{LANES, Lanes, Real};
use crate::collision::{ContactInputs, SignedDistanceField};
use crate::motion::{RigidMotion, RootPose};
use crate::settings::{Method, SimSettings, StepScheme};

/// The step's buffers for one strand of N elements.
#[derive(Clone, Debug)]
pub struct TwinBuffers {
    scratch: Vec<ElementData<f32>>,
    elimination: Vec<Elimination<f32>>,
    krylov: Krylov<f32>,
}

impl TwinBuffers {
    /// Buffers for N elements and the iterations `settings` asks for.
    pub fn new(n: usize, settings: &SimSettings) -> Self {
        let iterations = match settings.scheme {
            StepScheme::VelocityImplicit { corrections } => corrections as usize,
            StepScheme::VelocityExplicit => 0,
        };
        Self {
            scratch: vec![ElementData::zero(); n],
            elimination: vec![Elimination::zero(); n],
            krylov: Krylov::new(n, iterations),
        }
    }
}

/// WGSL `stage_step` for one strand (`model` rooted at `root`, state `q`,
/// `v`) while the head moves as `head` over the step (its
/// [`crate::HeadTrajectory::step_motion_at`]), with the head `collider`
/// and its near cells if any. Returns GMRES's iterations.
#[expect(
    clippy::too_many_arguments,
    reason = "the strand, the head, the collider and the step's state and buffers"
)]
pub fn stage_step(
    settings: &SimSettings,
    model: &BatchModel,
    root: &RootPose,
    head: &RigidMotion,
    collider: Option<(&SignedDistanceField, &NearCells)>,
    q: &mut [V3<f32>],
    v: &mut [V3<f32>],
    buffers: &mut TwinBuffers,
) -> usize {
    let h_secs = settings.substep_secs();
    let env = StepEnv {
        h_secs,
        gravity_m_per_s2: settings.gravity_m_per_s2.to_array(),
        air_velocity_m_per_s: settings.air_velocity_m_per_s.to_array(),
    };
    let motion = head.carry(root);
    let root_motion = RootMotion::<f32>::gather(std::slice::from_ref(&motion));
    let TwinBuffers {
        scratch,
        elimination,
        krylov,
    } = buffers;
    let contact = collider.map(|(field, near)| {
        let inputs = ContactInputs {
            collider: field,
            head,
            settings: settings.contact,
            h_secs,
        };
        LaneContact::new(
            SkinTest::new(inputs, near),
            Lanes::splat(model.mass_per_length),
            [motion.position_m; LANES],
        )
    });
    let step = TwinStep {
        method: settings.method,
        model,
        env: &env,
        root: &root_motion,
    };
    // One branch per step, as the batch engine takes it: without a
    // collider the sweep has no contact stage at all.
    match contact {
        Some(hook) => step.run(q, v, scratch, elimination, krylov, &hook),
        None => step.run(q, v, scratch, elimination, krylov, &NoContact),
    }
}

/// What one twin step is given besides its state and buffers.
struct TwinStep<'a> {
    method: Method,
    model: &'a BatchModel,
    env: &'a StepEnv,
    root: &'a RootMotion<f32>,
}

impl TwinStep<'_> {
    /// The batch engine's step for the method (its `BatchStep::of`: GMRES
    /// iterations in `krylov`, none for velocity-explicit) with `hook` at
    /// the samples; returns GMRES's iterations.
    fn run<H: SampleHook<f32>>(
        &self,
        q: &mut [V3<f32>],
        v: &mut [V3<f32>],
        scratch: &mut [ElementData<f32>],
        elimination: &mut [Elimination<f32>],
        krylov: &mut Krylov<f32>,
        hook: &H,
    ) -> usize {
        let (model, env, root) = (self.model, self.env, self.root);
        match self.method {
            Method::BlockDiagonal if krylov.iterations() > 0 => {
                step_block_implicit(model, env, root, q, v, scratch, krylov, hook)
            }
            Method::BlockDiagonal => {
                step_block_diagonal_with::<f32, true, H>(model, env, root, q, v, scratch, hook);
                0
            }
            _ => step_exact_implicit(model, env, root, q, v, scratch, elimination, krylov, hook),
        }
    }
}
