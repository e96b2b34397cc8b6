//! The report of `helixhair import`: what was read, skipped and fitted, how
//! well, and how long it took (docs/import.md lists the fields).

use std::collections::BTreeMap;
use std::fmt::Write as _;

use helixhair_formats::{Format, RepairSummary};
use helixhair_physics::fit::SagFreeStatus;
use serde::Serialize;

use crate::import::fit::{FitOutcome, Unstable};
use crate::style::imported::ImportedStrand;

/// Median, 95th percentile and maximum of a list of values.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Spread {
    /// The median.
    pub median: f64,
    /// The 95th percentile (nearest rank).
    pub p95: f64,
    /// The largest value.
    pub max: f64,
}

impl Spread {
    /// The spread of `values`; `None` when empty.
    pub fn of(values: &[f64]) -> Option<Spread> {
        if values.is_empty() {
            return None;
        }
        let mut v = values.to_vec();
        v.sort_by(f64::total_cmp);
        let rank = |p: f64| v[((p * v.len() as f64).ceil() as usize).clamp(1, v.len()) - 1];
        Some(Spread {
            median: rank(0.5),
            p95: rank(0.95),
            max: v[v.len() - 1],
        })
    }
}

/// Wall-clock seconds of each stage.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct ImportTimings {
    /// Reading and repairing the groom.
    pub read_secs: f64,
    /// Attaching roots to the head.
    pub attach_secs: f64,
    /// Fitting and the sag-free solve, all cores.
    pub fit_secs: f64,
    /// Writing the style.
    pub write_secs: f64,
    /// Everything, head loading included.
    pub total_secs: f64,
}

/// A strand whose rest shape the import could not hold, and why.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct UnstableStrand {
    /// Its index among the style's strands: the number `sim`, the guard and
    /// the window give it.
    pub strand: usize,
    /// Its length, metres.
    pub length_m: f64,
    /// Its root, head coordinates, metres.
    pub root_m: [f64; 3],
    /// Stability μ of its rest shape at the stiffness it got (below 0:
    /// unstable).
    pub stability: f64,
    /// The scale of the moduli it got (1: not stiffened).
    pub stiffness_scale: f64,
    /// The scale that would hold it; absent when μ is not a number.
    pub needed_scale: Option<f64>,
    /// Why, in words.
    pub why: String,
}

impl UnstableStrand {
    fn new(strand: usize, imported: &ImportedStrand, unstable: &Unstable) -> Self {
        let why = match unstable.needed_scale {
            None => "its stability could not be computed (not a number)".to_owned(),
            Some(_) if unstable.stiffness_scale > 1.0 => format!(
                "stiffened x{:.0}, its rest shape is still unstable (stability {:.2}); \
                 it will fall from its shape",
                unstable.stiffness_scale, unstable.stability
            ),
            Some(needed) if unstable.max_scale <= 1.0 => format!(
                "it would need its moduli x{needed:.1} to hold its shape, and --no-stiffen \
                 leaves it as it is; it will fall from its shape"
            ),
            Some(needed) => format!(
                "it stands out too far for its stiffness: it would need its moduli x{needed:.0} \
                 to hold its shape, beyond the cap of x{:.0}; it will fall from its shape",
                unstable.max_scale
            ),
        };
        let root = imported.root.position_m;
        UnstableStrand {
            strand,
            length_m: imported.element_length_m * imported.strains.len() as f64,
            root_m: [root.x, root.y, root.z],
            stability: unstable.stability,
            stiffness_scale: unstable.stiffness_scale,
            needed_scale: unstable.needed_scale,
            why,
        }
    }
}

/// Unstable strands the summary names one by one; the JSON report has them
/// all.
const UNSTABLE_NAMED: usize = 10;

/// The JSON report.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct ImportReport {
    /// The groom file.
    pub groom: String,
    /// Its format (`tfx`, `hair`, `usda`, `usdc`, `usdz`, `obj`, `abc`).
    pub format: String,
    /// The style written.
    pub style: String,
    /// Strands in the file.
    pub strands_read: usize,
    /// Strands in the style.
    pub strands_imported: usize,
    /// Strands simulated (guides); the others are drawn following them.
    pub guides: usize,
    /// Strands skipped, by reason (reader repair and fitting).
    pub skipped: BTreeMap<String, usize>,
    /// Strands repaired and kept, by reason.
    pub repaired: BTreeMap<String, usize>,
    /// Largest deviation of each imported strand over its length.
    pub fit_error_over_length: Option<Spread>,
    /// Strands whose fit missed the tolerance at the element cap.
    pub outside_tolerance: usize,
    /// How many strands got each element count N.
    pub elements_histogram: BTreeMap<usize, usize>,
    /// Sag-free outcomes (`held`, `stiffened`, `clamped`, `unstable`);
    /// absent with `--no-sag-free`.
    pub sag_free: Option<BTreeMap<String, usize>>,
    /// Every strand whose rest shape could not be held, and why.
    pub unstable_strands: Vec<UnstableStrand>,
    /// Distance from each root to the head's surface, metres (with `--head`).
    pub root_distance_to_head_m: Option<Spread>,
    /// What the reader read approximately or not at all (units assumed,
    /// curves read as polylines, …).
    pub warnings: Vec<String>,
    /// Stage timings.
    pub timings: ImportTimings,
}

