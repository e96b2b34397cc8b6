//! The style panel: simulation settings and, per strand group, every
//! physical parameter, each with its unit and a track it can be dragged
//! over. Values are written straight into the document; the frame loop
//! turns a whole drag into one undo step ([`crate::window::state::document`]).
//!
//! The tracks are the ranges the style format accepts
//! (`docs/style-format.md`, checked by the physics crate's `validate`;
//! [`TRACKS`] lists them and a test holds them to it), except gravity and
//! wind, whose useful range is far narrower than the format's. Every
//! slider comes from [`super::value_slider`]: a value outside its track is
//! shown as it is and never rewritten, and typed values may use the full
//! format range. Wide ranges (moduli, friction, time step) are
//! logarithmic.

use std::ops::RangeInclusive;

use egui::{DragValue, Ui};
use helixhair_physics::engine::EngineKind;
use helixhair_physics::{Method, NaturalShape};

use crate::style::{StrandGroup, Style};

use super::imported_summary::{group_shapes_strands, imported_summary};
use super::value_slider::{Look, scaled_slider, slider};

/// One slider's track: `(label, start, end)` in the value's own unit
/// (metres, pascals; not the µm or mm a slider may show).
pub type Track = (&'static str, f64, f64);

/// Every numeric slider's track, in the order of the panel.
pub const TRACKS: [Track; 18] = [
    ("CG iterations", 0.0, 1000.0),
    ("time step", 1e-6, 0.1),
    ("substeps", 1.0, 64.0),
    ("gravity (y)", -30.0, 30.0),
    ("wind (x)", -100.0, 100.0),
    ("length", 1e-3, 2.0),
    ("elements", 1.0, 200.0),
    ("radius", 5e-6, 5e-4),
    ("ellipticity", 1.0, 4.0),
    ("density", 100.0, 10_000.0),
    ("Young's modulus", 1e6, 1e12),
    ("shear modulus", 1e5, 1e12),
    ("internal friction", 0.0, 1e-6),
    ("air drag", 0.0, 1e-2),
    // Narrower than the format (1 mm to 1 m): real curls lie within it,
    // and on the full three decades a 30 px drag went from 12 to 120 mm.
    ("curl radius", 2e-3, 0.2),
    ("helix step (twist)", -1.0, 1.0),
    ("twist τ", -1000.0, 1000.0),
    ("κ₁ and κ₂", -1000.0, 1000.0),
];

/// Length of the curl radius slider's track, points: twice egui's
/// default, so a 30 px drag on the 2–200 mm track moves the radius by a
/// factor of 2 (it was 8 on a 100 px track over 1 mm–1 m).
pub const CURL_SLIDER_PX: f32 = 200.0;

/// How to set a curl finely, shown under the curl sliders.
pub const FINE_CONTROL: &str = "fine: drag the number, with Shift for finer";

/// The track of the slider labelled `label` (the first when `label` is
/// not in [`TRACKS`], which a test rules out).
fn track(label: &str) -> RangeInclusive<f64> {
    let (_, start, end) = TRACKS
        .iter()
        .find(|t| t.0 == label)
        .copied()
        .unwrap_or(TRACKS[0]);
    start..=end
}

/// The track of a whole-number slider.
fn count_track<N: egui::emath::Numeric>(label: &str) -> RangeInclusive<N> {
    let t = track(label);
    N::from_f64(*t.start())..=N::from_f64(*t.end())
}

/// Draws the simulation settings: engine, solver, time step, forces.
/// Typed text that is not a number is reported in `notes`.
///
/// The solver list shows only what the chosen engine runs, and choosing
/// the batch engine while the solver is one it lacks switches the solver
/// to Exact (which equals Dense, the reference solver, to round-off), so
/// the panel never makes the style invalid.
pub fn sim_settings(ui: &mut Ui, style: &mut Style, notes: &mut Vec<String>) {
    engine_selector(ui, style);
    let engine = style.engine;
    let sim = &mut style.sim;
    egui::ComboBox::from_label("solver")
        .selected_text(sim.method.label())
        .show_ui(ui, |ui| {
            for m in Method::ALL.into_iter().filter(|m| engine.runs(*m)) {
                ui.selectable_value(&mut sim.method, m, m.label());
            }
        });
    if let Method::Iterative { iterations } = &mut sim.method {
        let look = Look {
            logarithmic: true,
            ..Look::unit("")
        };
        count(ui, notes, "CG iterations", iterations, look);
    }
    number(
        ui,
        notes,
        "time step",
        &mut sim.dt_secs,
        Look::log(" s", 1e-6),
    );
    count(ui, notes, "substeps", &mut sim.substeps, Look::unit(""));
    let g = &mut sim.gravity_m_per_s2.y;
    number(ui, notes, "gravity (y)", g, Look::unit(" m/s²"));
    let wind = &mut sim.air_velocity_m_per_s.x;
    number(ui, notes, "wind (x)", wind, Look::unit(" m/s"));
    super::contact_panel::contact_settings(ui, style, notes);
    super::interaction_panel::interaction_settings(ui, style, notes);
}

/// A slider over the track [`TRACKS`] gives `label`.
fn number(ui: &mut Ui, notes: &mut Vec<String>, label: &str, value: &mut f64, look: Look) {
    slider(ui, notes, label, value, track(label), look);
}

/// A whole-number slider over the track [`TRACKS`] gives `label`.
fn count<N: egui::emath::Numeric>(
    ui: &mut Ui,
    notes: &mut Vec<String>,
    label: &str,
    value: &mut N,
    look: Look,
) {
    slider(ui, notes, label, value, count_track(label), look);
}

/// A slider in a smaller unit (`scale` of them per unit of the value)
/// over the track [`TRACKS`] gives `label`.
fn scaled(
    ui: &mut Ui,
    notes: &mut Vec<String>,
    label: &str,
    value: &mut f64,
    scale: f64,
    look: Look,
) {
    scaled_slider(ui, notes, label, value, track(label), scale, look);
}

/// The engine combo: reference (f64, every solver), batch (f32 SIMD) or
/// GPU (the batch engine's substeps on the GPU).
fn engine_selector(ui: &mut Ui, style: &mut Style) {
    let before = style.engine;
    egui::ComboBox::from_label("engine")
        .selected_text(style.engine.label())
        .show_ui(ui, |ui| {
            for kind in EngineKind::ALL {
                ui.selectable_value(&mut style.engine, kind, kind.label())
                    .on_hover_text(match kind {
                        EngineKind::Reference => {
                            "f64: every solver, stability guard, head collision, energies"
                        }
                        EngineKind::Batch => {
                            "f32 SIMD on all cores: Exact or Block-diagonal, thousands of strands"
                        }
                        EngineKind::Gpu => {
                            "the batch engine with its substeps (Exact or Block-diagonal) on the GPU; the CPU steps \
                             what the GPU cannot (the status line says why)"
                        }
                    });
            }
        });
    if style.engine != before {
        select_engine(style, style.engine);
    }
}

/// Sets `style`'s engine, switching its solver to Exact when the engine
/// cannot run the current one, and dropping an accuracy target the batch
/// engine cannot honour.
pub fn select_engine(style: &mut Style, engine: EngineKind) {
    style.engine = engine;
    if !engine.runs(style.sim.method) {
        style.sim.method = Method::Exact;
    }
    if engine != EngineKind::Reference {
        style.accuracy_target = None;
    }
}

/// Draws one group's parameters; typed text that is not a number is
/// reported in `notes`. An imported groom's strands take only the material
/// from the group: without listed or scalp roots, the shape sliders
/// (curl, length, elements) give way to a line on the groom
/// ([`imported_summary`]).
pub fn group_params(ui: &mut Ui, group: &mut StrandGroup, notes: &mut Vec<String>) {
    let shaped_here = group_shapes_strands(group);
    if let Some(imported) = &group.imported {
        ui.label(imported_summary(imported));
        if shaped_here {
            ui.label("the listed and scalp roots' strands:");
        }
    }
    let params = &mut group.params;
    if shaped_here {
        curl(ui, &mut params.natural_shape, params.elements, notes);
        number(ui, notes, "length", &mut params.length_m, Look::unit(" m"));
        count(ui, notes, "elements", &mut params.elements, Look::unit(""));
    }
    scaled(
        ui,
        notes,
        "radius",
        &mut params.radius_m,
        1e6,
        Look::unit(" µm"),
    );
    let ellipticity = &mut params.ellipticity;
    number(ui, notes, "ellipticity", ellipticity, Look::unit(""));
    let density = &mut params.density_kg_per_m3;
    number(ui, notes, "density", density, Look::unit(" kg/m³"));
    let logs: [(&str, &mut f64, Look); 4] = [
        (
            "Young's modulus",
            &mut params.youngs_modulus_pa,
            Look::log(" Pa", 1e6),
        ),
        (
            "shear modulus",
            &mut params.shear_modulus_pa,
            Look::log(" Pa", 1e5),
        ),
        (
            "internal friction",
            &mut params.internal_friction,
            Look::log(" N·m²·s", 1e-14),
        ),
        ("air drag", &mut params.air_drag, Look::log(" N·s/m²", 1e-9)),
    ];
    for (label, value, look) in logs {
        number(ui, notes, label, value, look);
    }
}

/// The curl editor: kind, then helix radius and step, or τ, κ₁, κ₂.
fn curl(ui: &mut Ui, shape: &mut NaturalShape, elements: usize, notes: &mut Vec<String>) {
    let kind = match shape {
        NaturalShape::Straight => "straight",
        NaturalShape::Uniform { .. } => "curvatures",
        NaturalShape::Helix { .. } => "helix",
        NaturalShape::PerElement(_) => "per element",
    };
    egui::ComboBox::from_label("curl")
        .selected_text(kind)
        .show_ui(ui, |ui| {
            let strains = shape.strains(elements).first().copied().unwrap_or_default();
            if ui
                .selectable_label(kind == "straight", "straight")
                .clicked()
            {
                *shape = NaturalShape::Straight;
            }
            if ui.selectable_label(kind == "helix", "helix").clicked() && kind != "helix" {
                *shape = NaturalShape::Helix {
                    radius_m: 0.012,
                    step_m: 0.03,
                };
            }
            if ui
                .selectable_label(kind == "curvatures", "curvatures")
                .clicked()
                && kind != "curvatures"
            {
                *shape = NaturalShape::Uniform {
                    twist_per_m: strains.x,
                    curvature1_per_m: strains.y,
                    curvature2_per_m: strains.z,
                };
            }
        });
    match shape {
        NaturalShape::Straight => {}
        NaturalShape::Helix { radius_m, step_m } => {
            let look = Look {
                logarithmic: true,
                ..Look::unit(" mm")
            };
            ui.scope(|ui| {
                // A longer track for the curl, which artists tune finely.
                ui.spacing_mut().slider_width = CURL_SLIDER_PX;
                scaled(ui, notes, "curl radius", radius_m, 1e3, look);
            });
            ui.small(FINE_CONTROL).on_hover_text(
                "Dragging the number moves by finer steps than the track, \
                 and ten times finer again with Shift held; typing sets it exactly.",
            );
            let look = Look {
                smallest_positive: 1e-4,
                ..look
            };
            scaled(ui, notes, "helix step (twist)", step_m, 1e3, look);
        }
        NaturalShape::Uniform {
            twist_per_m,
            curvature1_per_m,
            curvature2_per_m,
        } => {
            let look = Look::unit(" 1/m");
            number(ui, notes, "twist τ", twist_per_m, look);
            let strains = track("κ₁ and κ₂");
            slider(ui, notes, "κ₁", curvature1_per_m, strains.clone(), look);
            slider(ui, notes, "κ₂", curvature2_per_m, strains, look);
        }
        NaturalShape::PerElement(values) => {
            ui.label(format!(
                "{} per-element triples (edit in the file)",
                values.len()
            ));
        }
    }
}

/// A whole-number field for counts typed rather than dragged; a value
/// above `max` is shown as it is, never rewritten.
pub fn count_field(ui: &mut Ui, label: &str, value: &mut usize, max: usize) -> bool {
    ui.horizontal(|ui| {
        ui.label(label);
        ui.add(
            DragValue::new(value)
                .range(1..=max)
                .clamp_existing_to_range(false),
        )
        .changed()
    })
    .inner
}

#[cfg(test)]
mod tests {
    use helixhair_physics::{SimSettings, StrandParams};

    use super::*;

    /// Writes `value` into the field that the slider `label` edits.
    fn set(label: &str, value: f64, sim: &mut SimSettings, p: &mut StrandParams) {
        match label {
            "CG iterations" => {
                sim.method = Method::Iterative {
                    iterations: value as u32,
                }
            }
            "time step" => sim.dt_secs = value,
            "substeps" => sim.substeps = value as u32,
            "gravity (y)" => sim.gravity_m_per_s2.y = value,
            "wind (x)" => sim.air_velocity_m_per_s.x = value,
            "length" => p.length_m = value,
            "elements" => p.elements = value as usize,
            "radius" => p.radius_m = value,
            "ellipticity" => p.ellipticity = value,
            "density" => p.density_kg_per_m3 = value,
            "Young's modulus" => p.youngs_modulus_pa = value,
            "shear modulus" => p.shear_modulus_pa = value,
            "internal friction" => p.internal_friction = value,
            "air drag" => p.air_drag = value,
            "curl radius" => {
                p.natural_shape = NaturalShape::Helix {
                    radius_m: value,
                    step_m: 0.0,
                }
            }
            "helix step (twist)" => {
                p.natural_shape = NaturalShape::Helix {
                    radius_m: 0.01,
                    step_m: value,
                }
            }
            "twist τ" | "κ₁ and κ₂" => {
                p.natural_shape = NaturalShape::Uniform {
                    twist_per_m: value,
                    curvature1_per_m: value,
                    curvature2_per_m: value,
                }
            }
            other => panic!("no field for slider `{other}`"),
        }
    }

    /// Whether the physics crate accepts `value` in the slider's field.
    fn accepted(label: &str, value: f64) -> bool {
        let (mut sim, mut params) = (SimSettings::default(), StrandParams::default());
        set(label, value, &mut sim, &mut params);
        sim.validate().is_ok() && params.validate().is_ok()
    }

    #[test]
    fn a_short_drag_on_the_curl_radius_track_stays_within_a_factor_of_two() {
        // Issue 32, item 11: on egui's default 100 px slider, a 30 px drag
        // moved the curl radius from 12 to 120 mm (the track spanned three
        // decades, logarithmic).
        let (_, start, end): Track = TRACKS
            .iter()
            .copied()
            .find(|t| t.0 == "curl radius")
            .expect("a curl radius track");
        let factor_per_30_px = (end / start).powf(30.0 / f64::from(CURL_SLIDER_PX));
        assert!(
            factor_per_30_px < 2.0,
            "30 px moves the curl radius by a factor of {factor_per_30_px:.1}"
        );
        // And 12 mm, the curly example's, is on the track.
        assert!((start..=end).contains(&0.012));
    }

    #[test]
    fn every_track_lies_in_the_format_and_reaches_its_limits() {
        // Narrower than the format on purpose: a useful drag range.
        let narrower = ["gravity (y)", "wind (x)", "curl radius"];
        for (label, start, end) in TRACKS {
            assert!(accepted(label, start), "{label}: start {start} refused");
            assert!(accepted(label, end), "{label}: end {end} refused");
            if narrower.contains(&label) {
                continue;
            }
            // One step past the end is refused: the track is the format's.
            let past = if end.fract() == 0.0 && end > 1.0 {
                end + 1.0
            } else {
                end * 1.01
            };
            assert!(
                !accepted(label, past),
                "{label}: {past} accepted past the track"
            );
        }
    }
}
