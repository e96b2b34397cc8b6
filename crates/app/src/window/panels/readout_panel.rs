//! The readout panel: timings, throughput, the energy plot, the compare
//! view's difference and the guard's messages.
//!
//! Stage times and energies exist on the reference engine only (the
//! guard's interventions are shown for both engines); on the batch engine
//! their places say so ([`NOT_ON_BATCH`]) rather than
//! showing zeros that would read as measurements.
//!
//! The plot is drawn with egui's painter: two polylines over the history,
//! each scaled to its own largest value (kinetic and elastic energies
//! differ by orders of magnitude), labelled with that value.

use egui::{Color32, Pos2, Rect, Sense, Stroke, Ui, Vec2};
use helixhair_physics::engine::EngineKind;

use crate::window::state::app_state::AppState;
use crate::window::state::readouts::PhysicsSample;

/// What a readout the batch engine does not have says instead.
pub const NOT_ON_BATCH: &str = "not on the batch engine";

/// Frames averaged for the numbers shown.
const AVERAGE_FRAMES: usize = 30;

/// Draws the readouts.
pub fn readouts(ui: &mut Ui, app: &AppState) {
    let r = app.readouts();
    let ms = |s: Option<f64>| s.map_or("–".to_string(), |s| format!("{:.1} ms", 1e3 * s));
    ui.label(format!(
        "frame time {} ({:.0} fps)",
        ms(r.mean_frame_secs(AVERAGE_FRAMES)),
        r.mean_frame_secs(AVERAGE_FRAMES).map_or(0.0, |s| 1.0 / s)
    ));
    ui.label(format!(
        "physics {} per frame",
        ms(r.mean_physics_secs(AVERAGE_FRAMES))
    ));
    let batch = app.sim().kind() != EngineKind::Reference;
    if batch {
        ui.label(format!("stages: {NOT_ON_BATCH} (its stages are fused)"));
    } else if let Some(s) = r.last().and_then(|last| last.stages) {
        if s.reconstruct_secs + s.forces_secs + s.mass_secs == 0.0 {
            // Exact and Block-diagonal: the generic step, stages fused.
            ui.label(format!(
                "stages (CPU, all threads): fused, {:.2} ms (the generic step)",
                1e3 * s.total_secs()
            ));
        } else {
            ui.label(format!(
            "stages (CPU, all threads): reconstruct {:.2}, forces {:.2}, mass {:.2}, solve {:.2}, integrate {:.2} ms",
            1e3 * s.reconstruct_secs,
            1e3 * s.forces_secs,
            1e3 * s.mass_secs,
            1e3 * s.solve_secs,
            1e3 * s.integrate_secs
            ));
        }
    }
    ui.label(format!(
        "{:.3e} element-steps/s; {} strands, {} elements",
        r.element_steps_per_sec(AVERAGE_FRAMES).unwrap_or(0.0),
        app.sim().engine().strand_count(),
        app.sim().engine().element_count()
    ));
    let engine = app.sim().engine();
    let how = match engine.gpu_note() {
        Some(note) => note.to_owned(),
        None if batch => "f32 SIMD, all cores".to_owned(),
        None => "f64".to_owned(),
    };
    ui.label(format!("engine: {} ({how})", app.sim().kind().label()));
    ui.label(match r.drawn_on_device() {
        Some(n) => format!("hair: {n} strands drawn from the GPU engine's buffers"),
        None => "hair: drawn strands rebuilt on the CPU from the guides".to_owned(),
    });
    if let Some(side) = engine.gpu_side() {
        ui.label(format!(
            "state: read back from the GPU {} times",
            side.state_reads()
        ));
    }
    ui.separator();
    let history: Vec<&PhysicsSample> = r.history().collect();
    if batch {
        ui.label(format!("energy: {NOT_ON_BATCH}"));
    } else {
        ui.label("energy: kinetic (orange), elastic (blue)");
        let energies: Vec<_> = history.iter().filter_map(|s| s.energies).collect();
        plot(
            ui,
            &[
                (
                    energies.iter().map(|e| e.kinetic_j).collect(),
                    Color32::from_rgb(240, 150, 40),
                ),
                (
                    energies.iter().map(|e| e.elastic_j).collect(),
                    Color32::from_rgb(80, 150, 255),
                ),
            ],
            "J",
        );
    }
    if let Some((_, m)) = app.compare() {
        ui.separator();
        let last = r.last().and_then(|s| s.difference_m);
        if let Some((rms, max)) = last {
            ui.label(format!(
                "{} vs {}: tip distance RMS {:.2} mm, max {:.2} mm",
                m.left.label(),
                m.right.label(),
                1e3 * rms,
                1e3 * max
            ));
        }
        plot(
            ui,
            &[(
                history
                    .iter()
                    .map(|s| s.difference_m.map_or(0.0, |d| d.0))
                    .collect(),
                Color32::from_rgb(220, 90, 200),
            )],
            "m",
        );
    }
    ui.separator();
    let (log, total) = r.guard_log();
    ui.label(if total == 1 {
        "guard: 1 intervention".to_owned()
    } else {
        format!("guard: {total} interventions")
    });
    egui::ScrollArea::vertical()
        .id_salt("guard log")
        .max_height(120.0)
        .stick_to_bottom(true)
        .show(ui, |ui| {
            for line in log {
                ui.small(line);
            }
        });
}

/// Draws `series` (values, colour) as polylines, each scaled to its own
/// maximum, with the maxima written at the top left.
fn plot(ui: &mut Ui, series: &[(Vec<f64>, Color32)], unit: &str) {
    let size = Vec2::new(ui.available_width(), 90.0);
    let (rect, _) = ui.allocate_exact_size(size, Sense::hover());
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect, 2.0, Color32::from_gray(24));
    let mut label = String::new();
    for (values, colour) in series {
        let max = values.iter().copied().fold(0.0, f64::max);
        label.push_str(&format!("max {max:.2e} {unit}   "));
        if values.len() < 2 || max <= 0.0 {
            continue;
        }
        let points = polyline(values, max, rect);
        painter.add(egui::Shape::line(points, Stroke::new(1.5, *colour)));
    }
    painter.text(
        rect.left_top() + Vec2::new(4.0, 2.0),
        egui::Align2::LEFT_TOP,
        label,
        egui::FontId::monospace(10.0),
        Color32::from_gray(200),
    );
}

/// Screen points of `values` (0 to `max`) across `rect`.
fn polyline(values: &[f64], max: f64, rect: Rect) -> Vec<Pos2> {
    let n = values.len().max(2) - 1;
    values
        .iter()
        .enumerate()
        .map(|(i, v)| {
            let x = rect.left() + rect.width() * i as f32 / n as f32;
            let y = rect.bottom() - rect.height() * (v / max).clamp(0.0, 1.0) as f32 * 0.85;
            Pos2::new(x, y)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_polyline_spans_the_rect_with_the_maximum_near_the_top() {
        let rect = Rect::from_min_size(Pos2::new(10.0, 20.0), Vec2::new(100.0, 50.0));
        let p = polyline(&[0.0, 2.0, 1.0], 2.0, rect);
        assert_eq!(p[0], Pos2::new(10.0, 70.0));
        assert_eq!(p[2].x, 110.0);
        assert!((p[1].y - (70.0 - 50.0 * 0.85)).abs() < 1e-4);
    }
}
