//! Fitting imported curves with Super-Helices, and the rest shape that
//! holds them under gravity.
//!
//! A groom made elsewhere arrives as polylines: points from root to tip.
//! [`fit_polyline`] turns one into a Super-Helix of N equal elements, a
//! root frame and the strains (τ, κ₁, κ₂) of each element, in three steps:
//!
//! 1. an initial guess from the polyline's own turning ([`initial`]): the
//!    discrete parallel-transport frame and the rotation between element
//!    tangents;
//! 2. a Levenberg–Marquardt refinement of every point's distance to the
//!    strand, with the analytic Jacobians of the physics ([`refine`]);
//! 3. the smallest N (up to a cap) whose largest deviation is within a
//!    tolerance, by default 0.5% of the strand's length ([`FitOptions`]),
//!    searched upwards from 1, or, when a sag-free solve follows, from
//!    the count whose natural shape will be within 1% of the hair's
//!    ([`resolution`]: the gravity moment along the polyline decides).
//!
//! [`sag_free`](mod@sag_free) then solves the natural strains q⁰ that make the fitted
//! shape a static equilibrium under gravity (and the head's contact push,
//! by the law of the engine that will step it: [`crate::engine::Engine::rest_contact`]), so
//! an imported groom keeps its shape instead of sagging, and
//! [`sag_free_stiffened`] stiffens a strand whose equilibrium is unstable
//! by the least that holds it. `docs/import.md` teaches all three with the
//! formulas.
//!
//! This module knows no file format: callers pass plain point lists.

pub mod coefficients;
pub mod curve;
pub mod initial;
pub mod normal;
pub mod refine;
pub mod resolution;
pub mod sag_free;
pub mod stiffen;

use glam::DVec3;
use thiserror::Error;

pub use curve::UniformHelixChain;
pub use sag_free::{SagFree, SagFreeInputs, SagFreeStatus, sag_free};
pub use stiffen::{StiffenOptions, StiffenedRest, sag_free_stiffened, stiffness_scale_for_margin};

/// How closely and with how many elements to fit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitOptions {
    /// Largest allowed distance of a polyline point from the fitted strand,
    /// as a fraction of the strand's length. Default 0.005 (0.5%): 1 mm on a
    /// 20 cm strand, under a hair's visible thickness in a groom at arm's
    /// length, while keeping N small (the step costs grow with N).
    pub tolerance_over_length: f64,
    /// Most elements per strand. Default 20: twice the procedural default
    /// (10), enough for the curliest strands of public grooms at 0.5%.
    pub max_elements: usize,
    /// Gravity's load over the bending stiffness, ρS g / EI, in m⁻³, of the
    /// sag-free solve that will follow ([`resolution::sag_load_per_m3`]):
    /// the search over N then starts at the count whose natural shape
    /// meets `natural_tolerance_over_length` ([`resolution`]). Default
    /// zero: no sag-free solve follows, the fitted shape is the natural
    /// one, and the search starts at 1.
    pub sag_load_per_m3: DVec3,
    /// Largest allowed distance of the natural shape (the strand relaxed
    /// without gravity) from the hair's, as a fraction of the strand's
    /// length, with a sag load. Default 0.01 (1%): 2 mm on
    /// a 20 cm strand; it asks for more elements than the position
    /// tolerance alone (Sintel: 7.3 per strand against 4.2).
    pub natural_tolerance_over_length: f64,
}

impl Default for FitOptions {
    fn default() -> Self {
        Self {
            tolerance_over_length: 0.005,
            max_elements: 20,
            sag_load_per_m3: DVec3::ZERO,
            natural_tolerance_over_length: 0.01,
        }
    }
}

/// Why a polyline could not be fitted.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum FitError {
    /// Fewer than two points.
    #[error("a strand needs at least two points, this one has {0}")]
    TooFewPoints(usize),
    /// A coordinate is NaN or infinite.
    #[error("point {0} is not finite")]
    NotFinite(usize),
    /// Two consecutive points coincide (zero-length segment).
    #[error("point {0} coincides with the next one")]
    RepeatedPoint(usize),
    /// The options are out of range.
    #[error("fit options out of range: {0}")]
    Options(&'static str),
}

/// One fitted strand.
#[derive(Clone, Debug, PartialEq)]
pub struct StrandFit {
    /// Root point, the polyline's first point, in the polyline's
    /// coordinates (metres).
    pub root_m: DVec3,
    /// The fitted chain (root frame, element length, strains).
    pub chain: UniformHelixChain,
    /// Largest distance of a polyline point from the strand over the
    /// polyline's length.
    pub error_over_length: f64,
    /// Whether the error is within the tolerance (false: the cap was hit
    /// and this is the cap's fit).
    pub within_tolerance: bool,
    /// The polyline's length (sum of its segments), metres.
    pub polyline_length_m: f64,
}

/// Fits `points_m` (root first, metres) with the smallest N ≤ the cap
/// meeting `options.tolerance_over_length`, and no fewer than the sag
/// load asks for ([`resolution::elements_for_sag`]); n₁ of the root frame
/// is `reference` made orthogonal to the root tangent.
///
/// The cap is also limited by the data: with M + 1 points the fit has 3M
/// equations and 3N + 2 + M unknowns (strains, root tilt, length, and the
/// places of the M − 1 interior points), so N ≤ (2M − 2)/3 (at least 1).
pub fn fit_polyline(
    points_m: &[DVec3],
    reference: DVec3,
    options: &FitOptions,
) -> Result<StrandFit, FitError> {
    check(points_m, options)?;
    let m = points_m.len() - 1;
    let cap = element_cap(m, options);
    let arc = initial::chord_arc_lengths(points_m);
    let length = arc[m];
    let first = resolution::elements_for_sag(
        points_m,
        options.sag_load_per_m3,
        options.natural_tolerance_over_length,
    )
    .min(cap);
    let mut best = None;
    for n in first..=cap {
        let fit = fit_with_elements(points_m, n, reference, &arc, options);
        let error = fit.error_over_length;
        best = Some(fit);
        if error <= options.tolerance_over_length {
            break;
        }
    }
    let fit = best.ok_or(FitError::TooFewPoints(points_m.len()))?;
    let mut fit = relax_twist(points_m, fit, reference, &arc, options);
    fit.within_tolerance = fit.error_over_length <= options.tolerance_over_length;
    fit.polyline_length_m = length;
    Ok(fit)
}

