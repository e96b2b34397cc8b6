//! The panels as a cached layer: egui's paint jobs split into the panels
//! (everything painted before the first 3D picture) and the overlay (the
//! pictures and everything after them: labels over the view, menus,
//! tooltips), and the parts of the panels that changed since the last
//! frame.
//!
//! Why: on a CPU rasteriser (lavapipe) painting the panels is as dear as
//! drawing the hair: each frame shades every panel pixel again, about a
//! million of them, although between two frames only a slider's handle or
//! a readout's digits change (docs/window.md). So the window
//! keeps the panels in a texture, repaints only the rectangles where their
//! triangles differ from the last frame's, copies the texture to the
//! screen and paints the overlay on top ([`super::egui_paint`]).
//!
//! The 3D pictures, when drawn at the view's size in the window's byte
//! order, are copied onto the screen too ([`picture_copy`]) instead of
//! being painted as textures: painting samples a texture per pixel, which
//! a CPU rasteriser does slowly.
//!
//! A rectangle is found by comparing the two frames' triangles job by
//! job: the triangles both frames share at the start and at the end of a
//! job are drawn in the same order on the same pixels, so only the pixels
//! under the triangles in between (old and new) can differ. Everything
//! else (another job count, clip rectangles, textures, a paint callback)
//! repaints the whole layer, and so does a frame in which egui changes its
//! own textures (a glyph drawn at a new sub-pixel offset enters the font
//! atlas): those are the first frames, after which the median frame on the
//! default style repaints about 47,000 of the window's million pixels.
//! A partly repainted layer gives the same bytes as egui painting the
//! whole frame (`egui_paint`'s test).

use egui::epaint::{ClippedPrimitive, Mesh, Primitive};
use egui::{Color32, Pos2, Rect, TextureId};

/// Index of the first job that paints one of `pictures` (the 3D views):
/// the jobs before it are the panels' layer, the rest the overlay. With no
/// picture every job is the layer.
pub fn layer_len(jobs: &[ClippedPrimitive], pictures: &[TextureId]) -> usize {
    jobs.iter()
        .position(|job| match &job.primitive {
            Primitive::Mesh(mesh) => pictures.contains(&mesh.texture_id),
            Primitive::Callback(_) => false,
        })
        .unwrap_or(jobs.len())
}

/// Where the layer `new` differs from `old` (points): one rectangle per
/// changed job, or the whole `screen` when the jobs cannot be compared.
/// Empty when nothing changed.
pub fn damage(old: &[ClippedPrimitive], new: &[ClippedPrimitive], screen: Rect) -> Vec<Rect> {
    if old.len() != new.len() {
        return vec![screen];
    }
    let mut rects = Vec::new();
    for (a, b) in old.iter().zip(new) {
        let (Primitive::Mesh(ma), Primitive::Mesh(mb)) = (&a.primitive, &b.primitive) else {
            return vec![screen];
        };
        if a.clip_rect != b.clip_rect || ma.texture_id != mb.texture_id {
            return vec![screen];
        }
        if ma == mb {
            continue;
        }
        let changed = changed_bounds(ma, mb).intersect(b.clip_rect);
        if changed.is_positive() {
            rects.push(changed);
        }
    }
    rects
}

/// Bounding box of the triangles of `a` and `b` outside their common
/// first and last triangles.
fn changed_bounds(a: &Mesh, b: &Mesh) -> Rect {
    let tri = |m: &Mesh, t: usize| -> [egui::epaint::Vertex; 3] {
        std::array::from_fn(|k| m.vertices[m.indices[3 * t + k] as usize])
    };
    let (na, nb) = (a.indices.len() / 3, b.indices.len() / 3);
    let same_start = (0..na.min(nb))
        .take_while(|&t| tri(a, t) == tri(b, t))
        .count();
    let same_end = (0..na.min(nb) - same_start)
        .take_while(|&t| tri(a, na - 1 - t) == tri(b, nb - 1 - t))
        .count();
    let mut bounds = Rect::NOTHING;
    for (m, n) in [(a, na), (b, nb)] {
        for t in same_start..n - same_end {
            for v in tri(m, t) {
                bounds.extend_with(v.pos);
            }
        }
    }
    bounds
}

