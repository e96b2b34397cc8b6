//! One batch's step: which step the settings ask for ([`BatchStep`]), the
//! buffers it works in ([`Scratch`], kept per thread), and the call that
//! runs it with the head's contact and the hair–hair model's pull as the
//! forward sweep's hook.
//!
//! The buffers are sized by element count and GMRES iterations and made
//! once per thread: a step allocates nothing.

pub mod block_contact;
pub mod block_diagonal;
pub mod block_implicit;
pub mod dense;
pub mod exact;
pub mod implicit;
pub mod load_stiffness;

use std::cell::RefCell;

use super::forward::SampleHook;
use super::lane_model::{Constants, LaneModel};
use super::lanes::{Lanes, Real};
use super::layout::{ElementData, RootMotion, StepEnv};
use super::vec::V3;
use crate::batch::step::block_diagonal::step_block_diagonal_with;
use crate::batch::step::block_implicit::step_block_implicit;
use crate::batch::step::exact::{Elimination, step_exact_with};
use crate::batch::step::implicit::{Krylov, step_exact_implicit};
use crate::batch::volume::pull::{RootVelocity, SamplePull, WithPull};
use crate::settings::{Method, SimSettings, StepScheme};

/// Per-thread step buffers.
pub(super) struct Scratch {
    elements: Vec<ElementData<Lanes>>,
    elimination: Vec<Elimination<Lanes>>,
    /// GMRES's vectors (none without the velocity-implicit Exact step).
    krylov: Krylov<Lanes>,
    /// The element count and GMRES iterations these buffers were made for.
    made_for: (usize, usize),
}

impl Scratch {
    /// Buffers for N elements and `iterations` GMRES iterations.
    fn new(n: usize, iterations: usize) -> Self {
        Self {
            elements: vec![ElementData::zero(); n],
            elimination: vec![Elimination::zero(); n],
            krylov: Krylov::new(n, iterations),
            made_for: (n, iterations),
        }
    }

    /// Runs `f` with this thread's buffers for `n` elements and
    /// `iterations` GMRES iterations, made on the thread's first batch of
    /// that size and kept, on the parallel and the serial path alike:
    /// rayon's `for_each_init` made them afresh for every piece of work it
    /// split off (about 140 a frame on Sintel, 20 KB each, zero-filled). Nothing in a step calls back into rayon,
    /// so the borrow is never taken twice.
    pub(super) fn with_thread_scratch<R>(
        n: usize,
        iterations: usize,
        f: impl FnOnce(&mut Scratch) -> R,
    ) -> R {
        thread_local! {
            static KEPT: RefCell<Vec<Scratch>> = const { RefCell::new(Vec::new()) };
        }
        KEPT.with(|kept| {
            let mut kept = kept.borrow_mut();
            let fits = |s: &Scratch| s.made_for == (n, iterations);
            let index = match kept.iter().position(fits) {
                Some(index) => index,
                None => {
                    kept.push(Scratch::new(n, iterations));
                    kept.len() - 1
                }
            };
            f(&mut kept[index])
        })
    }
}

/// Which step a batch takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum BatchStep {
    /// Block-diagonal, the whole system's velocity terms, explicit.
    BlockDiagonal,
    /// Block-diagonal with its own Lagrangian's velocity terms, implicit,
    /// at most this many GMRES iterations ([`block_implicit`]).
    BlockImplicit(usize),
    /// Exact, velocity terms explicit.
    Exact,
    /// Exact with at most this many GMRES iterations on the velocity terms.
    ExactImplicit(usize),
}

impl BatchStep {
    pub(crate) fn of(settings: &SimSettings) -> Self {
        match (settings.method, settings.scheme) {
            (Method::Exact, StepScheme::VelocityImplicit { corrections }) if corrections > 0 => {
                BatchStep::ExactImplicit(corrections as usize)
            }
            (Method::Exact, _) => BatchStep::Exact,
            (Method::BlockDiagonal, StepScheme::VelocityImplicit { corrections })
                if corrections > 0 =>
            {
                BatchStep::BlockImplicit(corrections as usize)
            }
            _ => BatchStep::BlockDiagonal,
        }
    }

    /// The step the guard retries a failing frame with: Exact, with the
    /// settings' velocity terms ([`crate::batch::retry`]).
    pub(super) fn retry_of(settings: &SimSettings) -> Self {
        Self::of(&SimSettings {
            method: Method::Exact,
            ..*settings
        })
    }

    /// Whether this is a Block-diagonal step (the guard judges it by
    /// Block-diagonal's own energy, and retries it with Exact at the
    /// frame's substeps first).
    pub(super) fn is_block_diagonal(self) -> bool {
        matches!(self, BatchStep::BlockDiagonal | BatchStep::BlockImplicit(_))
    }

