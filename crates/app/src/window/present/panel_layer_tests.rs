//! The panels' layer: which jobs it holds and where it is repainted, on
//! hand-made jobs whose changes are known.

use egui::epaint::{ClippedPrimitive, Mesh, Primitive};
use egui::{Color32, Pos2, Rect, TextureId, pos2};

use super::*;

const SCREEN: Rect = Rect {
    min: Pos2::ZERO,
    max: pos2(1280.0, 800.0),
};

/// A job of coloured rectangles (two triangles each) on the font texture.
fn job(clip: Rect, rects: &[(Rect, Color32)]) -> ClippedPrimitive {
    let mut mesh = Mesh::default();
    for &(rect, colour) in rects {
        mesh.add_colored_rect(rect, colour);
    }
    ClippedPrimitive {
        clip_rect: clip,
        primitive: Primitive::Mesh(mesh),
    }
}

fn rect(x0: f32, y0: f32, x1: f32, y1: f32) -> Rect {
    Rect::from_min_max(pos2(x0, y0), pos2(x1, y1))
}

/// A left panel of three widgets (a background, a slider handle, a
/// label) and the 3D picture.
fn frame(handle_x: f32, label_width: f32) -> Vec<ClippedPrimitive> {
    let left = rect(0.0, 0.0, 500.0, 800.0);
    let mut picture = Mesh::with_texture(TextureId::User(7));
    picture.add_rect_with_uv(
        rect(500.0, 0.0, 950.0, 800.0),
        rect(0.0, 0.0, 1.0, 1.0),
        Color32::WHITE,
    );
    vec![
        job(
            left,
            &[
                (left, Color32::from_gray(27)),
                (
                    rect(handle_x, 100.0, handle_x + 12.0, 112.0),
                    Color32::LIGHT_GRAY,
                ),
                (rect(20.0, 300.0, 20.0 + label_width, 316.0), Color32::WHITE),
            ],
        ),
        ClippedPrimitive {
            clip_rect: SCREEN,
            primitive: Primitive::Mesh(picture),
        },
    ]
}

#[test]
fn the_layer_ends_where_the_first_picture_is_painted() {
    let jobs = frame(40.0, 30.0);
    assert_eq!(layer_len(&jobs, &[TextureId::User(7)]), 1);
    assert_eq!(layer_len(&jobs, &[TextureId::User(8)]), 2, "no picture");
    assert_eq!(layer_len(&[], &[TextureId::User(7)]), 0);
}

#[test]
fn unchanged_panels_repaint_nothing() {
    let a = frame(40.0, 30.0);
    assert!(damage(&a[..1], &a[..1], SCREEN).is_empty());
}

#[test]
fn a_moved_slider_handle_repaints_its_old_and_new_place_only() {
    let (a, b) = (frame(40.0, 30.0), frame(60.0, 30.0));
    let rects = damage(&a[..1], &b[..1], SCREEN);
    // The handle moved from x 40..52 to 60..72 on rows 100..112: the
    // background before it and the label after it are the same triangles.
    assert_eq!(rects, vec![rect(40.0, 100.0, 72.0, 112.0)]);
}

#[test]
fn a_longer_label_repaints_its_row_even_though_the_triangles_shift() {
    let (a, b) = (frame(40.0, 30.0), frame(40.0, 45.0));
    assert_eq!(
        damage(&a[..1], &b[..1], SCREEN),
        vec![rect(20.0, 300.0, 65.0, 316.0)]
    );
    // A triangle more or less (text of another length) shifts every index
    // after it; the common end still lines up.
    let mut longer = frame(40.0, 30.0);
    if let Primitive::Mesh(m) = &mut longer[0].primitive {
        let mut extra = Mesh::default();
        extra.add_colored_rect(rect(200.0, 100.0, 210.0, 110.0), Color32::RED);
        let tail = Mesh {
            indices: m.indices.split_off(6).iter().map(|i| i - 4).collect(),
            vertices: m.vertices.split_off(4),
            texture_id: m.texture_id,
        };
        m.append(extra);
        m.append(tail);
    }
    assert_eq!(
        damage(&a[..1], &longer[..1], SCREEN),
        vec![rect(200.0, 100.0, 210.0, 110.0)],
        "the handle and the label after the new rectangle are the same triangles"
    );
}

#[test]
fn changes_the_jobs_cannot_be_compared_by_repaint_everything() {
    let a = frame(40.0, 30.0);
    assert_eq!(damage(&a[..1], &a, SCREEN), vec![SCREEN], "a job more");
    let mut clipped = a.clone();
    clipped[0].clip_rect = rect(0.0, 0.0, 400.0, 800.0);
    assert_eq!(damage(&a, &clipped, SCREEN), vec![SCREEN], "another clip");
}

#[test]
fn a_change_outside_its_clip_rectangle_repaints_nothing() {
    let mut a = frame(40.0, 30.0);
    let mut b = frame(40.0, 30.0);
    for jobs in [&mut a, &mut b] {
        jobs[0].clip_rect = rect(0.0, 0.0, 500.0, 200.0);
    }
    let b2 = frame(40.0, 80.0);
    b[0].primitive = b2[0].primitive.clone();
    assert!(
        damage(&a[..1], &b[..1], SCREEN).is_empty(),
        "label below the clip"
    );
}

#[test]
fn a_repaint_clears_its_rectangle_and_clips_every_layer_job_to_it() {
    let a = frame(40.0, 30.0);
    let r = rect(40.0, 100.0, 72.0, 112.0);
    let jobs = repaint_jobs(&a[..1], &[r]);
    assert_eq!(jobs.len(), 2, "a black fill, then the panel");
    assert!(jobs.iter().all(|j| j.clip_rect == r));
    let Primitive::Mesh(fill) = &jobs[0].primitive else {
        panic!("a mesh")
    };
    assert!(fill.vertices.iter().all(|v| v.color == Color32::BLACK));
    assert_eq!(fill.calc_bounds(), r);
    // A rectangle outside a job's clip leaves that job out.
    let outside = repaint_jobs(&a[..1], &[rect(600.0, 0.0, 700.0, 10.0)]);
    assert_eq!(outside.len(), 1, "the fill only");
    // Skipped jobs keep their meshes (the renderer steps over their
    // buffers) but paint nothing.
    let skip: Vec<_> = skipped(&jobs).collect();
    assert!(skip.iter().all(|j| j.clip_rect.area() == 0.0));
}

#[test]
fn damage_grows_to_whole_pixels() {
    assert_eq!(
        to_whole_pixels(rect(10.2, 3.5, 20.1, 4.0), 1.0),
        rect(10.0, 3.0, 21.0, 4.0)
    );
    assert_eq!(
        to_whole_pixels(rect(10.2, 3.5, 20.1, 4.0), 2.0),
        rect(10.0, 3.5, 20.5, 4.0)
    );
}
