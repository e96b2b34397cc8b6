//! Whether a point lies inside a closed triangle mesh, by ray parity: the
//! independent check of "hair inside the head" in `export_cli.rs` and
//! `window_sintel.rs` (not the physics' own distance field).

/// How many of `points` lie inside `head`'s mesh ([`inside_mesh`]), and
/// their share of all of them.
pub fn inside_share(points: &[glam::DVec3], head: &helixhair_render::HeadMesh) -> (usize, f64) {
    let (positions, indices) = (&head.mesh.positions, &head.mesh.indices);
    let inside = points
        .iter()
        .filter(|p| inside_mesh(**p, positions, indices))
        .count();
    (inside, inside as f64 / points.len().max(1) as f64)
}

/// Whether `p` lies inside the closed triangle mesh (`positions`,
/// `indices`): a ray from it crosses the surface an odd number of times
/// (Möller–Trumbore; the ray's direction avoids the mesh's axes).
fn inside_mesh(p: glam::DVec3, positions: &[glam::Vec3], indices: &[u32]) -> bool {
    let d = glam::DVec3::new(1.0, 0.2345, 0.1234).normalize();
    let mut crossings = 0;
    for t in indices.chunks_exact(3) {
        let [a, b, c] = [t[0], t[1], t[2]].map(|i| positions[i as usize].as_dvec3());
        let (e1, e2) = (b - a, c - a);
        let h = d.cross(e2);
        let det = e1.dot(h);
        if det.abs() < 1e-14 {
            continue;
        }
        let s = p - a;
        let u = s.dot(h) / det;
        let q = s.cross(e1);
        let v = d.dot(q) / det;
        if (0.0..=1.0).contains(&u) && v >= 0.0 && u + v <= 1.0 && e2.dot(q) / det > 0.0 {
            crossings += 1;
        }
    }
    crossings % 2 == 1
}

/// The head's pose at the last time sample of a `.usda` HelixHair wrote
/// (its `xformOp:transform`, columns of a row-vector matrix): the rotation
/// and translation taking head coordinates to the world's. `None` when the
/// head has no transform (it stood still at rest).
pub fn usda_last_head_pose(text: &str) -> Option<(glam::DMat3, glam::DVec3)> {
    usda_head_poses(text)
        .pop()
        .map(|(_, rotation, offset)| (rotation, offset))
}

/// Every time sample of the head's pose in a `.usda` HelixHair wrote, as
/// (time code, rotation, translation); empty when the head has no
/// transform.
pub fn usda_head_poses(text: &str) -> Vec<(f64, glam::DMat3, glam::DVec3)> {
    let Some(start) = text.find("xformOp:transform.timeSamples = {") else {
        return Vec::new();
    };
    let samples = &text[start..];
    let samples = &samples[..samples.find("\n        }").unwrap_or(samples.len())];
    samples
        .lines()
        .filter_map(|line| {
            let colon = line.find(": (")?;
            let time: f64 = line[..colon].trim().parse().ok()?;
            let numbers: Vec<f64> = line[colon + 2..]
                .split(|c: char| "(), ".contains(c))
                .filter(|s| !s.is_empty())
                .map(str::parse)
                .collect::<Result<_, _>>()
                .ok()?;
            (numbers.len() == 16).then(|| {
                let [x, y, z, t] = [0, 4, 8, 12]
                    .map(|k| glam::DVec3::new(numbers[k], numbers[k + 1], numbers[k + 2]));
                (time, glam::DMat3::from_cols(x, y, z), t)
            })
        })
        .collect()
}
