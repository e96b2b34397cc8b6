//! A coil grown along its growth direction: the root frame that turns a
//! helix's axis along it ([`coil_along`]), and the first element that
//! bends the hair from the follicle's direction into the helix
//! ([`CoilLeadIn`]).
//!
//! # Why
//!
//! A helix whose axis follows the growth direction ([`coil_along`]) leaves
//! the root along its own tangent, which makes the pitch angle α with the
//! axis: 76° for the groomed coily example's 5 mm coil of 8 mm per turn.
//! Its first loop then starts along the scalp, a few millimetres above it
//! at most, and the coil, soft as a spring of hair is (the first turn of a
//! 25 cm coily strand gives about 1 cm under the weight beyond it), folds
//! that loop onto the scalp and into the contact's skin, where exported
//! points fall inside the head mesh (issue 32, item 3). Real coily hair
//! leaves the follicle along its growth direction and curls after; curl
//! modifiers of grooming tools ramp the curl in from the root for the same
//! reason.
//!
//! # How
//!
//! The strand's first element becomes a plain bend, with no twist, of
//! constant curvature α / ℓ₀ (ℓ₀ the element's length) about the material
//! axis b = (a × e₀)/|a × e₀|, a the helix's axis in the material frame
//! (its Darboux vector, signed by the twist). Inside an element the frame
//! turns about its Darboux vector, fixed in the material frame, so over the
//! element it turns by α about b, which takes a onto the tangent e₀. The
//! root frame is the helix's start frame (from [`coil_along`]) turned back
//! by α about b: its tangent is then the helix's axis, which is the growth
//! direction. The helix that follows is the one `coil_along` lays out,
//! moved by the bend's chord (about 0.77 ℓ₀ for the coily example, up off
//! the scalp first). Every strand of a group shares the bend (it is fixed
//! in the material frame), so the group's natural shape carries it as its
//! first element's strains.

use glam::{DMat3, DVec3};
use helixhair_physics::natural_shape::NaturalShape;

use crate::style::StrandGroup;
use crate::style::groom::CurlAxis;

/// The bend that leads a group's strands from their roots into their coils.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CoilLeadIn {
    /// The first element's natural strains (τ, κ₁, κ₂), m⁻¹: a bend.
    pub strains_per_m: DVec3,
    /// The helix's natural strains, m⁻¹, in every later element.
    pub helix_strains_per_m: DVec3,
    /// The material rotation from the helix's start frame back to the
    /// root's: the root frame is the start frame times this.
    root_from_helix_start: DMat3,
}

impl CoilLeadIn {
    /// The lead-in of a group grown with [`CurlAxis::Growth`] from its scalp
    /// placement alone (no listed roots, which keep their shape), whose
    /// natural shape is one helix (the same strains in every element, with
    /// twist and curvature); `None` for any other group.
    pub fn for_group(group: &StrandGroup) -> Option<Self> {
        let placement = group.scalp.as_ref()?;
        if placement.curl_axis != CurlAxis::Growth || !group.roots.is_empty() {
            return None;
        }
        let params = &group.params;
        let strains = params.natural_shape.strains(params.elements);
        let helix = *strains.first()?;
        if params.elements < 2 || strains.iter().any(|k| *k != helix) {
            return None;
        }
        Self::new(helix, params.length_m / params.elements as f64)
    }

    /// The lead-in into a helix of strains `helix` (τ, κ₁, κ₂), m⁻¹, over
    /// a first element `element_length_m` long; `None` without twist or
    /// curvature (no axis to lead into).
    pub fn new(helix: DVec3, element_length_m: f64) -> Option<Self> {
        let k = helix.length();
        if helix.x == 0.0 || helix.y.hypot(helix.z) == 0.0 || !k.is_finite() {
            return None;
        }
        let axis = helix * (helix.x.signum() / k);
        let bend_axis = axis.cross(DVec3::X).try_normalize()?;
        let pitch_angle_rad = axis.x.clamp(-1.0, 1.0).acos();
        Some(Self {
            strains_per_m: bend_axis * (pitch_angle_rad / element_length_m),
            helix_strains_per_m: helix,
            root_from_helix_start: DMat3::from_axis_angle(bend_axis, -pitch_angle_rad),
        })
    }

    /// The natural shape of a strand of `elements` elements: the bend, then
    /// the helix.
    pub fn natural_shape(&self, elements: usize) -> NaturalShape {
        let mut list = vec![self.helix_strains_per_m.to_array(); elements];
        if let Some(first) = list.first_mut() {
            *first = self.strains_per_m.to_array();
        }
        NaturalShape::PerElement(list)
    }

    /// The root's tangent and frame reference (n₁) for a strand growing
    /// along `growth` from a scalp of outward normal `normal`; `None` where
    /// [`coil_along`] has no frame.
    pub fn root_frame(&self, growth: DVec3, normal: DVec3) -> Option<(DVec3, DVec3)> {
        let (tangent, n1) = coil_along(growth, normal, self.helix_strains_per_m)?;
        let helix_start = DMat3::from_cols(tangent, n1, tangent.cross(n1));
        let root = helix_start * self.root_from_helix_start;
        Some((root.x_axis, root.y_axis))
    }
}

/// The root tangent and frame reference (n₁) that make a helix of strains
/// `strains` = (τ, κ₁, κ₂) advance along `growth`, its axis on the side of
/// the root away from a scalp of outward normal `normal`; `None` for a
/// strand without twist or without curvature, whose axis is not a
/// direction of growth.
///
/// Inside an element the frame turns about the Darboux vector k, fixed in
/// the material frame, so the centreline advances along k signed by the
/// twist, at the pitch angle α to the tangent (cos α = |τ|/|k|). The
/// tangent is tilted from `growth` by α sideways (along the scalp, so it
/// never points into it), to whichever side puts the centre of curvature,
/// R₀ (k × e₀), away from the scalp; the rotation taking the material
/// frame's (e₀, k⊥) to the world's (tangent, growth⊥) then gives n₁. The
/// coil's loops then lie at or above the root's tangent plane.
pub fn coil_along(growth: DVec3, normal: DVec3, strains: DVec3) -> Option<(DVec3, DVec3)> {
    let k = strains.length();
    let curvature = strains.y.hypot(strains.z);
    if strains.x == 0.0 || curvature == 0.0 || !k.is_finite() {
        return None;
    }
    let axis = strains * (strains.x.signum() / k);
    let (cos_a, sin_a) = (axis.x, curvature / k);
    let up = (normal - normal.dot(growth) * growth)
        .try_normalize()
        .unwrap_or_else(|| growth.any_orthonormal_vector());
    let side = growth.cross(up);
    // The material frame's basis (e₀, axis⊥, e₀ × axis⊥), taken to the
    // world's (tangent, growth⊥, tangent × growth⊥).
    let axis_across = (axis - cos_a * DVec3::X) / sin_a;
    let third = DVec3::X.cross(axis_across);
    [side, -side].into_iter().find_map(|side| {
        let tangent = cos_a * growth + sin_a * side;
        let growth_across = (growth - cos_a * tangent) / sin_a;
        let world_third = tangent.cross(growth_across);
        let to_world = |m: DVec3| {
            m.x * tangent + m.dot(axis_across) * growth_across + m.dot(third) * world_third
        };
        (to_world(strains.cross(DVec3::X)).dot(up) >= 0.0).then(|| (tangent, to_world(DVec3::Y)))
    })
}
