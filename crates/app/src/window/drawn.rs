//! Styles that say how they are drawn: groups with a `render` section
//! (drawn strand count, interpolation, colour; see the style format) are
//! drawn as `helixhair render` draws them ([`drawn_hair`]), so the window
//! and the offline pictures agree. Other styles use the window's own look
//! ([`super::viewport::HairLook`]).
//!
//! Two things differ from the offline path. The head moves, so guides are
//! taken into head coordinates, drawn there (where the groom's scalp and
//! shell are) and moved back. And drawing every strand a groom asks for
//! (thousands) is too slow for a software rasteriser, so the counts are
//! scaled down together to at most the window's `--render-strands`.

use glam::{DMat3, DVec3, Mat3, Vec3};
use helixhair_render::{HairStrands, HeadMesh, StrandBuffers};

use crate::drawn_hair::drawn_hair;
use crate::groom::Groom;
use crate::style::Style;

/// The groom of the style last drawn, rebuilt when the style changes.
#[derive(Debug, Default)]
pub struct DrawnCache {
    source: Option<Style>,
    groom: Option<Groom>,
}

/// Whether `style` says how it is drawn.
pub fn has_render_sections(style: &Style) -> bool {
    style.groups.iter().any(|g| g.render.is_some())
}

/// `style` with its groups' drawn counts scaled so they add up to at most
/// `max_strands` (each group keeps at least one).
pub fn capped(style: &Style, max_strands: usize) -> Style {
    let total: u64 = style
        .groups
        .iter()
        .filter_map(|g| g.render.as_ref().map(|r| u64::from(r.count)))
        .sum();
    let mut out = style.clone();
    if total > max_strands as u64 {
        let scale = max_strands as f64 / total as f64;
        for r in out.groups.iter_mut().filter_map(|g| g.render.as_mut()) {
            r.count = ((f64::from(r.count) * scale) as u32).max(1);
        }
    }
    out
}

impl DrawnCache {
    /// The drawn hair of `style` on `head` at `pose` (rotation, position)
    /// from `guides` (world coordinates), or `None` when the style has no
    /// `render` section or its guides do not match it (an edit not yet
    /// simulated).
    pub fn strands(
        &mut self,
        style: &Style,
        head: &HeadMesh,
        guides: &StrandBuffers,
        pose: (DMat3, DVec3),
        max_strands: usize,
    ) -> Option<HairStrands> {
        if !has_render_sections(style) {
            return None;
        }
        if self.source.as_ref() != Some(style) {
            self.groom = Some(Groom::new(capped(style, max_strands), head.clone()));
            self.source = Some(style.clone());
        }
        let groom = self.groom.as_ref()?;
        if groom.grown.strand_count() != guides.strand_count() {
            return None;
        }
        let rotation: Mat3 = pose.0.as_mat3();
        let position: Vec3 = pose.1.as_vec3();
        let inverse = rotation.transpose();
        let mut local = guides.clone();
        for p in &mut local.points {
            *p = inverse * (*p - position);
        }
        let mut hair = drawn_hair(groom, &local);
        for p in &mut hair.strands.points {
            *p = rotation * *p + position;
        }
        Some(hair)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_scale_down_together_and_keep_one_each() {
        let src = include_str!("../../../../assets/styles/groomed/curly.ron");
        let style = Style::from_ron(src, std::path::Path::new("curly.ron")).unwrap();
        let counts = |s: &Style| -> Vec<u32> {
            s.groups
                .iter()
                .filter_map(|g| g.render.as_ref().map(|r| r.count))
                .collect()
        };
        let before = counts(&style);
        let after = counts(&capped(&style, 750));
        let total: u32 = before.iter().sum();
        for (b, a) in before.iter().zip(&after) {
            assert_eq!(
                *a,
                ((f64::from(*b) * 750.0 / f64::from(total)) as u32).max(1)
            );
        }
        assert!(after.iter().sum::<u32>() <= 750);
        assert_eq!(counts(&capped(&style, 1_000_000)), before);
        assert!(has_render_sections(&style));
    }
}
