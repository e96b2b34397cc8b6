//! A style on a head: roots grown from scalp placements.
//!
//! A group's `scalp` placement becomes roots spread evenly (Poisson disk)
//! over its part of the scalp, each with a frame from the scalp: it grows
//! at `lift_deg` from the surface, leaning along the comb direction
//! projected onto the scalp, with the inward surface normal as its
//! reference: a curl starts in the plane of the normal and the growth
//! direction, bending towards the scalp, so hair hugs the head instead of
//! springing off it (with the outward normal, wavy and curly grooms stood
//! up from the crown). The
//! simulation then sees plain roots ([`Groom::grown`]); what is drawn from
//! the simulated guides is [`crate::hair::drawn`]'s business.

use glam::{DVec3, Vec3};
use helixhair_physics::collision::{CollisionError, SignedDistanceField};
use helixhair_render::HeadMesh;
use helixhair_render::head_shell::HeadShell;
use helixhair_render::scalp_sampling::{SurfaceSample, poisson_disk_on_scalp};

use crate::style::groom::{CurlAxis, ScalpPlacement};
use crate::style::{Root, StrandGroup, Style};

use super::coil::{CoilLeadIn, coil_along};

/// Grid spacing of the head's collision field, metres: 4 mm resolves a
/// head's curvature (radii of several centimetres) and keeps the grid of
/// a bust with shoulders near half a million points.
pub const COLLIDER_CELL_M: f64 = 0.004;

/// A style grown on a head: what the simulation and the drawing share.
#[derive(Clone, Debug)]
pub struct Groom {
    /// The style as written (its groups' `scalp` and `render` sections).
    pub style: Style,
    /// The style the simulation runs: every group's roots listed (its own,
    /// then those of its scalp placement), no scalp placement left.
    pub grown: Style,
    /// The head.
    pub head: HeadMesh,
    /// The head's shell, which keeps drawn hair out of it.
    pub shell: HeadShell,
}

impl Groom {
    /// Grows `style` on `head`.
    pub fn new(style: Style, head: HeadMesh) -> Self {
        Self {
            grown: grow_scalp_roots(&style, &head),
            shell: HeadShell::new(&head.mesh),
            style,
            head,
        }
    }

    /// The head as a collider for the physics ([`head_collider`]).
    pub fn collider(&self) -> Result<SignedDistanceField, CollisionError> {
        head_collider(&self.head)
    }

    /// Each group as written, with the same group grown (its roots all
    /// listed).
    pub fn groups(&self) -> impl Iterator<Item = (&StrandGroup, &StrandGroup)> {
        self.style.groups.iter().zip(&self.grown.groups)
    }
}

/// `head` as a collider for the physics (the groomed render and the
/// window share it): a signed distance field of the connected part of its
/// mesh that carries the scalp, with [`COLLIDER_CELL_M`] spacing, so
/// simulated hair rests on the head instead of falling through it. The
/// default head is one closed surface with its neck and shoulders, so all
/// of it collides. Other parts of an OBJ (a separate body, a floor) are
/// left out: the field's grid spans what collides, and a floor or a whole
/// figure would spread a 4 mm grid past its size limit. The part may be
/// open (a bust cut below the chest, holes for eyes and mouth): the field
/// takes its inside from the winding number. A head with no scalp faces
/// collides as a whole.
pub fn head_collider(head: &HeadMesh) -> Result<SignedDistanceField, CollisionError> {
    let mesh = &head.mesh;
    let positions: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
    let part = mesh_parts(head);
    let scalp_parts: Vec<usize> = head
        .scalp_triangles
        .iter()
        .map(|&t| part[t as usize])
        .collect();
    let triangles: Vec<[u32; 3]> = mesh
        .indices
        .chunks_exact(3)
        .enumerate()
        // A head without a scalp group collides as a whole.
        .filter(|(t, _)| scalp_parts.is_empty() || scalp_parts.contains(&part[*t]))
        .map(|(_, c)| [c[0], c[1], c[2]])
        .collect();
    SignedDistanceField::from_triangles(&positions, &triangles, COLLIDER_CELL_M)
}

/// Whether any group places roots on the scalp (and so needs a head).
pub fn needs_head(style: &Style) -> bool {
    style.groups.iter().any(|g| g.scalp.is_some())
}

/// The growth direction at a root with surface normal `normal`: `lift_deg`
/// up from the surface, towards `comb` projected onto the surface.
pub fn combed_direction(normal: DVec3, comb: DVec3, lift_deg: f64) -> DVec3 {
    let along = comb - normal * comb.dot(normal);
    let along = along
        .try_normalize()
        .unwrap_or_else(|| normal.any_orthonormal_vector());
    let lift = lift_deg.to_radians();
    along * lift.cos() + normal * lift.sin()
}

