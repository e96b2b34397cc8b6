//! How many elements a sag-free import needs for the hair's natural shape:
//! the gravity moment along the polyline.
//!
//! The sag-free solve ([`super::sag_free`]) makes the fitted shape an exact
//! equilibrium of the N-element strand: each element's natural strains are
//! its fitted ones less the mean gravity moment over it, divided by the
//! stiffness, q⁰ = q − K⁻¹Q. That is the hair's natural shape only as far
//! as the fitted strains are the hung curvature's means over each element.
//! A hanging strand's curvature is not uniform along an element: the
//! moment of the weight beyond a point falls from root to tip. An element
//! of uniform curvature fitted to positions bends to match them where it
//! can, and its end tangent misses the curve's by about ℓ²|M′|/EI; the
//! next element makes up for it in the hung shape, but not in the natural
//! one, where gravity is gone. Those misses grow with the moment and fall
//! as 1/N², and the position tolerance does not see them: a heavy strand
//! fitted within 0.5% of its length at 3 or 4 elements relaxes 3 to 8% of
//! its length from its true natural shape.
//!
//! The measure of the load is the **sag rotation** Θ = ∫|M(s)|/EI ds (the
//! angle by which gravity bends the whole strand), with M(s) the moment
//! about the point at s of the weight beyond it, summed along the
//! polyline as it hangs: the same strand needs more elements held out
//! sideways than hanging straight down, where the moment vanishes. The
//! natural shape's error is then e ≈ C Θ/N² of the length, and the fit
//! starts its search over N at N = ⌈√(CΘ/e)⌉ for the tolerance e asked
//! ([`super::FitOptions::natural_tolerance_over_length`]).
//!
//! The root's tangent is not the cause: the fit turns the root by 0.07 to
//! 0.11 rad at 3 or 4 elements, but fixing it at the true tangent lowers
//! the natural shape's error by a sixth at most at the same N (the curled
//! and helical strands below, N = 2 to 20), where a factor of 3 to 8 is
//! needed; so the root stays free and the elements do the work.
//!
//! The head's push is left out of Θ (the polyline alone does not say where
//! it rests on the head): a strand lying on the scalp counts as held out,
//! which errs towards more elements.

use glam::DVec3;

use crate::params::StrandParams;

/// The constant C of e ≈ CΘ/N² (e over the strand's length, Θ in
/// radians). Heavy 10 cm strands (ρS g L³/EI = 2, 5, 10, 20 and 40)
/// settled by the reference's Dense step at 20 elements and sampled at 32
/// points, with a straight, a curled (20 m⁻¹) and a helical (2 cm)
/// natural shape, give C from 0.09 to 0.83 over N = 3 to 16 (highest for
/// the heaviest curl, whose sag is far from linear); 0.9 bounds them all.
pub const NATURAL_SHAPE_ERROR_CONSTANT: f64 = 0.9;

/// Gravity's load over the softer bending stiffness, ρS g / min(EI₁, EI₂),
/// in m⁻³: what [`super::FitOptions::sag_load_per_m3`] wants for a strand of
/// `params` under `gravity_m_per_s2`. The softer direction sags most, so
/// it sets the count.
pub fn sag_load_per_m3(params: &StrandParams, gravity_m_per_s2: DVec3) -> DVec3 {
    let [_, ei1, ei2] = params.stiffness();
    gravity_m_per_s2 * (params.mass_per_length() / ei1.min(ei2))
}

/// Θ = ∫|M(s)|/EI ds along the polyline, radians, with `load_per_m3` =
/// ρS g / EI. Each point carries the weight of half its two chords, and
/// the moment at point i is (Σ_{j>i} w_j (P_j − P_i)) × load, summed from
/// the tip in one pass.
pub fn sag_rotation(points_m: &[DVec3], load_per_m3: DVec3) -> f64 {
    let chord = |j: usize| {
        if j + 1 < points_m.len() {
            (points_m[j + 1] - points_m[j]).length()
        } else {
            0.0
        }
    };
    let weight = |j: usize| 0.5 * (if j > 0 { chord(j - 1) } else { 0.0 } + chord(j));
    let (mut first_moment, mut total) = (DVec3::ZERO, 0.0);
    let mut theta = 0.0;
    for (i, p) in points_m.iter().enumerate().rev() {
        let moment = (first_moment - *p * total).cross(load_per_m3);
        let w = weight(i);
        theta += moment.length() * w;
        first_moment += *p * w;
        total += w;
    }
    theta
}

/// Fewest elements whose natural shape is within
/// `natural_tolerance_over_length` under `load_per_m3` = ρS g / EI (1
/// without a load); see the module docs.
pub fn elements_for_sag(
    points_m: &[DVec3],
    load_per_m3: DVec3,
    natural_tolerance_over_length: f64,
) -> usize {
    if load_per_m3 == DVec3::ZERO {
        return 1;
    }
    let theta = sag_rotation(points_m, load_per_m3);
    let n = (NATURAL_SHAPE_ERROR_CONSTANT * theta / natural_tolerance_over_length)
        .sqrt()
        .ceil();
    if n.is_finite() && n >= 1.0 {
        // Past the element limit the cap applies anyway.
        n.min(crate::params::MAX_ELEMENTS as f64) as usize
    } else {
        1
    }
}
