//! The style panel: simulation settings and, per strand group, every
//! physical parameter, each with its unit and a range it can be dragged
//! over. Values are written straight into the document; the frame loop
//! turns a whole drag into one undo step ([`super::document`]).
//!
//! Ranges are those the style format accepts (`docs/style-format.md`),
//! narrowed where the full range is useless to drag over (element counts
//! to 60, curl radius to 20 cm); typed values may use the full range. Wide
//! ranges (moduli, friction, time step) are logarithmic.

use egui::{DragValue, Slider, Ui};
use helixhair_physics::engine::EngineKind;
use helixhair_physics::{Method, NaturalShape, StrandParams};

use crate::style::Style;

/// Draws the simulation settings: engine, solver, time step, forces.
///
/// The solver list shows only what the chosen engine runs, and choosing
/// the batch engine while the solver is one it lacks switches the solver
/// to Exact (which equals Dense, the reference solver, to round-off), so
/// the panel never makes the style invalid.
pub fn sim_settings(ui: &mut Ui, style: &mut Style) {
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
        ui.add(Slider::new(iterations, 0..=50).text("CG iterations"));
    }
    ui.add(
        Slider::new(&mut sim.dt_secs, 1e-4..=0.1)
            .logarithmic(true)
            .text("time step")
            .suffix(" s"),
    );
    ui.add(Slider::new(&mut sim.substeps, 1..=64).text("substeps"));
    ui.add(
        Slider::new(&mut sim.gravity_m_per_s2.y, -30.0..=0.0)
            .text("gravity (y)")
            .suffix(" m/s²"),
    );
    ui.add(
        Slider::new(&mut sim.air_velocity_m_per_s.x, -10.0..=10.0)
            .text("wind (x)")
            .suffix(" m/s"),
    );
}

/// The engine combo: reference (f64, every solver) or batch (f32 SIMD).
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
    if engine == EngineKind::Batch {
        style.accuracy_target = None;
    }
}

/// Draws one group's parameters.
pub fn group_params(ui: &mut Ui, params: &mut StrandParams) {
    curl(ui, &mut params.natural_shape, params.elements);
    ui.add(
        Slider::new(&mut params.length_m, 0.02..=1.0)
            .text("length")
            .suffix(" m"),
    );
    ui.add(Slider::new(&mut params.elements, 1..=60).text("elements"));
    micro(ui, "radius", &mut params.radius_m, 5e-6..=5e-4, 1e6, " µm");
    ui.add(Slider::new(&mut params.ellipticity, 1.0..=4.0).text("ellipticity"));
    ui.add(
        Slider::new(&mut params.density_kg_per_m3, 100.0..=10_000.0)
            .text("density")
            .suffix(" kg/m³"),
    );
    log(
        ui,
        "Young's modulus",
        &mut params.youngs_modulus_pa,
        1e6..=1e12,
        " Pa",
    );
    log(
        ui,
        "shear modulus",
        &mut params.shear_modulus_pa,
        1e5..=1e12,
        " Pa",
    );
    log(
        ui,
        "internal friction",
        &mut params.internal_friction,
        1e-14..=1e-6,
        " N·m²·s",
    );
    log(ui, "air drag", &mut params.air_drag, 1e-9..=1e-2, " N·s/m²");
}

/// A logarithmic slider with scientific-notation readout.
fn log(
    ui: &mut Ui,
    label: &str,
    value: &mut f64,
    range: std::ops::RangeInclusive<f64>,
    unit: &str,
) {
    ui.add(
        Slider::new(value, range)
            .logarithmic(true)
            .text(label)
            .suffix(unit)
            .custom_formatter(|v, _| format!("{v:.3e}")),
    );
}

/// A slider shown in a smaller unit (`scale` per unit of the value).
fn micro(
    ui: &mut Ui,
    label: &str,
    value: &mut f64,
    range: std::ops::RangeInclusive<f64>,
    scale: f64,
    unit: &str,
) {
    let mut shown = *value * scale;
    let shown_range = range.start() * scale..=range.end() * scale;
    if ui
        .add(
            Slider::new(&mut shown, shown_range)
                .text(label)
                .suffix(unit),
        )
        .changed()
    {
        *value = shown / scale;
    }
}

/// The curl editor: kind, then helix radius and step, or τ, κ₁, κ₂.
fn curl(ui: &mut Ui, shape: &mut NaturalShape, elements: usize) {
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
            micro(ui, "curl radius", radius_m, 0.001..=0.2, 1e3, " mm");
            micro(ui, "helix step (twist)", step_m, -0.2..=0.2, 1e3, " mm");
        }
        NaturalShape::Uniform {
            twist_per_m,
            curvature1_per_m,
            curvature2_per_m,
        } => {
            let range = -300.0..=300.0;
            ui.add(
                Slider::new(twist_per_m, range.clone())
                    .text("twist τ")
                    .suffix(" 1/m"),
            );
            ui.add(
                Slider::new(curvature1_per_m, range.clone())
                    .text("κ₁")
                    .suffix(" 1/m"),
            );
            ui.add(
                Slider::new(curvature2_per_m, range)
                    .text("κ₂")
                    .suffix(" 1/m"),
            );
        }
        NaturalShape::PerElement(values) => {
            ui.label(format!(
                "{} per-element triples (edit in the file)",
                values.len()
            ));
        }
    }
}

/// A whole-number field for counts typed rather than dragged.
pub fn count_field(ui: &mut Ui, label: &str, value: &mut usize, max: usize) -> bool {
    ui.horizontal(|ui| {
        ui.label(label);
        ui.add(DragValue::new(value).range(1..=max)).changed()
    })
    .inner
}
