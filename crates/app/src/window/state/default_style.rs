//! The style the window opens with when no file is given: curly hair whose
//! guide strands grow from evenly spread points on the default head's
//! scalp.
//!
//! The example styles in `assets/styles/` put their roots on a sphere of
//! radius 10 cm, which the procedural head (narrower at the temples) does
//! not follow; the window's default instead samples the renderer's own
//! scalp ([`poisson_disk_on_scalp`]), so every root sits on the skin and
//! grows along its normal. [`regrow_roots`] does the same for any style
//! (the "guide strands" control), spreading the new roots over the groups.

use glam::DVec3;
use helixhair_physics::SimSettings;
use helixhair_physics::engine::EngineKind;
use helixhair_render::HeadMesh;
use helixhair_render::head_generate::default_head;
use helixhair_render::scalp_sampling::poisson_disk_on_scalp;

use crate::style::{Root, STYLE_VERSION, StrandGroup, Style};

use super::presets::built_in_presets;

/// Guide strands of the default style.
pub const DEFAULT_GUIDES: usize = 64;

/// Seed of the root sampling: the same roots on every start.
const ROOT_SEED: u64 = 7;

/// `count` roots evenly spread on `head`'s scalp, in head coordinates,
/// growing out of the skin and swept back: the direction is the part of
/// "backwards" (−z, or down where the scalp faces backwards) along the
/// skin, tilted a third of the way towards the normal, so hair clears the
/// face as a combed-back style does.
pub fn scalp_roots(head: &HeadMesh, count: usize) -> Vec<Root> {
    poisson_disk_on_scalp(head, count, ROOT_SEED)
        .into_iter()
        .map(|s| {
            let normal = s.normal.as_dvec3().normalize_or(DVec3::Y);
            let position = s.position_m.as_dvec3();
            let direction = swept_back(normal);
            Root {
                reference: outward_side(position, normal, direction),
                ..Root::new(position, direction)
            }
        })
        .collect()
}

/// The reference that sets a root's material frame: along the skin,
/// across the growth direction, away from the head's midline. A helix of
/// radius R and rise c per radian winds about the axis c n₀ + R n₁, so the
/// curls then flow back and out to the sides instead of over the face
/// (with the default reference, towards the face, they fall forward).
fn outward_side(position: DVec3, normal: DVec3, direction: DVec3) -> DVec3 {
    let side = normal.cross(direction).normalize_or(DVec3::X);
    if side.x * position.x < 0.0 {
        -side
    } else {
        side
    }
}

/// The growth direction of a root with skin normal `normal` (unit).
fn swept_back(normal: DVec3) -> DVec3 {
    let along_skin = |v: DVec3| v - v.dot(normal) * normal;
    let mut tangent = along_skin(DVec3::NEG_Z);
    if tangent.length() < 0.3 {
        // Skin facing the front goes up over the head, facing back, down.
        tangent = along_skin(DVec3::new(0.0, normal.z.signum(), 0.0));
    }
    (tangent.normalize_or(normal) + 0.5 * normal).normalize()
}

/// The default style with `guides` guide strands on the default head.
pub fn default_style(guides: usize) -> Style {
    let curly = built_in_presets()
        .into_iter()
        .find(|p| p.name == "curly")
        .map(|p| p.params)
        .unwrap_or_default();
    Style {
        version: STYLE_VERSION,
        name: "default".into(),
        // One substep: the velocity-implicit step takes these curls through
        // the head clips at 1/60 s (docs/RESULTS.md, section 9).
        sim: SimSettings::default(),
        engine: EngineKind::Reference,
        accuracy_target: None,
        groups: vec![StrandGroup {
            name: "all".into(),
            params: curly,
            roots: scalp_roots(&default_head(), guides.max(1)),
            scalp: None,
            render: None,
            imported: None,
            edits: Vec::new(),
        }],
    }
}

/// Replaces the roots of every group by `count` roots on `head`'s scalp,
/// dealt out to the groups in turn (each keeps at least one).
pub fn regrow_roots(style: &mut Style, head: &HeadMesh, count: usize) {
    let groups = style.groups.len().max(1);
    let roots = scalp_roots(head, count.max(groups));
    for g in &mut style.groups {
        g.roots.clear();
        g.scalp = None;
    }
    for (i, root) in roots.into_iter().enumerate() {
        if let Some(g) = style.groups.get_mut(i % groups) {
            g.roots.push(root);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_roots_sit_on_the_scalp_and_grow_outwards() {
        let style = default_style(40);
        assert!(style.validate().is_ok());
        let roots = &style.groups[0].roots;
        assert_eq!(roots.len(), 40);
        for r in roots {
            // On the scalp: above the ears, or down to the nape behind.
            assert!(r.position_m.y > -0.05, "{r:?}");
            assert!(r.position_m.y > 0.0 || r.position_m.z < 0.0, "{r:?}");
        }
    }

    #[test]
    fn roots_grow_out_of_the_skin_and_backwards() {
        for normal in [
            DVec3::Y,
            DVec3::Z,
            DVec3::NEG_Z,
            DVec3::X,
            DVec3::new(0.0, 0.5, 0.8).normalize(),
        ] {
            let d = swept_back(normal);
            assert!((d.length() - 1.0).abs() < 1e-12);
            // Out of the skin at 1 / √(1 + 0.5⁻²)… i.e. cos θ = 0.5/√1.25.
            assert!(
                (d.dot(normal) - 0.5 / 1.25f64.sqrt()).abs() < 1e-9,
                "{normal} {d}"
            );
            // Along the skin, never towards the face.
            let along = d - d.dot(normal) * normal;
            assert!(along.length() > 0.5 && along.z <= 1e-12, "{normal} {d}");
        }
        assert!(swept_back(DVec3::NEG_Z).y < 0.0);
    }

    #[test]
    fn regrowing_deals_roots_to_every_group() {
        let mut style = default_style(10);
        let mut second = style.groups[0].clone();
        second.name = "second".into();
        style.groups.push(second);
        regrow_roots(&mut style, &default_head(), 31);
        assert_eq!(style.groups[0].roots.len(), 16);
        assert_eq!(style.groups[1].roots.len(), 15);
        assert_eq!(style.strand_count(), 31);
    }
}
