//! Known answers of the strand shaping: helices whose axes and phases are
//! known, and the ends of clumping and following.

use super::*;

/// A helix about the vertical line through `centre`, radius `r`,
/// falling `pitch` per turn, starting at `phase`, `n` points over
/// `turns` turns.
fn helix(centre: Vec3, r: f32, pitch: f32, phase: f32, turns: f32, n: usize) -> Vec<Vec3> {
    (0..n)
        .map(|k| {
            let t = turns * std::f32::consts::TAU * k as f32 / (n - 1) as f32;
            centre
                + Vec3::new(
                    r * (t + phase).cos(),
                    -pitch * t / std::f32::consts::TAU,
                    r * (t + phase).sin(),
                )
        })
        .collect()
}

#[test]
fn the_centreline_of_a_helix_is_its_axis_away_from_the_ends() {
    let r = 0.01;
    let points = helix(Vec3::ZERO, r, 0.03, 0.0, 6.0, 601);
    // One turn's arc: √((2πr)² + pitch²).
    let period = ((std::f32::consts::TAU * r).powi(2) + 0.03f32.powi(2)).sqrt();
    let axis = centreline(&points, period);
    for p in &axis[120..480] {
        assert!(Vec3::new(p.x, 0.0, p.z).length() < 0.1 * r, "{p}");
    }
}

#[test]
fn a_clumped_curl_keeps_its_own_phase_and_radius_around_the_guides_axis() {
    // Known answer: a guide helix about x = 0 and a strand helix of the
    // same radius about x = 0.02, half a turn out of phase. Clumped
    // fully, the strand's axis goes onto the guide's at the tip, while
    // the strand stays a curl of its own radius and phase (gathering
    // its points, as `clump_onto` does, would lay it on the guide).
    let r = 0.008;
    let pitch = 0.03;
    let period = ((std::f32::consts::TAU * r).powi(2) + pitch * pitch).sqrt();
    let guide = helix(Vec3::ZERO, r, pitch, 0.0, 6.0, 601);
    let mut strand = helix(Vec3::X * 0.02, r, pitch, std::f32::consts::PI, 6.0, 601);
    let root = strand[0];
    clump_curl_onto(&mut strand, &guide, 1.0, period, (0.0, 1.0));
    assert!((strand[0] - root).length() < 1e-6, "the root moved");
    // Near the tip (away from the end's averaging), one turn back: the
    // axis has moved (arc length s of L) s/L of the way from x = 0.02
    // to the guide's at x = 0.
    for k in 480..520 {
        let p = strand[k];
        let g = guide[k];
        let axis_x = 0.02 * (1.0 - k as f32 / 600.0);
        let about_axis = Vec3::new(p.x - axis_x, 0.0, p.z).length();
        assert!(
            (about_axis - r).abs() < 0.25 * r,
            "point {k}: radius {about_axis}"
        );
        // Half a turn out of phase: opposite sides of the axis.
        assert!(p.distance(g) > 1.5 * r, "point {k} lies on the guide");
    }
}

#[test]
fn a_turned_curl_is_the_same_helix_in_another_phase() {
    // Known answer: a strand that is its guide, clumped with a phase of
    // π, stays a helix of the same radius about the same axis, on the
    // opposite side of it from the guide one turn along.
    let r = 0.008;
    let pitch = 0.03;
    let period = ((std::f32::consts::TAU * r).powi(2) + pitch * pitch).sqrt();
    let guide = helix(Vec3::ZERO, r, pitch, 0.0, 6.0, 601);
    let mut strand = guide.clone();
    clump_curl_onto(
        &mut strand,
        &guide,
        0.7,
        period,
        (std::f32::consts::PI, 1.0),
    );
    for k in 150..450 {
        let (p, g) = (strand[k], guide[k]);
        let about_axis = Vec3::new(p.x, 0.0, p.z).length();
        assert!(
            (about_axis - r).abs() < 0.1 * r,
            "point {k}: radius {about_axis}"
        );
        assert!(p.distance(g) > 1.8 * r, "point {k} did not turn");
    }
}

