//! One batch's step: which step the settings ask for ([`BatchStep`]), the
//! buffers it works in ([`Scratch`], kept per thread), and the call that
//! runs it with the head's contact and the hair–hair model's pull as the
//! forward sweep's hook.
//!
//! The buffers are sized by element count and GMRES iterations and made
//! once per thread: a step allocates nothing.

pub mod block_diagonal;
pub mod dense;
pub mod exact;
pub mod implicit;

use std::cell::RefCell;

use super::forward::SampleHook;
use super::lane_model::LaneModel;
use super::lanes::Lanes;
use super::layout::{ElementData, RootMotion, StepEnv};
use super::vec::V3;
use crate::batch::step::block_diagonal::step_block_diagonal_with;
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
pub(super) enum BatchStep {
    /// Block-diagonal, the whole system's velocity terms, explicit (the
    /// reference takes its own Lagrangian's, implicit).
    BlockDiagonal,
    /// Exact, velocity terms explicit.
    Exact,
    /// Exact with at most this many GMRES iterations on the velocity terms.
    ExactImplicit(usize),
}

impl BatchStep {
    pub(super) fn of(settings: &SimSettings) -> Self {
        match (settings.method, settings.scheme) {
            (Method::Exact, StepScheme::VelocityImplicit { corrections }) if corrections > 0 => {
                BatchStep::ExactImplicit(corrections as usize)
            }
            (Method::Exact, _) => BatchStep::Exact,
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

    /// GMRES iterations the scratch must hold.
    pub(super) fn iterations(self) -> usize {
        match self {
            BatchStep::ExactImplicit(k) => k,
            _ => 0,
        }
    }
}

/// Bytes of GMRES buffers per element for `iterations` iterations: the
/// basis (k + 1 vectors), the directions (k), Δv, the product and its
/// partial sums.
pub(super) fn krylov_bytes_per_element(iterations: usize) -> usize {
    if iterations == 0 {
        return 0;
    }
    (2 * iterations + 3) * std::mem::size_of::<V3<Lanes>>()
        + std::mem::size_of::<super::velocity_terms::OwnProduct<Lanes>>()
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
    match step {
        BatchStep::Exact => {
            step_exact_with::<_, true, _>(model, env, root, q, v, elements, elimination, hook);
        }
        BatchStep::ExactImplicit(_) => {
            step_exact_implicit(model, env, root, q, v, elements, elimination, krylov, hook);
        }
        BatchStep::BlockDiagonal => {
            step_block_diagonal_with::<_, true, _>(model, env, root, q, v, elements, hook);
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
