//! The head a style's hair belongs to, and the point that head turns
//! about.
//!
//! A style grown on the scalp (`scalp` groups) or listing roots on the
//! default head needs no head of its own. An imported groom does: its
//! roots were attached to the head mesh given to `helixhair import
//! --head`, which the style names (`imported.head`, relative to the style
//! file). `sim`, `render`, `export` and the window collide the hair with
//! that mesh when the command line names no other, and turn it about its
//! own pivot, because the head clips and motion files turn the head about
//! the origin of head coordinates, and an imported head need not stand
//! there (Sintel's bust stands 1.5 m up: a shake about the origin would
//! swing it through 1.5 m).
//!
//! A detailed bust makes a poor collider (hair slips into its eye holes
//! and lips); a style may name a coarse closed `collider` beside the
//! `head` it draws ([`OwnHead`] reads both).
//!
//! The pivot is the middle of the box around the hair's roots: the
//! scalp's centre, near the skull's, which is where the default head's
//! origin lies. The default head keeps the origin, so every built-in
//! style moves as before, and the window frames either head alike around
//! its pivot.

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use glam::DVec3;
use helixhair_physics::collision::SignedDistanceField;
use helixhair_render::HeadMesh;
use helixhair_render::obj::{ObjError, load_mesh_obj};

use crate::head::groom::{head_collider, needs_head};
use crate::style::Style;

/// The meshes a style names for its head: the one drawn and exported, and
/// the one its hair collides with and rests on (the same file unless the
/// style names a `collider`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct HeadFiles {
    /// The mesh drawn, picked by the brush and written with exports.
    pub drawn: PathBuf,
    /// The mesh the collision field is built from.
    pub collider: PathBuf,
}

/// The head meshes `style` (read from `style_path`) brings, as paths: the
/// first imported group's `head` and `collider`, relative to the style's
/// folder. `None` when it names no head, or grows hair on the scalp (it
/// takes the head it is grown on).
pub fn style_head_files(style: &Style, style_path: &Path) -> Option<HeadFiles> {
    if needs_head(style) {
        return None;
    }
    let imported = style
        .groups
        .iter()
        .filter_map(|g| g.imported.as_ref())
        .find(|i| i.head.is_some())?;
    let folder = style_path.parent().unwrap_or(Path::new(""));
    let drawn = folder.join(imported.head.as_deref()?);
    let collider = imported
        .collider
        .as_deref()
        .map_or_else(|| drawn.clone(), |c| folder.join(c));
    Some(HeadFiles { drawn, collider })
}

/// The head a style brings with it (an imported groom's own), read.
pub struct OwnHead {
    /// Its files.
    pub files: HeadFiles,
    /// The mesh drawn and exported.
    pub drawn: HeadMesh,
    /// The mesh collided with, when it is another file than `drawn`'s.
    pub collider: Option<HeadMesh>,
    /// The point the head turns about, world, metres ([`head_pivot_m`]).
    pub pivot_m: DVec3,
}

impl OwnHead {
    /// Reads the head `style` (at `style_path`) brings: `None` for a style
    /// that names none or grows hair on the scalp (it takes the head it is
    /// grown on). An unreadable mesh is an error naming its file and line.
    pub fn of_style(style: &Style, style_path: &Path) -> Result<Option<Self>, ObjError> {
        let Some(files) = style_head_files(style, style_path) else {
            return Ok(None);
        };
        let drawn = load_mesh_obj(&files.drawn)?;
        let collider = match files.collider != files.drawn {
            true => Some(load_mesh_obj(&files.collider)?),
            false => None,
        };
        Ok(Some(Self {
            files,
            drawn,
            collider,
            pivot_m: head_pivot_m(style),
        }))
    }

    /// The mesh the hair collides with.
    pub fn collider_mesh(&self) -> &HeadMesh {
        self.collider.as_ref().unwrap_or(&self.drawn)
    }

    /// The collision field of [`Self::collider_mesh`] ([`head_collider`]);
    /// the error names the mesh's file.
    pub fn collision_field(&self) -> anyhow::Result<SignedDistanceField> {
        head_collider(self.collider_mesh()).with_context(|| {
            format!(
                "cannot build the collision field of {}",
                self.files.collider.display()
            )
        })
    }
}

/// The pivot of a head carrying the roots of `grown` (the style with its
/// scalp roots grown), world coordinates at rest, metres; the origin when
/// it has no roots.
pub fn head_pivot_m(grown: &Style) -> DVec3 {
    let roots = grown.groups.iter().flat_map(|g| {
        let listed = g.roots.iter().map(|r| r.position_m);
        let imported = g
            .imported
            .iter()
            .flat_map(|i| i.strands.iter().map(|s| s.root.position_m));
        listed.chain(imported)
    });
    let (lo, hi) = roots.fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p), hi.max(p)),
    );
    if lo.x > hi.x {
        return DVec3::ZERO;
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::motion::clip::{Clip, about_pivot};

    #[test]
    fn a_pivoted_pose_keeps_the_pivot_in_place_and_turns_the_rest_alike() {
        let pivot = DVec3::new(0.01, 1.5, -0.02);
        for t in [0.1, 0.4, 0.9] {
            let (rotation, offset) = Clip::Shake.pose_at(t);
            let (r, o) = about_pivot((rotation, offset), pivot);
            // The pivot moves only by the clip's own offset.
            assert!((o + r * pivot - (pivot + offset)).length() < 1e-12);
            // Any other point keeps its distance to the pivot.
            let y = pivot + DVec3::new(0.1, 0.05, 0.0);
            let moved = o + r * y;
            assert!(((moved - (pivot + offset)).length() - (y - pivot).length()).abs() < 1e-12);
        }
    }
}
