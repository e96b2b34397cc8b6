//! A style file on its head: the style grown on the head it names (or
//! `--head`), built into a simulation ([`crate::sim::build`], through
//! [`HeadlessSim`]) that collides with that head.
//!
//! `render`, `export`, `sim` with a head, the bench and the window's drawn
//! hair all start here, so a style means the same hair everywhere: the
//! head is the command line's `--head`, else the one an imported groom
//! names (`imported.head`), else the default head; a placement that finds
//! no scalp is refused with the style's file, line and field.

use std::path::Path;
use std::sync::Arc;

use anyhow::Context as _;
use helixhair_render::obj::NO_SCALP_HINT;

use crate::head::groom::Groom;
use crate::head::load_head;
use crate::head::of_style::{OwnHead, head_pivot_m};
use crate::sim::build::SimOverrides;
use crate::sim::headless::HeadlessSim;
use crate::sim::settle::{settle_on_head, settles_on_head};
use crate::style::Style;
use crate::style::error::{StyleError, StyleErrorKind};
use crate::style::field_path::FieldPath;
use crate::style::source_map::SourceMap;
use helixhair_render::obj::load_mesh_obj;

/// Refuses a scalp placement that found no scalp to grow on (a `region`
/// that misses the head's scalp), naming the style's file, line and field
/// as a style error does.
fn check_placements(groom: &Groom, style_path: &Path, head: Option<&Path>) -> anyhow::Result<()> {
    let head = head.map_or_else(
        || "the default head".to_owned(),
        |p| p.display().to_string(),
    );
    let no_scalp = groom.head.scalp_triangles.is_empty();
    for (i, (group, grown)) in groom.groups().enumerate() {
        let Some(scalp) = &group.scalp else { continue };
        if grown.roots.len() > group.roots.len() && !no_scalp {
            continue;
        }
        let at = FieldPath::root().field("groups").index(i).field("scalp");
        let field = if scalp.region.is_some() {
            at.field("region")
        } else {
            at
        };
        // The file was just read; if it has gone since, report without a line.
        let src = std::fs::read_to_string(style_path).unwrap_or_default();
        let (position, field) = SourceMap::new(&src).locate(&field);
        return Err(StyleError::Located {
            path: style_path.to_owned(),
            position,
            field,
            kind: StyleErrorKind::InvalidValue,
            message: if no_scalp {
                format!("grows hair on the scalp of {head}, but {NO_SCALP_HINT}")
            } else {
                format!("places no roots: it covers none of the scalp of {head}")
            },
        }
        .into());
    }
    Ok(())
}

/// The style at `style_path` grown on `head` (an OBJ, or the default
/// head), and its simulation colliding with that head: what `render` and
/// `export` step.
pub fn grown_sim(
    style_path: &Path,
    head: Option<&Path>,
    overrides: SimOverrides,
) -> anyhow::Result<(Groom, HeadlessSim)> {
    let style = Style::load(style_path)?;
    // Without `--head`, an imported groom's own head (`imported.head`),
    // drawn, and its `collider` collided with.
    let own = match head {
        Some(_) => None,
        None => OwnHead::of_style(&style, style_path)?,
    };
    let (head_mesh, pivot_m, own_collider) = match own {
        Some(own) => {
            let collider = own.collision_field()?;
            (own.drawn, Some(own.pivot_m), Some(collider))
        }
        // A style that grows no hair on the scalp takes any mesh given as
        // its head, every face scalp when it has no `scalp` group.
        None => match head {
            Some(path) if !crate::head::groom::needs_head(&style) => {
                let pivot_m = head_pivot_m(&style);
                (load_mesh_obj(path)?, Some(pivot_m), None)
            }
            path => (load_head(path)?, None, None),
        },
    };
    let groom = Groom::new(style, head_mesh);
    check_placements(&groom, style_path, head)?;
    let mut sim = HeadlessSim::new(&groom.grown, overrides)
        .with_context(|| format!("cannot simulate {}", style_path.display()))?;
    if let Some(pivot_m) = pivot_m {
        sim.set_head_pivot(pivot_m);
    }
    let collider = match own_collider {
        Some(collider) => collider,
        None => groom
            .collider()
            .context("cannot build the head's collision field")?,
    };
    sim.engine_mut().set_collider(Some(Arc::new(collider)));
    if settles_on_head(&groom.style) {
        settle_on_head(sim.engine_mut());
    }
    Ok((groom, sim))
}
