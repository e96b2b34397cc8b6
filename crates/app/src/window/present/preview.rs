//! The interactive preview: on a software adapter (lavapipe), while the
//! user drags a slider, the view or the head, the 3D view is drawn with
//! fewer strands, without MSAA and without the hair's self-shadow, then at
//! full quality again as soon as the pointer is released.
//!
//! Why: on a CPU rasteriser the picture's cost grows with the pixels the
//! strands cover, with the samples per pixel, with the shadow passes and
//! with the strand count (docs/window.md, "What a frame costs on a
//! software adapter"), and a drag is only usable at interactive rates; the
//! picture the artist judges is the idle one, always at full quality. On a real GPU the preview is never used
//! (unless `--preview` forces it, to measure it).
//!
//! Also on a software adapter, whether previewing or not, the panels are
//! kept as a layer and repainted only where they change
//! ([`super::panel_layer`]): this changes nothing on screen, only what
//! painting the panels costs.

/// Most strands drawn in the preview.
pub const PREVIEW_STRANDS: usize = 300;

/// Fraction of each side of the view drawn in the preview (a smaller
/// picture would be scaled up to the view). 1: on lavapipe a half-size
/// picture saved as much drawing as scaling it up cost (egui samples a
/// texture per window pixel, the dearest thing a CPU rasteriser does),
/// while a full-size one is copied onto the window without shading
/// ([`super::panel_layer::picture_copy`]); docs/window.md.
pub const PREVIEW_SCALE: f32 = 1.0;

/// Samples per pixel of the preview's picture: no MSAA.
pub const PREVIEW_MSAA_SAMPLES: u32 = 1;

/// How the 3D view is drawn this frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Quality {
    /// Strands drawn (at most what the user asked for).
    pub render_strands: usize,
    /// Picture size, pixels.
    pub picture_px: [u32; 2],
    /// Samples per pixel (4: MSAA, 1: none).
    pub msaa_samples: u32,
    /// Whether the hair's self-shadow is drawn.
    pub shadows: bool,
}

/// Whether this frame is a preview: forced by `--preview`, or on a
/// software adapter while the user interacts.
pub fn wants_preview(forced: bool, software_adapter: bool, interacting: bool) -> bool {
    forced || (software_adapter && interacting)
}

/// Whether the panels are kept as a layer repainted where they change:
/// on a software adapter, or when `--preview` forces the preview (to
/// measure it as a software adapter would run it).
pub fn caches_panels(forced_preview: bool, software_adapter: bool) -> bool {
    forced_preview || software_adapter
}

/// How the window presents its frames: as egui's examples do (vsync) on
/// a GPU; where the panels are cached (a software adapter), without
/// waiting for a vertical blank where the surface offers it (Immediate,
/// else Mailbox): presenting is a copy by the CPU there, and Immediate was
/// 3–5% faster per frame than vsync in five of five paired runs on
/// lavapipe under Xvfb.
pub fn present_mode(panels_cached: bool, offered: &[wgpu::PresentMode]) -> wgpu::PresentMode {
    use wgpu::PresentMode::{AutoVsync, Immediate, Mailbox};
    if !panels_cached {
        return AutoVsync;
    }
    [Immediate, Mailbox]
        .into_iter()
        .find(|mode| offered.contains(mode))
        .unwrap_or(AutoVsync)
}

/// The drawing quality: full (`render_strands`, `view_px`, 4× MSAA,
/// shadows), or the preview's fewer strands, smaller picture, no MSAA and
/// no shadows.
pub fn quality(render_strands: usize, view_px: [u32; 2], preview: bool) -> Quality {
    if !preview {
        return Quality {
            render_strands,
            picture_px: view_px,
            msaa_samples: helixhair_render::gpu::settings::MSAA_SAMPLES,
            shadows: true,
        };
    }
    let scale = |px: u32| ((px as f32 * PREVIEW_SCALE) as u32).max(1);
    Quality {
        render_strands: render_strands.min(PREVIEW_STRANDS),
        picture_px: [scale(view_px[0]), scale(view_px[1])],
        msaa_samples: PREVIEW_MSAA_SAMPLES,
        shadows: false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_preview_caps_the_strands_and_drops_msaa_and_shadows_only_when_asked() {
        assert_eq!(
            quality(1000, [800, 600], false),
            Quality {
                render_strands: 1000,
                picture_px: [800, 600],
                msaa_samples: 4,
                shadows: true,
            }
        );
        assert_eq!(
            quality(1000, [800, 601], true),
            Quality {
                render_strands: 300,
                picture_px: [800, 601],
                msaa_samples: 1,
                shadows: false,
            },
            "full size: copied onto the window, not scaled"
        );
        assert_eq!(quality(50, [1, 1], true).render_strands, 50);
        assert_eq!(quality(50, [1, 1], true).picture_px, [1, 1]);
        assert!(!wants_preview(false, false, true), "never on a GPU");
        assert!(!wants_preview(false, true, false), "full quality when idle");
        assert!(wants_preview(false, true, true));
        assert!(wants_preview(true, false, false));
    }

    #[test]
    fn a_software_adapter_presents_without_waiting_where_it_can() {
        use wgpu::PresentMode::{AutoVsync, Fifo, Immediate, Mailbox};
        let lavapipe = [Immediate, Mailbox, Fifo];
        assert_eq!(present_mode(true, &lavapipe), Immediate);
        assert_eq!(present_mode(true, &[Mailbox, Fifo]), Mailbox);
        assert_eq!(present_mode(true, &[Fifo]), AutoVsync);
        assert_eq!(present_mode(false, &lavapipe), AutoVsync, "a GPU: vsync");
    }

    #[test]
    fn panels_are_cached_on_a_software_adapter_and_in_a_forced_preview_only() {
        assert!(caches_panels(false, true), "lavapipe, idle or not");
        assert!(caches_panels(true, false), "--preview measures it");
        assert!(!caches_panels(false, false), "a GPU paints as egui does");
    }
}
