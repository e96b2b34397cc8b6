//! Tests of [`super::head_of_style`] (kept apart to keep the module short).

use std::path::{Path, PathBuf};

use glam::{DVec3, Vec3};
use helixhair_render::head_generate::default_head;
use helixhair_render::obj::write_head_obj;

use super::super::app_state::AppState;
use crate::window::live::drawn::DrawnCache;
use crate::window::live::head_motion::Clip;
use helixhair_physics::engine::EngineKind;
use helixhair_physics::{SimSettings, StrandParams};

use crate::style::imported::{ImportedStrand, ImportedStrands};
use crate::style::{DEFAULT_REFERENCE, Root, STYLE_VERSION, StrandGroup, Style};

/// Where the test's head stands: 1.5 m up and 0.3 m aside, as a scanned
/// bust stands in its file (Sintel's 1.5 m up).
const HEAD_AT_M: DVec3 = DVec3::new(0.3, 1.5, 0.0);

/// Four straight 10 cm strands on the crown of the default head moved to
/// [`HEAD_AT_M`], as an imported style naming that head; returns the
/// style's path.
fn lifted_groom(dir: &Path) -> PathBuf {
    std::fs::create_dir_all(dir).expect("scratch folder");
    let mut head = default_head();
    for p in &mut head.mesh.positions {
        *p += HEAD_AT_M.as_vec3();
    }
    let crown = head
        .mesh
        .positions
        .iter()
        .copied()
        .fold(Vec3::splat(f32::MIN), |a, b| if b.y > a.y { b } else { a })
        .as_dvec3();
    std::fs::write(dir.join("head.obj"), write_head_obj(&head, "lifted")).expect("head");
    let strands = (0..4)
        .map(|i| ImportedStrand {
            root: Root {
                position_m: crown + DVec3::new(0.0, 0.0, 0.01 * f64::from(i) - 0.015),
                direction: DVec3::new(1.0, 0.3, 0.0),
                reference: DEFAULT_REFERENCE,
            },
            element_length_m: 0.02,
            strains: vec![DVec3::ZERO; 5],
            natural: vec![DVec3::ZERO; 5],
            guide: true,
            stiffness_scale: 1.0,
        })
        .collect();
    let style = Style {
        version: STYLE_VERSION,
        name: "lifted".into(),
        sim: SimSettings::default(),
        engine: EngineKind::Reference,
        accuracy_target: None,
        groups: vec![StrandGroup {
            name: "imported".into(),
            params: StrandParams::default(),
            roots: Vec::new(),
            scalp: None,
            render: None,
            imported: Some(ImportedStrands {
                source: "groom.obj".into(),
                head: Some("head.obj".into()),
                collider: None,
                strands,
            }),
            edits: Vec::new(),
        }],
    };
    let path = dir.join("lifted.ron");
    style.save(&path).expect("saves");
    path
}

/// Largest distance of any simulated point from `centre_m`, metres.
fn reach_m(app: &AppState, centre_m: DVec3) -> f64 {
    let engine = app.sim.engine();
    (0..engine.strand_count())
        .flat_map(|i| engine.boundary_points_world(i))
        .map(|p| (p - centre_m).length())
        .fold(0.0, f64::max)
}

#[test]
fn an_imported_groom_brings_its_head_draws_and_turns_about_it() {
    let dir = std::env::temp_dir().join(format!("helixhair-head-of-style-{}", std::process::id()));
    let path = lifted_groom(&dir);
    let style = Style::load(&path).expect("loads");
    let mut app = AppState::new(style.clone(), Some(&path)).expect("opens");
    assert_eq!(
        app.head_files.as_ref().map(|f| f.drawn.as_path()),
        Some(dir.join("head.obj").as_path())
    );
    assert!(app.sim.engine().collider().is_some());
    let pivot = app.head.pivot_m;
    assert!(
        (pivot - HEAD_AT_M).length() < 0.15,
        "pivot {pivot} beside the head"
    );

    // The window draws imported guides (it drew nothing: no strand counted).
    let drawn = DrawnCache::default().strands(&style, &app.head_mesh, app.sim.engine(), 100);
    assert_eq!(drawn.expect("drawn").strands.strand_count(), 4);

    // A 20° nod about the head's own pivot keeps the hair by the head;
    // about the origin, 1.5 m below, it would swing the hair 0.5 m.
    let start = reach_m(&app, pivot);
    app.play(Clip::Nod);
    let mut farthest: f64 = 0.0;
    for _ in 0..60 {
        app.step_frame();
        farthest = farthest.max(reach_m(&app, pivot));
    }
    assert!(
        farthest < start + 0.05,
        "the hair went {farthest} m from the pivot, {start} m at rest"
    );

    // Issue 32, item 6: a style naming a collider apart from its head
    // draws the head and collides with the collider (here the head grown
    // by a third about its middle, so the drawn crown lies inside it).
    let mut grown = default_head();
    for p in &mut grown.mesh.positions {
        *p = *p * 1.3 + HEAD_AT_M.as_vec3();
    }
    std::fs::write(dir.join("collider.obj"), write_head_obj(&grown, "big")).expect("collider");
    let mut with_collider = style.clone();
    let imported = with_collider.groups[0].imported.as_mut().expect("imported");
    imported.collider = Some("collider.obj".into());
    let collided = dir.join("collided.ron");
    with_collider.save(&collided).expect("saves");
    app.load(&collided);
    let files = app.head_files.clone().expect("its own head");
    assert_eq!(files.drawn, dir.join("head.obj"));
    assert_eq!(files.collider, dir.join("collider.obj"));
    let crown = app
        .head_mesh
        .mesh
        .positions
        .iter()
        .fold(f32::MIN, |top, p| top.max(p.y));
    assert!(
        (f64::from(crown) - HEAD_AT_M.y - 0.1).abs() < 0.05,
        "the drawn head is the head, not the grown collider (crown {crown})"
    );
    let field = app.sim.engine().collider().expect("collides");
    let crown_point = DVec3::new(HEAD_AT_M.x, f64::from(crown), HEAD_AT_M.z);
    let (distance_m, _) = field.sample(crown_point).expect("inside the field's box");
    assert!(
        distance_m < -0.01,
        "the drawn crown is {distance_m} m from the collider: not the grown mesh"
    );

    // A style without a head of its own brings the default head back.
    let plain = dir.join("plain.ron");
    super::super::default_style::default_style(4)
        .save(&plain)
        .expect("saves");
    app.load(&plain);
    assert_eq!(app.head_files, None);
    assert_eq!(app.head.pivot_m, DVec3::ZERO);
    let _ = std::fs::remove_dir_all(dir);
}
