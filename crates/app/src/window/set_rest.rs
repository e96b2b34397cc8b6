//! "Set current shape as rest": the hair as it is now becomes the static
//! equilibrium, so an artist can pose hair with the head (drag it, shake
//! it, let it fall) and freeze it.
//!
//! # How it works
//!
//! For every simulated strand, its current strains q (twist and two
//! curvatures per element) are kept as its starting shape, and its natural
//! strains are solved with the sag-free solve `helixhair import` uses
//! ([`helixhair_physics::fit::sag_free`](mod@helixhair_physics::fit::sag_free)): q⁰ = q − K⁻¹ Q(q), so that the
//! elastic force K(q − q⁰) balances gravity exactly in the current shape,
//! with the root where the head holds it now. Per-strand natural strains
//! are what an `imported` section of the style holds (docs/import.md), so
//! each group's strands become imported strands (roots, element length,
//! `strains`, `natural`); a group's material stays. The head stops where
//! it is ([`HeadDriver::hold`]) and the strands' rates are set to zero:
//! the hair is then at rest in its equilibrium and stays put. The edit is
//! one undo step.
//!
//! Where strands lie on the head, the rest shape also holds them against
//! the head's contact push where they are now, by the engine's own
//! contact law ([`helixhair_physics::fit::rest_contact`]): the pose is then
//! an exact equilibrium of the step, contact included.
//!
//! Limits: procedural groups with graded element layouts are refused (an
//! imported strand has uniform elements). A pose is only kept if it is a
//! stable equilibrium: fine hair held out from the head by its rest shape
//! alone (ρSgL³/EI ≫ 1: the default curls' is about 170) is at rest but
//! unstable, and would fall away at the smallest push. As the import does,
//! such a strand is stiffened by the least factor that holds it
//! ([`helixhair_physics::fit::stiffen`], kept as the strand's
//! `stiffness_scale`, at most 100 in all); one that would need more stays
//! unstable. The message counts each kind. Drawn strands of a `render` section follow the guides only
//! where the style draws imported groups (only guides are drawn today).
//!
//! [`HeadDriver::hold`]: super::head_motion::HeadDriver::hold

use helixhair_physics::engine::Engine;
use helixhair_physics::fit::stiffen::MAX_STIFFNESS_SCALE;
use helixhair_physics::fit::{SagFreeInputs, SagFreeStatus, StiffenOptions, sag_free_stiffened};
use helixhair_physics::{ElementLayout, RigidMotion};

use crate::style::Style;
use crate::style_imported::{ImportedStrand, ImportedStrands};

use super::app_state::AppState;

/// How the solve went, strand by strand.
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

/// A strand frozen in its current shape: its strains, its sag-free
/// natural strains, and the factor its moduli were stiffened by (1: not).
struct Frozen {
    strains: Vec<glam::DVec3>,
    natural: Vec<glam::DVec3>,
    stiffened_by: f64,
}

/// Strand `index` of `engine` frozen as it is now, resting on the head
/// where it lies on it; stiffened if its equilibrium is
/// unstable, so that its whole scale (`scale_now` times the new factor)
/// stays within the style's limit.
fn rest_of(
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
        max_scale: MAX_STIFFNESS_SCALE / scale_now,
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

/// `grown` (the style as the engine was built from it: scalp placements
/// grown into roots) with every simulated strand frozen in `engine`'s
/// current shape as its rest shape.
pub fn rest_style(grown: &Style, engine: &Engine) -> Result<(Style, RestCounts), String> {
    let mut style = grown.clone();
    let mut counts = RestCounts::default();
    let mut index = 0;
    for group in &mut style.groups {
        if !group.roots.is_empty() && group.params.layout != ElementLayout::Uniform {
            return Err(format!(
                "group `{}` has a graded element layout; set as rest needs uniform elements",
                group.name
            ));
        }
        let element_length_m = group.params.length_m / group.params.elements as f64;
        let mut frozen = Vec::with_capacity(group.roots.len());
        for root in &group.roots {
            let rest = rest_of(engine, index, 1.0, &mut counts)?;
            index += 1;
            frozen.push(ImportedStrand {
                root: *root,
                element_length_m,
                strains: rest.strains,
                natural: rest.natural,
                guide: true,
                stiffness_scale: rest.stiffened_by,
            });
        }
        if let Some(imported) = &mut group.imported {
            for strand in imported.strands.iter_mut().filter(|s| s.guide) {
                let rest = rest_of(engine, index, strand.stiffness_scale, &mut counts)?;
                (strand.strains, strand.natural) = (rest.strains, rest.natural);
                strand.stiffness_scale *= rest.stiffened_by;
                index += 1;
            }
        }
        if frozen.is_empty() {
            continue;
        }
        let imported = group.imported.get_or_insert_with(|| ImportedStrands {
            source: String::new(),
            head: None,
            strands: Vec::new(),
        });
        imported.strands.splice(0..0, frozen);
        group.roots.clear();
        group.scalp = None;
        group.render = None;
    }
    if index != engine.strand_count() {
        return Err(format!(
            "the simulation has {} strands and the style {index}; edit settled?",
            engine.strand_count()
        ));
    }
    Ok((style, counts))
}

impl AppState {
    /// Sets the hair's current shape as its rest shape (see the module
    /// docs); one undo step. On failure nothing changes and the message
    /// says why.
    pub fn set_current_shape_as_rest(&mut self) {
        if self.invalid.is_some() {
            self.message = Some("fix the style first: it is not being simulated".into());
            return;
        }
        let (style, counts) = match rest_style(self.sim.grown_style(), self.sim.engine()) {
            Ok(done) => done,
            Err(e) => {
                self.message = Some(format!("not set as rest: {e}"));
                return;
            }
        };
        self.head.hold();
        self.doc.edit(|s| *s = style);
        if let Err(e) = self.sim.sync(self.doc.style()) {
            self.message = Some(format!("not set as rest: {e}"));
            self.doc.undo();
            return;
        }
        self.sim.stop();
        let total = counts.held + counts.stiffened + counts.clamped + counts.unstable;
        self.message = Some(format!(
            "current shape set as rest for {total} strands ({} held exactly, {} stiffened to \
             hold, {} clamped to the curvature limit, {} unstable); Undo restores the style",
            counts.held, counts.stiffened, counts.clamped, counts.unstable
        ));
    }
}

#[cfg(test)]
#[path = "set_rest_tests.rs"]
mod tests;
