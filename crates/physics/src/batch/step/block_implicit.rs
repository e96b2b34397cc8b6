//! Block-diagonal's velocity-implicit step: its own matrix and its own
//! Lagrangian's velocity terms ([`crate::batch::block_terms`]), for every
//! width: the f64 reference's and the f32 batch engine's, written once.
//!
//! # How it works
//!
//! The step solves (P + h G_bd) Δv = rhs, where
//!
//! - P = s M_bd + D (+ the head's contact) + h²K_load is Block-diagonal's
//!   matrix: the diagonal blocks of the whole one, as the explicit step
//!   forms them ([`super::block_diagonal`]), with the stiffness of gravity
//!   and of the root's acceleration ([`super::load_stiffness`]), each
//!   inverted once and kept;
//! - rhs takes the forces of Block-diagonal's own Lagrangian: the forward
//!   sweep's forces plus the correction F_true − F_bd
//!   ([`crate::batch::block_terms`]);
//! - G_bd = G_true − ∂(F_true − F_bd)/∂q̇: the whole system's derivative
//!   ([`crate::batch::velocity_terms::velocity_product`], which holds the
//!   head's gyroscopic and centrifugal terms) less the correction's. The
//!   correction is a polynomial of degree two in the rates, so its
//!   derivative along z is exactly [corr(q̇ + cz) − corr(q̇ − cz)]/2c
//!   (polarisation, two more sweeps per product; c as the velocity
//!   product scales it).
//!
//! GMRES ([`crate::gmres`]) corrects Δv₀ = P⁻¹ rhs, right-preconditioned by
//! P; every stopping test is per lane. Where a sample touches the head,
//! the operator also holds the contact between elements that P's blocks
//! leave out, C − C_bd ([`super::block_contact`]): the step solves
//! (P + C − C_bd + θ h G_bd) Δv = rhs, its contact as implicit as
//! Exact's.
//!
//! # θ: how implicit the velocity terms are
//!
//! The velocity terms enter the operator as θ h G_bd, not h G_bd: the
//! linearly implicit θ-method, which takes them as
//! F(q̇) + θ ∂F/∂q̇ (q̇⁺ − q̇) over the step, with θ = [`BLOCK_THETA`]. Why not θ = 1 (Newton's linearisation,
//! as Exact takes it): Block-diagonal's own velocity terms are quadratic
//! in the rates plus a part linear from the head's turn,
//! F = Γ(q̇, q̇) + L q̇, and ∂F/∂q̇ = 2Γ(q̇, ·) + L doubles the quadratic
//! part. On one mode with F ≈ λ q̇ (λ = Γ(q̇, ·) there), Newton's step
//! multiplies the rate by (1 − hλ)/(1 − 2hλ), singular at hλ = ½: where a
//! strand's rates grow the operator P + hG_bd nears singular, and GMRES's
//! correction multiplied Δv by up to 85 in the failing steps measured
//! (docs/physics.md section 6). With θ the factor is
//! (1 + (1 − 2θ)hλ)/(1 − 2θhλ): θ = ½ takes the quadratic part with one
//! factor old and one new (Picard's linearisation, singular only at
//! hλ = 1) and the head's linear part by the midpoint rule, which neither
//! damps nor amplifies; above ½ both are damped a little.
//!
//! The value is measured, not derived (docs/physics.md section 6):
//! interventions of the guard over the four example styles × still and
//! four head clips, 300 frames at 60 Hz with one substep, batch engine:
//! 25 at θ = 1, 20 at 0.8, 9 at 0.7, **2 at 0.6**, 2 at 0.55; the groomed
//! coily style at one substep 68, 34, 33, **15**, 42, at two substeps 0,
//! 0, 0, **2**, 32. It costs nothing: the operator is only scaled.

use super::block_contact::{add_contact_coupling, any_touching};
use super::implicit::{BlockBuffers, Krylov};
use crate::batch::block_terms::{BlockElement, block_correction};
use crate::batch::forward::{SampleHook, forward_with};
use crate::batch::lane_model::Constants;
use crate::batch::lanes::Real;
use crate::batch::layout::{ElementData, RootMotion, StepEnv};
use crate::batch::step::block_diagonal::blocks_tip_to_root;
use crate::batch::step::load_stiffness::UniformLoad;
use crate::batch::suffix::integrate;
use crate::batch::vec::{M3, V3};
use crate::batch::velocity_terms::{coefficients_of, polarisation_shift, velocity_product};
use crate::gmres;

/// How implicit Block-diagonal's velocity-implicit step takes its velocity
/// terms: the operator's θ h G_bd (module docs). 0.6: the fewest guard
/// interventions measured (module docs); ½ and below let tight coils
/// blow up at two substeps, 1 (Newton) nears a singular operator at one.
pub const BLOCK_THETA: f64 = 0.6;

