//! Whether a point lies inside a closed triangle mesh, by ray parity: the
//! independent check of "hair inside the head" in `export_cli.rs` and
//! `window_sintel.rs` (not the physics' own distance field).

/// Whether `p` lies inside the closed triangle mesh (`positions`,
/// `indices`): a ray from it crosses the surface an odd number of times
/// (Möller–Trumbore; the ray's direction avoids the mesh's axes).
pub fn inside_mesh(p: glam::DVec3, positions: &[glam::Vec3], indices: &[u32]) -> bool {
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
