//! A sphere collider: an icosphere mesh and its signed distance field.

use std::collections::HashMap;

use glam::DVec3;
use helixhair_physics::collision::SignedDistanceField;

/// The sphere's radius, metres (about a head's).
pub const RADIUS_M: f64 = 0.08;
/// The field's grid spacing, metres.
pub const CELL_M: f64 = 0.004;

/// An icosphere of radius `r`, subdivided `levels` times.
pub fn icosphere(r: f64, levels: usize) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut v: Vec<DVec3> = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| DVec3::new(x, y, z).normalize())
    .collect();
    let mut f: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..levels {
        let mut mid = HashMap::new();
        let mut midpoint = |a: u32, b: u32, v: &mut Vec<DVec3>| {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                v.push(((v[a as usize] + v[b as usize]) / 2.0).normalize());
                (v.len() - 1) as u32
            })
        };
        let mut next = Vec::with_capacity(f.len() * 4);
        for [a, b, c] in f {
            let (ab, bc, ca) = (
                midpoint(a, b, &mut v),
                midpoint(b, c, &mut v),
                midpoint(c, a, &mut v),
            );
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        f = next;
    }
    (v.into_iter().map(|p| p * r).collect(), f)
}

pub fn sphere_field() -> (SignedDistanceField, f64) {
    let (v, f) = icosphere(RADIUS_M, 3);
    // How far the faceted mesh lies inside the sphere: the largest gap at a
    // face centre.
    let sag = f
        .iter()
        .map(|t| {
            RADIUS_M - ((v[t[0] as usize] + v[t[1] as usize] + v[t[2] as usize]) / 3.0).length()
        })
        .fold(0.0, f64::max);
    let field = SignedDistanceField::from_triangles(&v, &f, CELL_M).expect("a valid mesh");
    (field, sag)
}