impl ImportReport {
    /// The report of reading `summary` and fitting to `outcomes`.
    pub fn new(
        groom: &str,
        format: Format,
        summary: &RepairSummary,
        outcomes: &[FitOutcome],
    ) -> Self {
        let mut report = ImportReport {
            groom: groom.to_owned(),
            format: format.name().to_owned(),
            strands_read: summary.strands_read,
            ..Self::default()
        };
        for (reason, count) in summary.nonzero() {
            let map = if reason.skips_strand() {
                &mut report.skipped
            } else {
                &mut report.repaired
            };
            map.insert(reason.name().to_owned(), count);
        }
        let mut errors = Vec::new();
        let mut sag = BTreeMap::new();
        for outcome in outcomes {
            match outcome {
                FitOutcome::Skipped(reason) => {
                    *report.skipped.entry((*reason).to_owned()).or_default() += 1
                }
                FitOutcome::Fitted {
                    strand,
                    error_over_length,
                    within_tolerance,
                    sag_free,
                    unstable,
                } => {
                    if let Some(unstable) = unstable {
                        report.unstable_strands.push(UnstableStrand::new(
                            report.strands_imported,
                            strand,
                            unstable,
                        ));
                    }
                    report.strands_imported += 1;
                    errors.push(*error_over_length);
                    report.outside_tolerance += usize::from(!within_tolerance);
                    *report
                        .elements_histogram
                        .entry(strand.strains.len())
                        .or_default() += 1;
                    if let Some(status) = sag_free {
                        let name = match status {
                            SagFreeStatus::Held => "held",
                            SagFreeStatus::Stiffened => "stiffened",
                            SagFreeStatus::Clamped => "clamped",
                            SagFreeStatus::Unstable => "unstable",
                        };
                        *sag.entry(name.to_owned()).or_default() += 1;
                    }
                }
            }
        }
        report.fit_error_over_length = Spread::of(&errors);
        report.sag_free = (!sag.is_empty()).then_some(sag);
        report
    }

    /// A few lines for the terminal.
    pub fn summary(&self) -> String {
        let mut s = format!(
            "groom {} ({}): {} strands read, {} imported, {} simulated as guides\n",
            self.groom, self.format, self.strands_read, self.strands_imported, self.guides
        );
        let list = |m: &BTreeMap<String, usize>| {
            m.iter()
                .map(|(k, v)| format!("{k} {v}"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        for warning in &self.warnings {
            let _ = writeln!(s, "  warning: {warning}");
        }
        if !self.skipped.is_empty() {
            let _ = writeln!(s, "  skipped: {}", list(&self.skipped));
        }
        if !self.repaired.is_empty() {
            let _ = writeln!(s, "  repaired: {}", list(&self.repaired));
        }
        if let Some(e) = self.fit_error_over_length {
            let _ = writeln!(
                s,
                "  fit error over length: median {:.2e}, p95 {:.2e}, max {:.2e} ({} outside the tolerance)",
                e.median, e.p95, e.max, self.outside_tolerance
            );
        }
        let hist: Vec<String> = self
            .elements_histogram
            .iter()
            .map(|(n, c)| format!("N={n}: {c}"))
            .collect();
        let _ = writeln!(s, "  elements: {}", hist.join(", "));
        match &self.sag_free {
            Some(m) => {
                let _ = writeln!(s, "  sag-free: {}", list(m));
            }
            None => s.push_str("  sag-free: off (the fitted shape is the rest shape)\n"),
        }
        for u in self.unstable_strands.iter().take(UNSTABLE_NAMED) {
            let _ = writeln!(
                s,
                "  unstable: strand {} ({:.0} mm long, root at ({:.3}, {:.3}, {:.3}) m): {}",
                u.strand,
                u.length_m * 1e3,
                u.root_m[0],
                u.root_m[1],
                u.root_m[2],
                u.why
            );
        }
        if self.unstable_strands.len() > UNSTABLE_NAMED {
            let _ = writeln!(
                s,
                "  unstable: {} more, listed in the JSON report (--json)",
                self.unstable_strands.len() - UNSTABLE_NAMED
            );
        }
        let t = &self.timings;
        let _ = writeln!(
            s,
            "  {:.2} s: read {:.2} s, attach {:.2} s, fit {:.2} s, write {:.2} s\n  wrote {}",
            t.total_secs, t.read_secs, t.attach_secs, t.fit_secs, t.write_secs, self.style
        );
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spread_takes_nearest_ranks() {
        let v: Vec<f64> = (1..=100).map(f64::from).collect();
        let s = Spread::of(&v).expect("non-empty");
        assert_eq!((s.median, s.p95, s.max), (50.0, 95.0, 100.0));
        assert!(Spread::of(&[]).is_none());
    }
}