/// `rect` grown to whole pixels at `pixels_per_point`, so that a fill and
/// the scissor rectangles egui derives from it cover the same pixels.
pub fn to_whole_pixels(rect: Rect, pixels_per_point: f32) -> Rect {
    let ppp = pixels_per_point;
    Rect::from_min_max(
        Pos2::new(
            (rect.min.x * ppp).floor() / ppp,
            (rect.min.y * ppp).floor() / ppp,
        ),
        Pos2::new(
            (rect.max.x * ppp).ceil() / ppp,
            (rect.max.y * ppp).ceil() / ppp,
        ),
    )
}

/// The jobs that repaint the layer inside `rects` only: for each
/// rectangle, black (as the layer's clear colour) and then every layer job
/// clipped to it.
pub fn repaint_jobs(layer: &[ClippedPrimitive], rects: &[Rect]) -> Vec<ClippedPrimitive> {
    let mut jobs = Vec::new();
    for &rect in rects {
        let mut fill = Mesh::default();
        fill.add_colored_rect(rect, Color32::BLACK);
        jobs.push(ClippedPrimitive {
            clip_rect: rect,
            primitive: Primitive::Mesh(fill),
        });
        for job in layer {
            let clip_rect = job.clip_rect.intersect(rect);
            if clip_rect.is_positive() {
                jobs.push(ClippedPrimitive {
                    clip_rect,
                    primitive: job.primitive.clone(),
                });
            }
        }
    }
    jobs
}

/// Where a 3D picture is copied onto the window instead of being painted
/// as a texture: `job` paints one of `pictures` (texture and size,
/// pixels) as one unclipped rectangle of the picture's own size (give or
/// take the pixel egui's layout rounds off). Returns the picture's index,
/// the top-left pixel and the size copied (cut to `screen_px`).
pub fn picture_copy(
    job: &ClippedPrimitive,
    pictures: &[(TextureId, [u32; 2])],
    pixels_per_point: f32,
    screen_px: [u32; 2],
) -> Option<(usize, [u32; 2], [u32; 2])> {
    let Primitive::Mesh(mesh) = &job.primitive else {
        return None;
    };
    let index = pictures.iter().position(|p| p.0 == mesh.texture_id)?;
    let size_px = pictures[index].1;
    let bounds = mesh.calc_bounds();
    let one_rect = mesh.vertices.len() == 4 && mesh.indices.len() == 6;
    let unclipped = job.clip_rect.contains_rect(bounds);
    let px = |v: f32| (v * pixels_per_point).round();
    let (x, y) = (px(bounds.min.x), px(bounds.min.y));
    let (w, h) = (px(bounds.max.x) - x, px(bounds.max.y) - y);
    let fits = (w - size_px[0] as f32).abs() <= 1.0 && (h - size_px[1] as f32).abs() <= 1.0;
    if !(one_rect && unclipped && fits && x >= 0.0 && y >= 0.0) {
        return None;
    }
    let origin = [x as u32, y as u32];
    let size = [
        size_px[0].min(screen_px[0].saturating_sub(origin[0])),
        size_px[1].min(screen_px[1].saturating_sub(origin[1])),
    ];
    (size[0] > 0 && size[1] > 0).then_some((index, origin, size))
}

/// `jobs` with their clip rectangles emptied: egui's renderer then skips
/// them while still stepping over their buffers, so one upload serves a
/// pass that paints only the jobs after them.
pub fn skipped(jobs: &[ClippedPrimitive]) -> impl Iterator<Item = ClippedPrimitive> + '_ {
    jobs.iter().map(|job| ClippedPrimitive {
        clip_rect: Rect::from_min_size(Pos2::ZERO, egui::Vec2::ZERO),
        primitive: job.primitive.clone(),
    })
}

#[cfg(test)]
#[path = "panel_layer_tests.rs"]
mod tests;
