//! Freezing a strand: its current shape made its rest shape, so what the
//! artist combed, grabbed or posed stays where it is.
//!
//! # How it works
//!
//! The strand's current strains q (twist and two curvatures per element)
//! are kept as the shape it starts and rests in, and its natural strains
//! are solved with the sag-free solve `helixhair import` uses
//! ([`helixhair_physics::fit::sag_free`](mod@helixhair_physics::fit::sag_free)):
//! q⁰ = q − K⁻¹ Q(q), so that the elastic force K(q − q⁰) balances gravity
//! exactly in the current shape, with the root where the head holds it
//! now. Where the strand lies on the head, the rest shape also holds it
//! against the head's contact push where it is, by the engine's own contact
//! law ([`helixhair_physics::engine::rest_contact`]): the shape is then an
//! exact equilibrium of the step, contact included.
//!
//! A shape is only kept if it is a stable equilibrium: fine hair held out
//! from the head by its rest shape alone (ρSgL³/EI ≫ 1) is at rest but
//! unstable, and would fall away at the smallest push. As the import does,
//! such a strand is stiffened by the least factor that holds it
//! ([`helixhair_physics::fit::stiffen`]), at most
//! the edits' largest scale ([`STIFFNESS_SCALE_RANGE`], 100×) in all and
//! within the moduli's range; one that would need more stays
//! unstable, and the counts say so.

use glam::DVec3;
use helixhair_physics::RigidMotion;
use helixhair_physics::engine::Engine;
use helixhair_physics::fit::stiffen::max_stiffness_scale;
use helixhair_physics::fit::{SagFreeInputs, SagFreeStatus, StiffenOptions, sag_free_stiffened};

use crate::sim::strands::StyleStrand;
use crate::style::Style;
use crate::style::strand_edit::{RestShape, STIFFNESS_SCALE_RANGE, edit_mut};

/// How freezing went, strand by strand.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RestCounts {
    /// Exact, stable equilibria.
    pub held: usize,
    /// Exact equilibria made stable by stiffening the strand by the least
    /// factor that holds it (as the import does).
    pub stiffened: usize,
    /// Natural strains clamped to the format's limit (the shape then sags
    /// a little).
    pub clamped: usize,
    /// Unstable equilibria (the strand will fall away from its shape).
    pub unstable: usize,
}

impl RestCounts {
    /// Strands frozen.
    pub fn total(&self) -> usize {
        self.held + self.stiffened + self.clamped + self.unstable
    }

    /// The counts in words ("12 held exactly, 2 stiffened to hold, …").
    pub fn describe(&self) -> String {
        format!(
            "{} held exactly, {} stiffened to hold, {} clamped to the curvature limit, {} unstable",
            self.held, self.stiffened, self.clamped, self.unstable
        )
    }
}

/// A strand frozen in its current shape.
#[derive(Clone, Debug, PartialEq)]
pub struct Frozen {
    /// Its strains now: the shape it starts and rests in.
    pub strains: Vec<DVec3>,
    /// Its sag-free natural strains.
    pub natural: Vec<DVec3>,
    /// The factor its moduli were stiffened by to hold (1: not).
    pub stiffened_by: f64,
}

/// Strand `index` of `engine` frozen as it is now, resting on the head
/// where it lies on it; stiffened if its equilibrium is unstable, so that
/// its whole scale (`scale_now` times the new factor) stays within
/// [`STIFFNESS_SCALE_RANGE`]. Counts the outcome in `counts`.
pub fn freeze_strand(
    engine: &Engine,
    index: usize,
    scale_now: f64,
    counts: &mut RestCounts,
) -> Result<Frozen, String> {
    let q = engine.q(index);
    let (root, _) = engine.kinematics(index);
    let root = RigidMotion::at_rest(root.position_m, root.world_from_body);
    let inputs = SagFreeInputs {
        root: &root,
        gravity_m_per_s2: engine.settings().gravity_m_per_s2,
        support: engine.rest_contact(),
    };
    let model = engine.strand_model(index);
    let options = StiffenOptions {
        max_scale: (STIFFNESS_SCALE_RANGE.1 / scale_now).min(max_stiffness_scale(&model.params)),
        ..StiffenOptions::default()
    };
    let samples = model.quadrature.nodes.len();
    let stiff = sag_free_stiffened(&model.params, samples, &q, &inputs, &options)
        .map_err(|e| format!("strand {index}: {e}"))?;
    match stiff.rest.status {
        SagFreeStatus::Held => counts.held += 1,
        SagFreeStatus::Stiffened => counts.stiffened += 1,
        SagFreeStatus::Clamped => counts.clamped += 1,
        SagFreeStatus::Unstable => counts.unstable += 1,
    }
    Ok(Frozen {
        strains: q,
        natural: stiff.rest.natural_per_m,
        stiffened_by: stiff.stiffness_scale,
    })
}

/// The strands `which` (engine indices; `strands` the engine's strands of
/// `grown`) frozen in `engine`'s current shapes, each kept in `grown` as
/// its edit's rest shape (and stiffness scale, where stiffened).
pub fn freeze_strands(
    engine: &Engine,
    strands: &[StyleStrand],
    which: &[usize],
    grown: &mut Style,
) -> Result<RestCounts, String> {
    let mut counts = RestCounts::default();
    let mut frozen = Vec::with_capacity(which.len());
    for &i in which {
        let scale_now =
            engine.strand_model(i).params.youngs_modulus_pa / strands[i].base.youngs_modulus_pa;
        frozen.push(freeze_strand(engine, i, scale_now, &mut counts)?);
    }
    for (&i, rest) in which.iter().zip(frozen) {
        let strand = &strands[i];
        let edit = edit_mut(&mut grown.groups[strand.group].edits, strand.strand);
        let scale = edit.stiffness_scale.unwrap_or(1.0) * rest.stiffened_by;
        edit.stiffness_scale = (scale != 1.0).then_some(scale);
        edit.rest = Some(RestShape {
            strains: rest.strains,
            natural: rest.natural,
        });
    }
    Ok(counts)
}
