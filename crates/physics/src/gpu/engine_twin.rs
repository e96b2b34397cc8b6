//! The CPU twin of the GPU engine's one stage, `stage_step`
//! (`shaders/physics/engine.wgsl`): the batch engine's step at f32, one
//! strand wide, with the head's implicit contact ([`LaneContact`]) where
//! there is a collider: Exact or Block-diagonal, velocity-implicit or
//! explicit, picked and run by the batch engine's own dispatch
//! (`batch::step::run_step` of `BatchStep::of` the settings).
//! Not a second copy of the step: the very code the batch engine runs in
//! SIMD lanes, instanced at `f32`.

use crate::batch::contact::{LaneContact, NearCells, SkinTest};
use crate::batch::forward::NoContact;
use crate::batch::layout::{BatchModel, ElementData, RootMotion, StepEnv};
use crate::batch::step::exact::Elimination;
use crate::batch::step::implicit::Krylov;
use crate::batch::step::{BatchStep, run_step};
use crate::batch::vec::V3;
use crate::batch::{LANES, Lanes, Real};
use crate::collision::{ContactInputs, SignedDistanceField};
use crate::motion::{RigidMotion, RootPose};
use crate::settings::SimSettings;

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
        let iterations = BatchStep::of(settings).iterations();
        Self {
            scratch: vec![ElementData::zero(); n],
            elimination: vec![Elimination::zero(); n],
            krylov: Krylov::new(n, iterations),
        }
    }
}

/// What a CPU twin of an engine stage takes for one strand, as the kernel
/// sees it: the substep's forces, the root carried by the head, and the
/// head's contact where there is a collider (the batch engine's hook at
/// width one).
pub(crate) struct OneStrand<'a> {
    /// Gravity, air and the substep's h.
    pub env: StepEnv,
    /// The root's motion, as the head carries it.
    pub motion: RigidMotion,
    /// The same, one lane wide.
    pub root_motion: RootMotion<f32>,
    /// The head's contact, if there is a collider.
    pub contact: Option<LaneContact<'a>>,
}

impl<'a> OneStrand<'a> {
    /// Strand `model` rooted at `root`, the head moving as `head`, with the
    /// head `collider` and its near cells if any, under `settings`.
    pub(crate) fn new(
        settings: &SimSettings,
        model: &BatchModel,
        root: &RootPose,
        head: &'a RigidMotion,
        collider: Option<(&'a SignedDistanceField, &'a NearCells)>,
    ) -> Self {
        let h_secs = settings.substep_secs();
        let env = StepEnv {
            h_secs,
            gravity_m_per_s2: settings.gravity_m_per_s2.to_array(),
            air_velocity_m_per_s: settings.air_velocity_m_per_s.to_array(),
        };
        let motion = head.carry(root);
        let root_motion = RootMotion::<f32>::gather(std::slice::from_ref(&motion));
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
        Self {
            env,
            motion,
            root_motion,
            contact,
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
    let OneStrand {
        env,
        root_motion,
        contact,
        ..
    } = OneStrand::new(settings, model, root, head, collider);
    let TwinBuffers {
        scratch,
        elimination,
        krylov,
    } = buffers;
    let step = BatchStep::of(settings);
    let buffers = (&mut scratch[..], &mut elimination[..], krylov);
    // One branch per step, as the batch engine takes it: without a
    // collider the sweep has no contact stage at all.
    match contact {
        Some(hook) => run_step(step, model, &env, &root_motion, q, v, buffers, &hook),
        None => run_step(step, model, &env, &root_motion, q, v, buffers, &NoContact),
    }
}
