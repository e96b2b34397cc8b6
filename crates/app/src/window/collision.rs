//! The head collider the app hands to the physics.
//!
//! The physics crate owns collision: a signed distance field built from
//! triangles in head coordinates, moving rigidly with the head trajectory,
//! and a penalty contact in the step's force stage
//! (`helixhair_physics::collision`). The app only turns the renderer's head
//! mesh into plain triangles for it, once, and shares the field between
//! the runs (main and compare) through an `Arc`.

use std::collections::{HashMap, HashSet};
use std::sync::Arc;

use glam::DVec3;
use helixhair_physics::HairSystem;
use helixhair_physics::collision::SignedDistanceField;
use helixhair_render::HeadMesh;

/// Grid spacing of the head's distance field, metres: 4 mm resolves the
/// nose and ears well enough for hair that rests on the skull, and the
/// field of the default head then takes about 1 MB.
pub const HEAD_CELL_M: f64 = 0.004;

/// A collider built from the head mesh, shared by every run.
#[derive(Clone, Debug)]
pub struct HeadCollider {
    field: Arc<SignedDistanceField>,
}

impl HeadCollider {
    /// Builds the collider of `head` (head coordinates, metres).
    pub fn from_head(head: &HeadMesh) -> Result<Self, String> {
        let (positions, triangles) = closed_triangles(head);
        SignedDistanceField::from_triangles(&positions, &triangles, HEAD_CELL_M)
            .map(|field| Self {
                field: Arc::new(field),
            })
            .map_err(|e| format!("head collision is off: {e}"))
    }

    /// The distance field.
    pub fn field(&self) -> &SignedDistanceField {
        &self.field
    }

    /// Makes `system` collide its strands with this collider.
    pub fn attach(&self, system: &mut HairSystem) {
        system.set_collider(Some(self.field.clone()));
    }
}

/// The triangles of the head's part that grows hair (the connected part
/// holding the scalp), with every hole capped. The field's inside is found
/// by a flood fill from the grid's boundary, and the sign near the surface
/// from the nearest triangle: both go wrong where two closed parts
/// intersect (the default head's neck tube runs into the skull) or where a
/// part is open, so the collider takes the skull alone, closed. Hair can
/// therefore pass into the neck.
///
/// A hole is a loop of directed edges whose opposite edge no triangle
/// has; each is closed by a fan of triangles to the loop's centroid,
/// wound like the rest of the mesh.
pub fn closed_triangles(head: &HeadMesh) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut positions: Vec<DVec3> = head.mesh.positions.iter().map(|p| p.as_dvec3()).collect();
    let all: Vec<[u32; 3]> = head
        .mesh
        .indices
        .chunks_exact(3)
        .map(|t| [t[0], t[1], t[2]])
        .collect();
    let mut triangles = scalp_component(&all, &head.scalp_triangles, positions.len());
    let edges: HashSet<(u32, u32)> = triangles
        .iter()
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
        .collect();
    // Boundary edge a → b, keyed by a: the cap uses b → a.
    let mut next: HashMap<u32, u32> = edges
        .iter()
        .filter(|(a, b)| !edges.contains(&(*b, *a)))
        .map(|&(a, b)| (a, b))
        .collect();
    while let Some(&start) = next.keys().next() {
        let mut ring = vec![start];
        let mut at = start;
        while let Some(b) = next.remove(&at) {
            if b == start {
                break;
            }
            ring.push(b);
            at = b;
        }
        if ring.len() < 3 {
            continue;
        }
        let centre = ring.iter().map(|&i| positions[i as usize]).sum::<DVec3>() / ring.len() as f64;
        let c = positions.len() as u32;
        positions.push(centre);
        for k in 0..ring.len() {
            let (a, b) = (ring[k], ring[(k + 1) % ring.len()]);
            triangles.push([b, a, c]);
        }
    }
    (positions, triangles)
}

/// The triangles connected (through shared vertices) to the first scalp
/// triangle; all of them when there is no scalp.
fn scalp_component(triangles: &[[u32; 3]], scalp: &[u32], vertices: usize) -> Vec<[u32; 3]> {
    let Some(&seed) = scalp.first() else {
        return triangles.to_vec();
    };
    // Union-find over vertices.
    let mut parent: Vec<usize> = (0..vertices).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for t in triangles {
        let a = root(&mut parent, t[0] as usize);
        for &v in &t[1..] {
            let b = root(&mut parent, v as usize);
            parent[b] = a;
        }
    }
    let Some(seed_triangle) = triangles.get(seed as usize) else {
        return triangles.to_vec();
    };
    let part = root(&mut parent, seed_triangle[0] as usize);
    triangles
        .iter()
        .filter(|t| root(&mut parent, t[0] as usize) == part)
        .copied()
        .collect()
}

#[cfg(test)]
mod tests {
    use helixhair_render::head_generate::default_head;

    use super::*;

    #[test]
    fn the_default_heads_field_is_negative_inside_and_positive_outside() {
        let collider = HeadCollider::from_head(&default_head()).unwrap();
        let field = collider.field();
        // The skull's centre is inside; the crown is 10 cm above it.
        let (inside, _) = field.sample(DVec3::ZERO).unwrap();
        assert!(inside < -0.01, "{inside}");
        let (above, gradient) = field.sample(DVec3::new(0.0, 0.105, 0.0)).unwrap();
        assert!(above > 0.0 && above < 0.01, "{above}");
        assert!(gradient.y > 0.9, "{gradient}");
    }

    #[test]
    fn capping_closes_every_edge() {
        let (_, triangles) = closed_triangles(&default_head());
        let edges: HashSet<(u32, u32)> = triangles
            .iter()
            .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
            .collect();
        assert!(edges.iter().all(|(a, b)| edges.contains(&(*b, *a))));
    }
}
