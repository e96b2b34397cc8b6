//! The interactive preview: on a software adapter (lavapipe), while the
//! user drags a slider, the view or the head, the 3D view is drawn with
//! fewer strands and at half resolution (a quarter of the pixels), then at
//! full quality again as soon as the pointer is released.
//!
//! Why: on a CPU rasteriser the picture's cost grows with the pixels the
//! strands cover and with their count (README, "Window numbers"), and a
//! drag is only usable at interactive rates; the picture the artist
//! judges is the idle one, always at full quality. On a real GPU the
//! preview is never used (unless `--preview` forces it, to measure it).

/// Most strands drawn in the preview.
pub const PREVIEW_STRANDS: usize = 300;

/// Fraction of each side of the view drawn in the preview; the picture is
/// scaled up to the view.
pub const PREVIEW_SCALE: f32 = 0.5;

/// How the 3D view is drawn this frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Quality {
    /// Strands drawn (at most what the user asked for).
    pub render_strands: usize,
    /// Picture size, pixels.
    pub picture_px: [u32; 2],
}

/// Whether this frame is a preview: forced by `--preview`, or on a
/// software adapter while the user interacts.
pub fn wants_preview(forced: bool, software_adapter: bool, interacting: bool) -> bool {
    forced || (software_adapter && interacting)
}

/// The drawing quality: full (`render_strands`, `view_px`), or the
/// preview's fewer strands and smaller picture.
pub fn quality(render_strands: usize, view_px: [u32; 2], preview: bool) -> Quality {
    if !preview {
        return Quality {
            render_strands,
            picture_px: view_px,
        };
    }
    let scale = |px: u32| ((px as f32 * PREVIEW_SCALE) as u32).max(1);
    Quality {
        render_strands: render_strands.min(PREVIEW_STRANDS),
        picture_px: [scale(view_px[0]), scale(view_px[1])],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_preview_halves_the_picture_and_caps_the_strands_only_when_asked() {
        assert_eq!(
            quality(1000, [800, 600], false),
            Quality {
                render_strands: 1000,
                picture_px: [800, 600]
            }
        );
        assert_eq!(
            quality(1000, [800, 601], true),
            Quality {
                render_strands: PREVIEW_STRANDS,
                picture_px: [400, 300]
            }
        );
        assert_eq!(quality(50, [1, 1], true).render_strands, 50);
        assert_eq!(quality(50, [1, 1], true).picture_px, [1, 1]);
        assert!(!wants_preview(false, false, true), "never on a GPU");
        assert!(!wants_preview(false, true, false), "full quality when idle");
        assert!(wants_preview(false, true, true));
        assert!(wants_preview(true, false, false));
    }
}