/// The connected part each triangle of `head` belongs to (triangles that
/// share a vertex position, to a micrometre, are connected: an OBJ's groups
/// repeat the vertices on their borders).
fn mesh_parts(head: &HeadMesh) -> Vec<usize> {
    let mesh = &head.mesh;
    let mut welded = std::collections::HashMap::new();
    let vertex_key: Vec<usize> = mesh
        .positions
        .iter()
        .map(|p| {
            let key = (*p * 1e6).round().as_ivec3().to_array();
            let next = welded.len();
            *welded.entry(key).or_insert(next)
        })
        .collect();
    // Union-find over welded vertices.
    let mut parent: Vec<usize> = (0..welded.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for t in mesh.indices.chunks_exact(3) {
        let a = root(&mut parent, vertex_key[t[0] as usize]);
        for &k in &t[1..] {
            let b = root(&mut parent, vertex_key[k as usize]);
            parent[b] = a;
        }
    }
    mesh.indices
        .chunks_exact(3)
        .map(|t| root(&mut parent, vertex_key[t[0] as usize]))
        .collect()
}

/// `head` with its scalp cut down to `placement`'s region (all of it
/// without one).
pub fn placement_scalp(placement: &ScalpPlacement, head: &HeadMesh) -> HeadMesh {
    let Some(region) = &placement.region else {
        return head.clone();
    };
    let mut cut = head.clone();
    cut.scalp_triangles.retain(|&t| {
        let centre = head.mesh.triangle(t as usize).iter().sum::<Vec3>() / 3.0;
        region.contains(centre.as_dvec3())
    });
    cut
}

/// The root `placement` grows at `sample` of the scalp, for hair whose
/// natural strains at the root are `root_strains` (τ, κ₁, κ₂), m⁻¹: combed
/// at its lift with the inward normal as frame reference
/// ([`CurlAxis::Hug`]), or turned so that its helix advances along that
/// direction ([`CurlAxis::Growth`], [`coil_along`]), after the group's
/// `lead_in` where it has one (its root then points along the growth).
pub fn scalp_root(
    sample: &SurfaceSample,
    placement: &ScalpPlacement,
    root_strains: DVec3,
    lead_in: Option<&CoilLeadIn>,
) -> Root {
    let normal = sample.normal.as_dvec3();
    let growth = combed_direction(normal, placement.comb, placement.lift_deg);
    let hug = (growth, -normal);
    let (direction, reference) = match (placement.curl_axis, lead_in) {
        (CurlAxis::Hug, _) => hug,
        (CurlAxis::Growth, Some(lead_in)) => lead_in.root_frame(growth, normal).unwrap_or(hug),
        (CurlAxis::Growth, None) => coil_along(growth, normal, root_strains).unwrap_or(hug),
    };
    Root {
        position_m: sample.position_m.as_dvec3(),
        direction,
        reference,
    }
}

/// The natural strains at the root of `group`'s strands (the first
/// element's), m⁻¹.
pub fn root_strains(group: &StrandGroup) -> DVec3 {
    let params = &group.params;
    params
        .natural_shape
        .strains(params.elements)
        .first()
        .copied()
        .unwrap_or(DVec3::ZERO)
}

/// The roots `placement` puts on `head`'s scalp, for hair whose natural
/// strains at the root are `root_strains`.
pub fn scalp_roots(
    placement: &ScalpPlacement,
    head: &HeadMesh,
    root_strains: DVec3,
    lead_in: Option<&CoilLeadIn>,
) -> Vec<Root> {
    poisson_disk_on_scalp(
        &placement_scalp(placement, head),
        placement.count as usize,
        placement.seed,
    )
    .iter()
    .map(|s| scalp_root(s, placement, root_strains, lead_in))
    .collect()
}

/// `style` with every group's scalp placement turned into roots (after the
/// group's listed roots, the placement itself removed). A coil grown along
/// its growth direction gets its lead-in as its first element's natural
/// strains ([`CoilLeadIn`]). Groups without placement are unchanged.
pub fn grow_scalp_roots(style: &Style, head: &HeadMesh) -> Style {
    let mut grown = style.clone();
    for group in &mut grown.groups {
        let lead_in = CoilLeadIn::for_group(group);
        if let Some(placement) = group.scalp.take() {
            let strains = root_strains(group);
            if let Some(lead_in) = &lead_in {
                group.params.natural_shape = lead_in.natural_shape(group.params.elements);
            }
            let roots = scalp_roots(&placement, head, strains, lead_in.as_ref());
            group.roots.extend(roots);
        }
    }
    grown
}
