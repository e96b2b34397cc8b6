//! The fitting stage of `helixhair import`: every polyline becomes a
//! Super-Helix ([`helixhair_physics::fit`]) and, unless asked not to, gets
//! sag-free natural strains, on all cores.
//!
//! The work is one strand at a time and independent, so the strands are cut
//! into one contiguous chunk per core (`std::thread::scope`; the physics
//! crate's own parallelism is for stepping). The order of the result is the
//! groom's order whatever the number of cores, and each strand's result
//! depends on nothing else: imports are reproducible.

use glam::DVec3;
use helixhair_physics::engine::RestContact;
use helixhair_physics::fit::{
    FitError, FitOptions, SagFreeInputs, SagFreeStatus, StiffenOptions, StrandFit, fit_polyline,
    sag_free_stiffened,
};
use helixhair_physics::{RigidMotion, StrandParams};

use crate::style::Root;
use crate::style::imported::ImportedStrand;
use crate::work_progress::WorkProgress;

/// Quadrature samples per element of the models the sag-free solve uses
/// (the simulation's default).
const SAMPLES_PER_ELEMENT: usize = 4;

/// One strand to fit: its points (root first, head coordinates) and the
/// reference direction of its root frame.
#[derive(Clone, Debug)]
pub struct FitJob {
    /// Points, metres.
    pub points_m: Vec<DVec3>,
    /// Reference for n₁ (the inward normal, or the default).
    pub reference: DVec3,
}

/// What fitting one strand gave.
#[derive(Clone, Debug)]
pub enum FitOutcome {
    /// Fitted (and solved for its rest shape).
    Fitted {
        /// The style's record of the strand.
        strand: ImportedStrand,
        /// Largest deviation over length.
        error_over_length: f64,
        /// Whether the tolerance was met (otherwise the cap was hit).
        within_tolerance: bool,
        /// The sag-free outcome; `None` with sag-free off.
        sag_free: Option<SagFreeStatus>,
        /// Why the rest shape could not be held, when `sag_free` is
        /// [`SagFreeStatus::Unstable`].
        unstable: Option<Unstable>,
    },
    /// Skipped, with the reason's snake_case name.
    Skipped(&'static str),
}

/// Why a strand's sag-free rest shape is unstable: the numbers behind the
/// import report's sentence about it (`docs/import.md`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Unstable {
    /// Stability μ of the equilibrium at the stiffness the strand got
    /// (below 0: unstable; see `helixhair_physics::fit::stiffen`).
    pub stability: f64,
    /// The scale of the moduli the strand got (1: not stiffened).
    pub stiffness_scale: f64,
    /// The scale that would hold it with the stiffening margin, from μ at
    /// the strand's own stiffness; `None` when μ is not a number.
    pub needed_scale: Option<f64>,
    /// The largest scale the import allows (1 with `--no-stiffen`).
    pub max_scale: f64,
}

/// Settings shared by every strand's fit.
#[derive(Clone, Copy, Debug)]
pub struct FitSettings<'a> {
    /// Tolerance and cap.
    pub options: FitOptions,
    /// The material of every strand (radius, density, moduli).
    pub material: &'a StrandParams,
    /// Gravity for the sag-free solve; `None`: no sag-free.
    pub gravity_m_per_s2: Option<DVec3>,
    /// The head as a support for sag-free, with the contact law of the
    /// engine the style will run on.
    pub support: Option<RestContact<'a>>,
    /// How strands whose sag-free equilibrium is unstable are stiffened
    /// ([`StiffenOptions::none`]: left as they are, to fall when simulated).
    pub stiffen: StiffenOptions,
}

/// Fits every job on all cores; results in job order. Each strand fitted
/// counts one unit of `progress`; once it is cancelled the strands not yet
/// fitted are skipped as `cancelled`.
pub fn fit_all(
    jobs: &[FitJob],
    settings: &FitSettings,
    progress: &WorkProgress,
) -> Vec<FitOutcome> {
    progress.start(jobs.len());
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let chunk = jobs.len().div_ceil(cores).max(1);
    std::thread::scope(|scope| {
        let handles: Vec<_> = jobs
            .chunks(chunk)
            .map(|part| {
                scope.spawn(move || {
                    part.iter()
                        .map(|j| {
                            if progress.cancelled() {
                                return FitOutcome::Skipped("cancelled");
                            }
                            let outcome = fit_one(j, settings);
                            progress.add(1);
                            outcome
                        })
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().unwrap_or_default())
            .collect()
    })
}

/// Fits one strand.
pub fn fit_one(job: &FitJob, settings: &FitSettings) -> FitOutcome {
    let fit = match fit_polyline(&job.points_m, job.reference, &settings.options) {
        Ok(fit) => fit,
        Err(FitError::TooFewPoints(_)) => return FitOutcome::Skipped("too_few_points"),
        Err(FitError::NotFinite(_)) => return FitOutcome::Skipped("non_finite_point"),
        Err(FitError::RepeatedPoint(_)) => return FitOutcome::Skipped("repeated_points"),
        Err(FitError::Options(_)) => return FitOutcome::Skipped("bad_fit_options"),
    };
    if fit.chain.length_m() > 2.0 {
        return FitOutcome::Skipped("longer_than_2_m");
    }
    let mut strand = record(&fit, job.reference);
    let sag = settings.gravity_m_per_s2.and_then(|gravity| {
        let params = strand.params(settings.material);
        let root = RigidMotion::at_rest(fit.root_m, fit.chain.root_frame);
        let inputs = SagFreeInputs {
            root: &root,
            gravity_m_per_s2: gravity,
            support: settings.support,
        };
        let q = &fit.chain.strains_per_m;
        let stiff =
            sag_free_stiffened(&params, SAMPLES_PER_ELEMENT, q, &inputs, &settings.stiffen).ok()?;
        strand.natural = stiff.rest.natural_per_m.clone();
        strand.stiffness_scale = stiff.stiffness_scale;
        Some(stiff)
    });
    let unstable = sag.as_ref().and_then(|stiff| {
        (stiff.rest.status == SagFreeStatus::Unstable).then(|| Unstable {
            stability: stiff.rest.stability,
            stiffness_scale: stiff.stiffness_scale,
            needed_scale: stiff.needed_scale(settings.stiffen.margin),
            max_scale: settings.stiffen.max_scale,
        })
    });
    if strand
        .strains
        .iter()
        .any(|k| k.abs().max_element() > helixhair_physics::natural_shape::MAX_NATURAL_STRAIN_PER_M)
    {
        return FitOutcome::Skipped("kink_beyond_element_bending");
    }
    FitOutcome::Fitted {
        strand,
        error_over_length: fit.error_over_length,
        within_tolerance: fit.within_tolerance,
        sag_free: sag.map(|stiff| stiff.rest.status),
        unstable,
    }
}

/// The style's record of a fit: natural strains = fitted ones until the
/// sag-free solve replaces them.
fn record(fit: &StrandFit, reference: DVec3) -> ImportedStrand {
    ImportedStrand {
        root: Root {
            position_m: fit.root_m,
            direction: fit.chain.root_frame.col(0),
            reference,
        },
        element_length_m: fit.chain.element_length_m,
        strains: fit.chain.strains_per_m.clone(),
        natural: fit.chain.strains_per_m.clone(),
        guide: true,
        stiffness_scale: 1.0,
    }
}