/// Fits `points_m` with exactly `elements` elements (no search over N);
/// `arc` holds the polyline's chord arc lengths. The refinement stops once
/// every point is within a tenth of the tolerance (closer is invisible,
/// and the search over N only needs to know the tolerance is met), or
/// once it crawls within the tolerance, or outside it below the cap,
/// where the search will try a larger N ([`refine::EarlyStop`]).
pub fn fit_with_elements(
    points_m: &[DVec3],
    elements: usize,
    reference: DVec3,
    arc: &[f64],
    options: &FitOptions,
) -> StrandFit {
    let length = *arc.last().unwrap_or(&0.0);
    let start = initial::initial_chain(points_m, elements, reference);
    let tolerance_m = options.tolerance_over_length * length;
    let stop = refine::EarlyStop {
        good_enough_m: 0.1 * tolerance_m,
        tolerance_m,
        last_try: elements >= element_cap(points_m.len() - 1, options),
    };
    let mut refined = refine::refine(points_m, start, arc, &stop, 0.0);
    refine::fix_roll(&mut refined.chain, reference);
    let worst = refined.deviations_m.iter().copied().fold(0.0, f64::max);
    StrandFit {
        root_m: points_m[0],
        chain: refined.chain,
        error_over_length: worst / length,
        within_tolerance: true,
        polyline_length_m: length,
    }
}

/// Each radian of an element's twist costs, in [`relax_twist`], as much as
/// a point this fraction of the strand's length off: a fifth of the
/// default tolerance, so a twist that moves the points less than that is
/// given up, and one the shape needs (a helix's: each radian moves points
/// by a good part of its radius) is kept.
pub const TWIST_WEIGHT_OVER_LENGTH: f64 = 1e-3;

/// The fit with only the twist its shape needs. A polyline carries no
/// material twist, and an element's twist is seen only through its
/// curvature's turn, so on a nearly straight element it is barely
/// observable: a least-squares fit near the data's cap of elements spends
/// it on the polyline's last tenths of a millimetre (Sintel's fitted twists
/// reached hundreds of rad/m on nearly straight strands). The fit is
/// refined again with a penalty on each element's twist angle ℓτ
/// ([`TWIST_WEIGHT_OVER_LENGTH`]) and the result kept if its points stay
/// within the tolerance (or, for a fit outside it, no further out). A
/// polyline a chain reproduces exactly keeps its exact fit: the penalty
/// would move its points further than its tolerance allows.
fn relax_twist(
    points_m: &[DVec3],
    fit: StrandFit,
    reference: DVec3,
    arc: &[f64],
    options: &FitOptions,
) -> StrandFit {
    let length = *arc.last().unwrap_or(&0.0);
    let tolerance_m = options.tolerance_over_length * length;
    let stop = refine::EarlyStop {
        good_enough_m: f64::MIN_POSITIVE,
        tolerance_m,
        last_try: false,
    };
    let weight_m = TWIST_WEIGHT_OVER_LENGTH * length;
    let mut relaxed = refine::refine(points_m, fit.chain.clone(), arc, &stop, weight_m);
    let worst = relaxed.deviations_m.iter().copied().fold(0.0, f64::max);
    // A NaN deviation keeps the position fit too.
    let kept = worst <= tolerance_m.max(fit.error_over_length * length);
    if !kept {
        return fit;
    }
    refine::fix_roll(&mut relaxed.chain, reference);
    StrandFit {
        chain: relaxed.chain,
        error_over_length: worst / length,
        ..fit
    }
}

/// The most elements `options` and M + 1 points allow (see
/// [`fit_polyline`]).
fn element_cap(m: usize, options: &FitOptions) -> usize {
    options
        .max_elements
        .min((2 * m).saturating_sub(2) / 3)
        .max(1)
}

fn check(points_m: &[DVec3], options: &FitOptions) -> Result<(), FitError> {
    if !(options.tolerance_over_length > 0.0 && options.tolerance_over_length < 1.0) {
        return Err(FitError::Options(
            "tolerance_over_length must lie in (0, 1)",
        ));
    }
    if !(options.natural_tolerance_over_length > 0.0 && options.natural_tolerance_over_length < 1.0)
    {
        return Err(FitError::Options(
            "natural_tolerance_over_length must lie in (0, 1)",
        ));
    }
    if !options.sag_load_per_m3.is_finite() {
        return Err(FitError::Options("sag_load_per_m3 must be finite"));
    }
    if options.max_elements == 0 || options.max_elements > crate::params::MAX_ELEMENTS {
        return Err(FitError::Options("max_elements must lie in 1..=200"));
    }
    if points_m.len() < 2 {
        return Err(FitError::TooFewPoints(points_m.len()));
    }
    if let Some(i) = points_m.iter().position(|p| !p.is_finite()) {
        return Err(FitError::NotFinite(i));
    }
    if let Some(i) = points_m.windows(2).position(|w| w[0] == w[1]) {
        return Err(FitError::RepeatedPoint(i));
    }
    Ok(())
}
