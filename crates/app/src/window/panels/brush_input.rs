//! The pointer as a brush in the 3D view: where it touches, the circle
//! showing its reach, and the press, drag and release that make a stroke.
//!
//! Under the pointer the brush sits where the camera's ray first meets the
//! hair (within half the brush's radius of a hair point) or the head
//! ([`crate::window::present::pick`]); the circle drawn around the pointer
//! is the brush sphere's radius at that depth. A stroke begins on press
//! where the brush touches (nothing happens on empty space). Comb and Grab
//! then move the brush in the plane through that point facing the camera,
//! as a hand moves a comb at the depth it entered the hair; the painting
//! tools follow the surface under the pointer. Release ends the stroke
//! ([`AppState::end_stroke`]). The Mask tool paints instead: the strands
//! rooted under the brush are masked from every tool (Shift unmasks).

use egui::{PointerButton, Response, Ui};
use glam::Vec2;

use crate::brush::host::hair_points_world;
use crate::window::present::pick::{pointer_ray, radius_pt, ray_hair, ray_mesh, ray_plane};
use crate::window::state::app_state::AppState;
use crate::window::state::brush_state::ToolKind;

use super::view_state::ViewState;

/// Turns pointer input over `rect` (the main view) into brush strokes and
/// draws the brush.
pub fn brush_input(
    ui: &mut Ui,
    app: &mut AppState,
    view: &mut ViewState,
    response: &Response,
    rect: egui::Rect,
) {
    if app.brush().active.is_some() && !response.dragged_by(PointerButton::Primary) {
        app.end_stroke();
        view.brush_plane_m = None;
    }
    let Some(pointer) = response.hover_pos().or(response.interact_pointer_pos()) else {
        view.brush_at_m = None;
        return;
    };
    let size = Vec2::new(rect.width(), rect.height());
    let local = pointer - rect.min;
    let ray = pointer_ray(&view.camera, size, Vec2::new(local.x, local.y));
    let radius_m = app.brush().settings.radius_m;
    let surface = || {
        let head = app.sim().engine().head();
        let posed = app
            .head_mesh()
            .posed(head.world_from_body.as_mat3(), head.position_m.as_vec3());
        let hair = hair_points_world(app.sim().engine());
        let t_head = ray_mesh(&ray, &posed.mesh);
        let t_hair = ray_hair(&ray, &hair, 0.5 * radius_m);
        match (t_head, t_hair) {
            (Some(a), Some(b)) => Some(ray.at(a.min(b))),
            (a, b) => a.or(b).map(|t| ray.at(t)),
        }
    };
    let drives = matches!(app.brush().settings.kind, ToolKind::Comb | ToolKind::Grab);
    let facing = (view.camera.target_m - view.camera.eye_m())
        .as_dvec3()
        .normalize();
    let at = match (view.brush_plane_m, app.brush().active.is_some()) {
        (Some(plane), true) if drives => ray_plane(&ray, plane, facing),
        (Some(plane), true) => surface().or_else(|| ray_plane(&ray, plane, facing)),
        _ => surface(),
    };
    view.brush_at_m = at;
    if app.brush().settings.kind == ToolKind::Mask {
        let painting = response.dragged_by(PointerButton::Primary)
            || response.clicked_by(PointerButton::Primary);
        if painting && let Some(p) = at {
            let unmask = ui.input(|i| i.modifiers.shift);
            app.paint_mask(p, unmask);
        }
    } else if response.drag_started_by(PointerButton::Primary)
        && let Some(start) = at
        && app.begin_stroke(start)
    {
        view.brush_plane_m = Some(start);
    } else if app.brush().active.is_some()
        && let Some(p) = at
    {
        app.move_brush(p);
    }
    let target_depth_m = f64::from(view.camera.distance_m);
    let centre = at.unwrap_or_else(|| ray.at(target_depth_m));
    let r = radius_pt(&view.camera, centre, radius_m, rect.height());
    let colour = if at.is_some() {
        egui::Color32::from_rgb(255, 220, 120)
    } else {
        egui::Color32::from_gray(140)
    };
    ui.painter()
        .circle_stroke(pointer, r, egui::Stroke::new(1.5, colour));
}