/// One velocity-implicit Block-diagonal step of every lane's strand, with
/// at most `krylov.iterations()` GMRES iterations; moments about each
/// element's own points. Returns the iterations the batch ran.
#[expect(
    clippy::too_many_arguments,
    reason = "the step's buffers, as in `step_exact_implicit`"
)]
#[inline(always)]
pub fn step_block_implicit<T: Real, H: SampleHook<T>>(
    model: &impl Constants<T>,
    env: &StepEnv,
    root: &RootMotion<T>,
    q: &mut [V3<T>],
    v: &mut [V3<T>],
    scratch: &mut [ElementData<T>],
    krylov: &mut Krylov<T>,
    hook: &H,
) -> usize {
    let n = q.len();
    let Krylov {
        gmres,
        delta_v,
        own,
        coefficients,
        block,
    } = krylov;
    block.size(n);
    coefficients_of(model, q, coefficients);
    forward_with::<T, false, true, H>(model, env, root, q, v, scratch, hook, Some(coefficients));
    let BlockBuffers {
        elements,
        correction,
        shifted_rates,
        plus,
        minus,
        inverse,
        contact_block,
    } = block;
    block_correction(model, root, q, v, coefficients, elements, correction);
    let mut rhs_squared = T::splat(0.0);
    let drag = hook.drag_rate_per_s();
    blocks_tip_to_root::<T, true>(
        model,
        env,
        scratch,
        drag,
        q,
        v,
        Some(correction),
        Some(&UniformLoad::new(
            env.gravity_m_per_s2,
            root.acceleration_m_per_s2,
        )),
        |e, block, contact, rhs, _, _| {
            contact_block[e] = contact;
            inverse[e] = block.inverse();
            delta_v[e] = inverse[e] * rhs;
            rhs_squared = rhs.dot_add(rhs, rhs_squared);
        },
    );
    let touching = any_touching(scratch);
    let theta_h = BLOCK_THETA * env.h_secs;
    let iterations = gmres::correct(
        gmres.iterations(),
        T::splat_f64(theta_h),
        rhs_squared.sqrt(),
        delta_v,
        gmres,
        |b, z| {
            for ((z, b), inv) in z.iter_mut().zip(b).zip(inverse.iter()) {
                *z = *inv * *b;
            }
        },
        |x, out| {
            velocity_product(model, root, q, v, scratch, coefficients, x, own, out);
            // G_bd x = G_true x − (∂corr/∂q̇) x, by polarisation.
            let one = T::splat(1.0);
            let reach = polarisation_shift(v, x);
            for (sign, into) in [(one, &mut *plus), (-one, &mut *minus)] {
                shifted_rates.clear();
                shifted_rates.extend(
                    v.iter()
                        .zip(x.iter())
                        .map(|(v, x)| *v + x.scale(reach * sign)),
                );
                block_correction(model, root, q, shifted_rates, coefficients, elements, into);
            }
            let half_over = one / (reach + reach);
            for ((o, p), m) in out.iter_mut().zip(plus.iter()).zip(minus.iter()) {
                *o = *o - (*p - *m).scale(half_over);
            }
            if touching {
                // GMRES scales the product by θh; the contact is not.
                // `plus` and `minus` are free again: the wrench buffers.
                let scale = T::splat_f64(1.0 / theta_h);
                add_contact_coupling(scratch, contact_block, x, scale, plus, minus, out);
            }
        },
    );
    for ((q, v), dv) in q.iter_mut().zip(v.iter_mut()).zip(delta_v.iter()) {
        integrate(env.h_secs, q, v, *dv);
    }
    iterations
}

/// Empty: Exact's steps never size them.
impl<T> Default for BlockBuffers<T> {
    fn default() -> Self {
        Self {
            elements: Vec::new(),
            correction: Vec::new(),
            shifted_rates: Vec::new(),
            plus: Vec::new(),
            minus: Vec::new(),
            inverse: Vec::new(),
            contact_block: Vec::new(),
        }
    }
}

impl<T: Real> BlockBuffers<T> {
    /// Room for `n` elements (kept once grown: a step allocates nothing
    /// after its thread's first).
    fn size(&mut self, n: usize) {
        self.elements.resize(n, BlockElement::zero());
        for x in [
            &mut self.correction,
            &mut self.shifted_rates,
            &mut self.plus,
            &mut self.minus,
        ] {
            x.resize(n, V3::zero());
        }
        self.inverse.resize(n, M3::zero());
        self.contact_block.resize(n, M3::zero());
    }
}
