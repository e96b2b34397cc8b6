//! Motion files: known poses at and between keys, and errors located by
//! line and field.

use std::path::Path;

use glam::{DMat3, DVec3};

use super::*;

fn parse(src: &str) -> Result<Motion, MotionError> {
    Motion::from_ron(src, Path::new("shot.ron"))
}

#[test]
fn keys_are_hit_exactly_and_held_outside_them() {
    let motion = parse(
        "(version: 1, name: \"look\", keys: [
            (time_secs: 0.5),
            (time_secs: 1.0, turn_deg: 90.0, offset_m: (0.0, 0.02, 0.0)),
            (time_secs: 2.0, tilt_deg: 30.0),
        ])",
    )
    .expect("parses");
    assert_eq!(motion.name, "look");
    assert_eq!(motion.duration_secs(), 2.0);
    let (r, p) = motion.pose_at(1.0);
    let turned = r * DVec3::Z;
    // Ry(90°) takes +Z to +X.
    assert!(turned.distance(DVec3::X) < 1e-12, "{turned}");
    assert!(p.distance(DVec3::new(0.0, 0.02, 0.0)) < 1e-15);
    for t in [-1.0, 0.0, 0.5] {
        assert_eq!(motion.pose_at(t), (DMat3::IDENTITY, DVec3::ZERO), "t = {t}");
    }
    let (r, _) = motion.pose_at(5.0);
    let want = DMat3::from_rotation_x(30f64.to_radians());
    assert!((r - want).abs().to_cols_array().iter().all(|&e| e < 1e-12));
}

/// Keys on a straight line in time (equal steps): Catmull–Rom slopes are
/// the line's slope, so between the interior keys the curve is the line
/// itself; at the first and last key the head is at rest.
#[test]
fn evenly_moving_keys_interpolate_linearly_inside_and_start_at_rest() {
    let keys: Vec<String> = (0..5)
        .map(|i| format!("(time_secs: {}.0, offset_m: ({}.0, 0.0, 0.0))", i, i))
        .collect();
    let motion = parse(&format!("(version: 1, keys: [{}])", keys.join(", "))).expect("parses");
    for t in [1.0, 1.25, 1.5, 2.7, 3.0] {
        let x = motion.pose_at(t).1.x;
        assert!((x - t).abs() < 1e-12, "t = {t}: x = {x}");
    }
    let trajectory = MotionTrajectory(motion);
    let start = trajectory.motion_at(0.0);
    assert!(start.velocity_m_per_s.length() < 1e-2, "{start:?}");
    let middle = trajectory.motion_at(2.0);
    assert!((middle.velocity_m_per_s.x - 1.0).abs() < 1e-6, "{middle:?}");
}

#[test]
fn a_saved_motion_reads_back_the_same() {
    let motion = Motion {
        version: MOTION_VERSION,
        name: "round trip".into(),
        keys: vec![
            MotionKey::default(),
            MotionKey {
                time_secs: 0.1 + 0.2,
                turn_deg: -12.345678901234567,
                tilt_deg: 1e-9,
                roll_deg: 3.0,
                offset_m: DVec3::new(0.001, -0.002, 0.003),
            },
        ],
    };
    let dir = std::env::temp_dir().join(format!("helixhair-motion-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch folder");
    let path = dir.join("shot.ron");
    motion.save(&path).expect("saves");
    assert_eq!(Motion::load(&path).expect("loads"), motion);
    std::fs::remove_dir_all(&dir).expect("clean up");
}

#[test]
fn errors_name_the_file_line_and_field() {
    let cases = [
        (
            "(version: 1, keys: [\n  (time_secs: 0.0),\n  (time_secs: 1.0, turn_dg: 3.0),\n])",
            "shot.ron:3:20: field `keys[1].turn_dg`: Unexpected field named `turn_dg`",
        ),
        (
            "(version: 1, keys: [\n  (time_secs: 1.0),\n  (time_secs: 0.5),\n])",
            "shot.ron:3:4: field `keys[1].time_secs`: 0.5 s does not come after the previous \
             key's 1 s: times must increase",
        ),
        (
            "(version: 2, keys: [(time_secs: 0.0)])",
            "shot.ron:1:2: field `version`: version 2 is not supported",
        ),
        (
            "(version: 1, keys: [])",
            "shot.ron:1:14: field `keys`: a motion needs at least one key",
        ),
        (
            "(version: 1, keys: [\n  (time_secs: 0.0, offset_m: (0.0, 25.0, 0.0)),\n])",
            "shot.ron:2:20: field `keys[0].offset_m`: each coordinate must be finite and within",
        ),
        (
            "(version: 1, keys: [\n  (time_secs: \"soon\"),\n])",
            "shot.ron:2:",
        ),
    ];
    // Positions are where the field's name starts, as for styles.
    for (src, want) in cases {
        let error = parse(src).expect_err("refused").to_string();
        assert!(error.starts_with(want), "got  {error}\nwant {want}");
    }
    let missing = Motion::load(Path::new("no/such/shot.ron")).expect_err("no file");
    assert!(
        missing
            .to_string()
            .starts_with("no/such/shot.ron: cannot read the motion file"),
        "{missing}"
    );
}