    /// GMRES iterations the scratch must hold.
    pub(crate) fn iterations(self) -> usize {
        match self {
            BatchStep::ExactImplicit(k) | BatchStep::BlockImplicit(k) => k,
            _ => 0,
        }
    }
}

/// Bytes of the velocity-implicit buffers per element for `step`: GMRES's
/// basis (k + 1 vectors) and directions (k), Δv, the product and its
/// partial sums; Block-diagonal's own terms add their sweep's record, four
/// vectors of corrections and rates, and the inverted blocks.
pub(super) fn krylov_bytes_per_element(step: BatchStep) -> usize {
    let iterations = step.iterations();
    if iterations == 0 {
        return 0;
    }
    let gmres = (2 * iterations + 3) * std::mem::size_of::<V3<Lanes>>()
        + std::mem::size_of::<super::velocity_terms::OwnProduct<Lanes>>();
    let block = if step.is_block_diagonal() {
        std::mem::size_of::<super::block_terms::BlockElement<Lanes>>()
            + 4 * std::mem::size_of::<V3<Lanes>>()
            + std::mem::size_of::<super::vec::M3<Lanes>>()
    } else {
        0
    };
    gmres + block
}

/// One step of one batch with `hook` at the quadrature samples.
#[expect(
    clippy::too_many_arguments,
    reason = "the step's inputs and buffers, passed through"
)]
#[inline(always)]
fn step_batch_with<H: SampleHook<Lanes>>(
    model: &LaneModel,
    env: &StepEnv,
    root: &RootMotion<Lanes>,
    step: BatchStep,
    q: &mut [V3<Lanes>],
    v: &mut [V3<Lanes>],
    scratch: &mut Scratch,
    hook: &H,
) {
    let Scratch {
        elements,
        elimination,
        krylov,
        made_for: _,
    } = scratch;
    run_step(
        step,
        model,
        env,
        root,
        q,
        v,
        (elements, elimination, krylov),
        hook,
    );
}

/// `step` of the strands in (`q`, `v`) at any width `T` (the batch
/// engine's lanes, or f32 one strand wide for the GPU engine's twin,
/// [`crate::gpu::engine_twin`]), in the step's buffers, with `hook` at
/// the samples; moments about each element's own points. Returns GMRES's
/// iterations (0 for the velocity-explicit steps).
#[expect(
    clippy::too_many_arguments,
    reason = "the step's inputs and buffers, passed through"
)]
#[inline(always)]
pub(crate) fn run_step<T: Real, H: SampleHook<T>>(
    step: BatchStep,
    model: &impl Constants<T>,
    env: &StepEnv,
    root: &RootMotion<T>,
    q: &mut [V3<T>],
    v: &mut [V3<T>],
    (elements, elimination, krylov): (&mut [ElementData<T>], &mut [Elimination<T>], &mut Krylov<T>),
    hook: &H,
) -> usize {
    match step {
        BatchStep::Exact => {
            step_exact_with::<_, true, _>(model, env, root, q, v, elements, elimination, hook);
            0
        }
        BatchStep::ExactImplicit(_) => {
            step_exact_implicit(model, env, root, q, v, elements, elimination, krylov, hook)
        }
        BatchStep::BlockDiagonal => {
            step_block_diagonal_with::<_, true, _>(model, env, root, q, v, elements, hook);
            0
        }
        BatchStep::BlockImplicit(_) => {
            step_block_implicit(model, env, root, q, v, elements, krylov, hook)
        }
    }
}

/// [`step_batch_with`] with the hair–hair model's `pull` added to
/// `hook` when it is on ([`crate::batch::volume::pull`]).
#[expect(
    clippy::too_many_arguments,
    reason = "the step's inputs and buffers, passed through"
)]
#[inline(always)]
pub(super) fn step_pulled<H: SampleHook<Lanes>>(
    model: &LaneModel,
    env: &StepEnv,
    root: &RootMotion<Lanes>,
    step: BatchStep,
    q: &mut [V3<Lanes>],
    v: &mut [V3<Lanes>],
    scratch: &mut Scratch,
    hook: H,
    pull: Option<SamplePull<'_>>,
) {
    match pull {
        Some(pull) => {
            let pulled = WithPull {
                inner: hook,
                pull,
                root: RootVelocity::of(root),
            };
            step_batch_with(model, env, root, step, q, v, scratch, &pulled);
        }
        None => step_batch_with(model, env, root, step, q, v, scratch, &hook),
    }
}
