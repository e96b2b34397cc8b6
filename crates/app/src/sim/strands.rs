//! A grown style's strands, in the order the engine holds them, and the one
//! place that adds them to an engine.
//!
//! Every face that simulates a style (`sim`, `render`, `export`, the bench,
//! the window, the styling tools) adds its strands here, so a strand means
//! the same everywhere: its parameters (the group's, with the group's
//! per-strand edits, [`crate::style::strand_edit`]), its root, and the
//! shape it starts and rests in.
//!
//! # Order
//!
//! Group by group: the listed roots (a grown style's scalp roots are
//! listed by then, [`crate::head::groom::grow_scalp_roots`]), then the
//! imported guides. Within a group a strand's number in that order is the
//! `strand` its edits name.
//!
//! # Batching
//!
//! Consecutive strands with the same parameters are added in one call, so
//! a procedural group with a few edited strands still shares one model
//! among the rest (the reference engine's memory and the batch engine's
//! packing both gain).

use std::ops::Range;

use glam::DVec3;
use helixhair_physics::engine::Engine;
use helixhair_physics::{ParamError, RootPose, StrandParams};

use crate::style::field_path::FieldPath;
use crate::style::strand_edit::edit_of;
use crate::style::{StrandGroup, Style};

/// One simulated strand of a grown style.
#[derive(Clone, Debug, PartialEq)]
pub struct StyleStrand {
    /// Its group's index in the style.
    pub group: usize,
    /// Its number within the group (what an edit's `strand` names).
    pub strand: usize,
    /// Its parameters before its edit: the group's (or the automatic
    /// choice's), or its imported strand's.
    pub base: StrandParams,
    /// Its parameters: `base` with its edit.
    pub params: StrandParams,
    /// Its root frame, head coordinates.
    pub pose: RootPose,
    /// The strains it starts and rests in, when not its natural ones (an
    /// imported strand's fitted shape, a frozen shape).
    pub rest_strains: Option<Vec<DVec3>>,
    /// Where its parameters sit in the style file, for errors.
    pub field: FieldPath,
}

/// The simulated strands of `group` (index `g` of a grown style, its
/// parameters `params`: the group's, or the automatic choice's), in order.
pub fn group_strands(g: usize, group: &StrandGroup, params: &StrandParams) -> Vec<StyleStrand> {
    let at = FieldPath::root().field("groups").index(g);
    let listed = group.roots.iter().map(|root| (params.clone(), *root, None));
    let imported = group.imported.iter().flat_map(|imported| {
        imported.guides().map(|strand| {
            (
                strand.params(params),
                strand.root,
                Some(strand.strains.clone()),
            )
        })
    });
    listed
        .chain(imported)
        .enumerate()
        .map(|(n, (base, root, fitted))| {
            let (params, pose_root, rest_strains, field) = match edit_of(&group.edits, n) {
                Some((k, edit)) => (
                    edit.params(&base),
                    edit.root(&root),
                    edit.rest_strains().map(<[DVec3]>::to_vec).or(fitted),
                    at.field("edits").index(k),
                ),
                None => (base.clone(), root, fitted, at.field("params")),
            };
            StyleStrand {
                group: g,
                strand: n,
                base,
                params,
                pose: pose_root.pose(),
                rest_strains,
                field,
            }
        })
        .collect()
}

/// Every simulated strand of the grown `style`, in engine order, each
/// group with the parameters `params_of(g)` gives it.
pub fn style_strands(
    style: &Style,
    params_of: impl Fn(usize, &StrandGroup) -> StrandParams,
) -> Vec<StyleStrand> {
    style
        .groups
        .iter()
        .enumerate()
        .flat_map(|(g, group)| group_strands(g, group, &params_of(g, group)))
        .collect()
}

/// Adds `strands` to `engine`, each started at rest in its rest strains
/// (its natural shape otherwise), which are also the shape the hair–hair
/// model's rest density and the guard's reset take. Returns the engine
/// indices of the strands added; on a parameter error, the field it names
/// and the error.
pub fn add_strands(
    engine: &mut Engine,
    strands: &[StyleStrand],
) -> Result<Range<usize>, (FieldPath, ParamError)> {
    let start = engine.strand_count();
    let mut i = 0;
    while i < strands.len() {
        // A run of strands sharing parameters and starting natural.
        let first = &strands[i];
        let mut end = i + 1;
        while end < strands.len()
            && first.rest_strains.is_none()
            && strands[end].rest_strains.is_none()
            && strands[end].params == first.params
        {
            end += 1;
        }
        let poses: Vec<RootPose> = strands[i..end].iter().map(|s| s.pose).collect();
        let range = engine
            .add_group(&first.params, &poses)
            .map_err(|e| (first.field.clone(), e))?;
        if let Some(q) = &first.rest_strains {
            let at_rest = vec![DVec3::ZERO; q.len()];
            engine.set_state(range.start, q, &at_rest);
            // It rests there (sag-free: gravity holds it in that shape,
            // away from its natural one).
            engine.set_rest_pose(range.start, q);
        }
        i = end;
    }
    Ok(start..engine.strand_count())
}