#[test]
fn the_sliding_centreline_is_the_windowed_mean() {
    // Known answer: points on a line at unequal spacing; each point's
    // window mean computed directly.
    let points: Vec<Vec3> = [0.0f32, 0.01, 0.015, 0.03, 0.05, 0.051, 0.07, 0.1]
        .iter()
        .map(|&x| Vec3::new(x, 0.2 * x, 0.0))
        .collect();
    let period = 0.04;
    let arc: Vec<f32> = points.iter().map(|p| p.length()).collect();
    let axis = centreline(&points, period);
    for (i, a) in axis.iter().enumerate() {
        let window: Vec<Vec3> = points
            .iter()
            .zip(&arc)
            .filter(|&(_, &s)| (s - arc[i]).abs() <= 0.5 * period + 1e-6)
            .map(|(p, _)| *p)
            .collect();
        let mean = window.iter().sum::<Vec3>() / window.len() as f32;
        assert!((*a - mean).length() < 1e-6, "point {i}: {a} against {mean}");
    }
}

#[test]
fn clumping_leaves_the_root_and_meets_the_guide_at_the_tip() {
    let strand: Vec<Vec3> = (0..11)
        .map(|i| Vec3::new(0.02, -0.01 * i as f32, 0.0))
        .collect();
    let guide: Vec<Vec3> = (0..21)
        .map(|i| Vec3::new(0.0, -0.005 * i as f32, 0.0))
        .collect();
    let mut clumped = strand.clone();
    clump_onto(&mut clumped, &guide, 1.0);
    assert_eq!(clumped[0], strand[0]);
    assert!(clumped[10].distance(guide[20]) < 1e-6, "{}", clumped[10]);
    // Halfway along, halfway over.
    assert!((clumped[5].x - 0.01).abs() < 1e-6, "{}", clumped[5]);
    // Following a blended shape of two guides, weighted 0.25 / 0.75, from
    // the strand's own root: the tip lands on the blend.
    let a: Vec<Vec3> = (0..10)
        .map(|i| Vec3::new(0.01 * i as f32, 0.0, 0.0))
        .collect();
    let b: Vec<Vec3> = (0..10)
        .map(|i| Vec3::new(0.0, 0.0, 0.01 * i as f32))
        .collect();
    let (sa, sb) = (
        resampled_shape(&a, FOLLOW_POINTS),
        resampled_shape(&b, FOLLOW_POINTS),
    );
    let mut followed = strand.clone();
    let blended = blended_shape(&[(&sa, 0.25), (&sb, 0.75)], strand[0]);
    follow_guides(&mut followed, &blended);
    let tip = strand[0] + Vec3::new(0.0225, 0.0, 0.0675);
    assert!(followed[10].distance(tip) < 1e-6, "{}", followed[10]);
}

#[test]
fn clumping_gathers_a_strand_onto_its_guide_towards_the_tip() {
    let guide: Vec<Vec3> = (0..11)
        .map(|k| Vec3::new(0.0, -0.01 * k as f32, 0.0))
        .collect();
    let mut strand: Vec<Vec3> = guide.iter().map(|p| *p + Vec3::X * 0.02).collect();
    clump_onto(&mut strand, &guide, 0.8);
    // The root stays; the offset shrinks linearly along the length to
    // 1 − 0.8 of itself at the tip.
    assert_eq!(strand[0], Vec3::new(0.02, 0.0, 0.0));
    for (k, p) in strand.iter().enumerate() {
        let want = 0.02 * (1.0 - 0.8 * k as f32 / 10.0);
        assert!((p.x - want).abs() < 1e-6, "point {k}: {p}");
        assert!((p.y + 0.01 * k as f32).abs() < 1e-6, "point {k}: {p}");
    }
}
