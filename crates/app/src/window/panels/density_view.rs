//! The density grid's view: a window with one slice of the hair–hair
//! model's grid (docs/volume.md), the plane through the grid's middle
//! facing the side of the head (y up, z across), each cell shaded by the
//! hair's density there as a fraction of the typical rest density ρ̄, and
//! red where the density is above its rest threshold (where the pressure
//! pushes).
//!
//! It reads the last frame's field from either engine
//! (`Engine::volume_field`); with the model off it says so. The
//! window's open state lives in egui's memory, so the view needs no field
//! of its own in the app's state.

use egui::{Color32, Id, Pos2, Rect, Sense, Ui, Vec2};

use crate::window::state::app_state::AppState;

/// Side of the slice's drawing, points.
const SIZE_PT: f32 = 300.0;

fn open_id() -> Id {
    Id::unique("density_view_open")
}

/// The style panel's checkbox that opens the view.
pub fn toggle(ui: &mut Ui) {
    let id = open_id();
    let mut open = ui.ctx().data(|d| d.get_temp::<bool>(id).unwrap_or(false));
    if ui.checkbox(&mut open, "show the density grid").changed() {
        ui.ctx().data_mut(|d| d.insert_temp(id, open));
    }
}

/// Draws the view's window when it is open.
pub fn show(ctx: &egui::Context, app: &AppState) {
    let id = open_id();
    let mut open = ctx.data(|d| d.get_temp::<bool>(id).unwrap_or(false));
    if !open {
        return;
    }
    egui::Window::new("Hair density")
        .open(&mut open)
        .default_width(SIZE_PT + 20.0)
        .show(ctx, |ui| slice(ui, app));
    ctx.data_mut(|d| d.insert_temp(id, open));
}

fn slice(ui: &mut Ui, app: &AppState) {
    let Some((rest, field)) = app.sim().engine().volume_field() else {
        ui.label("the hair–hair interaction is off (or not yet stepped)");
        return;
    };
    let density = field.density_kg_per_m3();
    let excess = field.excess();
    let grid = &rest.grid;
    if density.len() != grid.node_count() {
        ui.label("no frame stepped with the model yet");
        return;
    }
    let [nx, ny, nz] = grid.dims;
    let i = nx / 2;
    let cell = SIZE_PT / ny.max(nz) as f32;
    let (rect, _) = ui.allocate_exact_size(
        Vec2::new(nz as f32 * cell, ny as f32 * cell),
        Sense::hover(),
    );
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect, 0.0, Color32::from_gray(16));
    for j in 0..ny {
        for k in 0..nz {
            let n = grid.index(i, j, k);
            let fraction = (density[n] / rest.typical_kg_per_m3).min(2.0) / 2.0;
            if fraction <= 0.0 {
                continue;
            }
            let shade = (40.0 + 215.0 * fraction) as u8;
            let colour = if excess[n] > 0.0 {
                Color32::from_rgb(shade, 40, 40)
            } else {
                Color32::from_gray(shade)
            };
            // Row j = 0 is the bottom of the grid.
            let min = Pos2::new(
                rect.min.x + k as f32 * cell,
                rect.max.y - (j + 1) as f32 * cell,
            );
            painter.rect_filled(Rect::from_min_size(min, Vec2::splat(cell)), 0.0, colour);
        }
    }
    ui.label(format!(
        "slice x = {:.1} cm of {nx} × {ny} × {nz} nodes, cell {:.1} cm; white: 2 ρ̄ = {:.2} kg/m³; red: above the rest threshold",
        100.0 * grid.node_position(i, 0, 0).x,
        100.0 * grid.cell_m,
        2.0 * rest.typical_kg_per_m3
    ));
}
