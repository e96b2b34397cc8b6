//! Tests of the default head: its shape, scalp, hairline and closed
//! surface.

use super::*;

/// Vertices of the head (crown pole and rings), before the neck's.
const HEAD_VERTICES: usize = 1 + (SCALP_RINGS + FACE_RINGS) * HEAD_SEGMENTS;

#[test]
fn the_scalp_is_the_top_and_back_of_the_head() {
    let head = default_head();
    let scalp = head.scalp_triangles.len();
    let total = head.mesh.triangle_count();
    assert!(scalp > total / 6 && scalp < total / 2, "{scalp} of {total}");
    // Scalp area of a real adult head is about 0.06 m²; a stylised one
    // should be the same order.
    let area = head.scalp_area_m2();
    assert!((0.02..0.09).contains(&area), "{area} m²");
    for &t in &head.scalp_triangles {
        let centre = head.mesh.triangle(t as usize).iter().sum::<Vec3>() / 3.0;
        assert!(centre.y > 0.0 || centre.z < 0.0, "{centre}");
    }
}

#[test]
fn normals_point_outwards_and_the_face_looks_along_plus_z() {
    let head = default_head();
    for (p, n) in head.mesh.positions[..HEAD_VERTICES]
        .iter()
        .zip(&head.mesh.normals)
    {
        // Outward except in the deep folds (ears, nose sides).
        assert!(n.dot(*p) > -0.5 * p.length(), "{p} {n}");
    }
    let (lo, hi) = head.mesh.bounds_m();
    assert!(hi.z > 0.1 && lo.z > -0.11, "nose in front: {lo} {hi}");
    assert!((hi.y - 0.1).abs() < 0.01, "crown at 10 cm: {hi}");
}

/// Each undirected edge of `head` with the triangles using it, as
/// (edge, uses in one direction, uses in the other).
fn edge_uses(head: &HeadMesh) -> std::collections::HashMap<(u32, u32), (u32, u32)> {
    let mut uses = std::collections::HashMap::new();
    for t in head.mesh.indices.chunks_exact(3) {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            let entry = uses.entry((a.min(b), a.max(b))).or_insert((0, 0));
            if a < b {
                entry.0 += 1;
            } else {
                entry.1 += 1;
            }
        }
    }
    uses
}

/// The neck was a separate tube whose top ring lay on the head's
/// curved surface (a crack under the jaw where chords and ring
/// parted, a rim at the nape) and whose bottom was a flat cap. Now
/// every edge is shared by exactly two triangles, once in each
/// direction: one closed, consistently oriented surface.
#[test]
fn head_neck_and_shoulders_are_one_watertight_surface() {
    let head = default_head();
    let uses = edge_uses(&head);
    let open: Vec<_> = uses.iter().filter(|(_, u)| **u != (1, 1)).collect();
    assert!(
        open.is_empty(),
        "{} edges not shared by two triangles: {:?}",
        open.len(),
        &open[..open.len().min(5)]
    );
    // Euler characteristic of a sphere: V − E + F = 2.
    let (v, e, f) = (
        head.mesh.positions.len(),
        uses.len(),
        head.mesh.triangle_count(),
    );
    assert_eq!(v as i64 - e as i64 + f as i64, 2);
    // It reaches down to the shoulders.
    let (lo, hi) = head.mesh.bounds_m();
    assert!(lo.y < -0.25 && hi.x > 0.14, "{lo} {hi}");
    // No sliver or fold: every triangle has area.
    for t in 0..head.mesh.triangle_count() {
        let [a, b, c] = head.mesh.triangle(t);
        assert!(
            (b - a).cross(c - a).length() > 1e-9,
            "triangle {t} is degenerate"
        );
    }
}

/// The scalp was the grid cells above the hairline, so its edge went in
/// stair steps along the cells. Now its edge is one ring of vertices on
/// the hairline, turning by a few degrees from edge to edge.
#[test]
fn the_hairline_is_a_smooth_ring_on_the_hairline_curve() {
    let head = default_head();
    let scalp: std::collections::HashSet<u32> = head.scalp_triangles.iter().copied().collect();
    let mut scalp_uses = std::collections::HashMap::<(u32, u32), u32>::new();
    for &t in &scalp {
        let c = &head.mesh.indices[3 * t as usize..3 * t as usize + 3];
        for (a, b) in [(c[0], c[1]), (c[1], c[2]), (c[2], c[0])] {
            *scalp_uses.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    let edge: Vec<(u32, u32)> = scalp_uses
        .into_iter()
        .filter(|(_, n)| *n == 1)
        .map(|(e, _)| e)
        .collect();
    assert_eq!(edge.len(), HEAD_SEGMENTS, "one ring of edges");
    // Walk the ring: every vertex has two edge neighbours.
    let mut next = std::collections::HashMap::<u32, Vec<u32>>::new();
    for &(a, b) in &edge {
        next.entry(a).or_default().push(b);
        next.entry(b).or_default().push(a);
    }
    assert!(next.values().all(|n| n.len() == 2));
    let hairline: Vec<Vec3> = (0..3600)
        .map(|k| {
            let phi = TAU * k as f32 / 3600.0;
            let theta = hairline_theta(phi);
            let d = direction(theta, phi);
            assert!(
                on_scalp(direction(theta - 1e-3, phi)) && !on_scalp(direction(theta + 1e-3, phi))
            );
            head_point_m(d)
        })
        .collect();
    let start = edge[0].0;
    let (mut before, mut at) = (start, next[&start][0]);
    let mut max_turn_deg = 0.0f32;
    for _ in 0..HEAD_SEGMENTS {
        let p = head.mesh.positions[at as usize];
        // On the hairline: the head's point in a direction where the
        // scalp test flips (within 0.5 mm, a tenth of an edge).
        let off_m = hairline
            .iter()
            .map(|q| q.distance(p))
            .fold(f32::MAX, f32::min);
        assert!(off_m < 5e-4, "{p} is {off_m} m off the hairline");
        let after = *next[&at].iter().find(|&&n| n != before).expect("ring");
        let (u, w) = (
            p - head.mesh.positions[before as usize],
            head.mesh.positions[after as usize] - p,
        );
        let turn_deg = u.angle_between(w).to_degrees();
        assert!(turn_deg < 30.0, "the hairline turns by {turn_deg}° at {p}");
        max_turn_deg = max_turn_deg.max(turn_deg);
        (before, at) = (at, after);
    }
    assert_eq!(at, next[&start][0], "the ring closes");
    // A stair step turns by 90°; 64 edges round a smooth curve turn by
    // about 6° each, more where the hairline bends at the temples.
    assert!(
        max_turn_deg < 30.0,
        "the hairline turns by {max_turn_deg}° at a vertex"
    );
}
