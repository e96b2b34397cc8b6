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
//! The pivot is the middle of the box around the hair's roots: the
//! scalp's centre, near the skull's, which is where the default head's
//! origin lies. The default head keeps the origin, so every built-in
//! style moves as before, and the window frames either head alike around
//! its pivot.

use std::path::{Path, PathBuf};

use glam::DVec3;

use crate::style::Style;

/// The head mesh `style` (read from `style_path`) names, as a path: the
/// first imported group's `head`, relative to the style's folder.
pub fn style_head_path(style: &Style, style_path: &Path) -> Option<PathBuf> {
    let head = style
        .groups
        .iter()
        .filter_map(|g| g.imported.as_ref())
        .find_map(|i| i.head.as_deref())?;
    let folder = style_path.parent().unwrap_or(Path::new(""));
    Some(folder.join(head))
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
