//! The automatic choice of solver and element count against the error
//! model built into the binary, and against a fresh run: the chosen
//! setting must really meet the target on the scene it was measured on.

use helixhair_app::bench::accuracy::REFERENCE;
use helixhair_app::bench::scenes::{CurlClass, RunSetting, Scene, run_scene, tip_rms_error};
use helixhair_app::sim::auto_choice::choose;
use helixhair_app::sim::error_model::ErrorModel;
use helixhair_physics::StrandParams;

/// One percent of the strand's length: a tip error an artist cannot see on
/// a moving strand.
const TARGET: f64 = 0.01;
const FRAME_SECS: f64 = 1.0 / 60.0;

fn model() -> ErrorModel {
    ErrorModel::built_in().expect("the built-in error model parses")
}

fn params(class: CurlClass, length_m: f64) -> StrandParams {
    StrandParams {
        length_m,
        natural_shape: class.shape(),
        ..StrandParams::default()
    }
}

#[test]
fn the_built_in_model_covers_every_class_and_solver() {
    let model = model();
    assert_eq!(model.classes.len(), CurlClass::ALL.len());
    for class in CurlClass::ALL {
        let runs = model
            .entries
            .iter()
            .filter(|e| e.class == class.name())
            .count();
        assert!(runs >= 50, "{}: {runs} runs", class.name());
    }
}

#[test]
fn straight_hair_gets_fewer_elements_than_coils_and_long_hair_more() {
    let model = model();
    let elements = |class, length| {
        choose(&model, &params(class, length), FRAME_SECS, 1, TARGET)
            .expect("a choice")
            .elements
    };
    let straight = elements(CurlClass::Straight, 0.2);
    let coily = elements(CurlClass::Coily, 0.2);
    assert!(straight < coily, "straight {straight}, coily {coily}");
    assert!(elements(CurlClass::Curly, 0.4) > elements(CurlClass::Curly, 0.2));
}

#[test]
fn a_looser_curl_than_any_class_uses_the_next_tighter_class() {
    let model = model();
    let mut p = params(CurlClass::Curly, 0.2);
    p.natural_shape = helixhair_physics::NaturalShape::Helix {
        radius_m: 0.02,
        step_m: 0.06,
    };
    let choice = choose(&model, &p, FRAME_SECS, 1, TARGET).expect("a choice");
    assert_eq!(choice.class, "curly");
}

#[test]
fn the_chosen_setting_meets_the_target_on_a_fresh_run() {
    // Run the choice for curly hair again, against the fine Dense
    // reference, and measure: the model's number must hold.
    let model = model();
    let p = params(CurlClass::Curly, 0.2);
    let choice = choose(&model, &p, FRAME_SECS, 1, TARGET).expect("a choice");
    assert!(choice.target_met, "{choice:?}");
    let scene = Scene::bounce(CurlClass::Curly, 3.0);
    let run = run_scene(
        &scene,
        RunSetting {
            method: choice.method,
            elements: choice.elements,
            substeps: choice.substeps,
        },
    );
    let truth = run_scene(&scene, REFERENCE);
    let error = tip_rms_error(&run, &truth, 0.2);
    assert!(error <= TARGET, "measured {error} for {choice:?}");
}
