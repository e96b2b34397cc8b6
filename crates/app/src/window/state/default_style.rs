//! The style the window opens with when no file is given: curly hair whose
//! guide strands grow from evenly spread points on the default head's
//! scalp.
//!
//! The example styles in `assets/styles/` put their roots on a sphere of
//! radius 10 cm, which the procedural head (narrower at the temples) does
//! not follow; the window's default instead samples the renderer's own
//! scalp ([`poisson_disk_on_scalp`]), so every root sits on the skin and
//! grows along its normal. [`regrow_roots`] regrows any style to a new
//! strand count (the "guide strands" control), each group keeping its
//! share, its placement and its region of the scalp.

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
        // the head clips at 1/60 s (docs/solvers.md, "Stability").
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

/// Regrows the style to `count` grown strands in all, each group keeping
/// its share of them and its layout (issue 32, item 5: regrowing used to
/// deal new roots over the whole scalp to the groups in turn, so a fringe
/// covered the scalp and lost its comb, lift and region):
///
/// - a group placed on the scalp (`scalp`) keeps its comb, lift, region and
///   seed, and its listed roots; its placement's count takes the rest of
///   its share;
/// - a group of listed roots only gets new roots spread evenly over the
///   scalp where its old roots were: each new root goes to the group whose
///   old root is nearest (ties dealt in turn), with that root's direction;
/// - imported strands stay as they are.
pub fn regrow_roots(style: &mut Style, head: &HeadMesh, count: usize) {
    let now: Vec<usize> = style
        .groups
        .iter()
        .map(|g| match (&g.imported, &g.scalp) {
            (Some(_), _) => 0,
            (None, scalp) => g.roots.len() + scalp.as_ref().map_or(0, |p| p.count as usize),
        })
        .collect();
    let shares = proportional_shares(count, &now);
    // Placed groups: the placement's count.
    for (g, share) in style.groups.iter_mut().zip(&shares) {
        if let Some(placement) = &mut g.scalp {
            let listed = g.roots.len();
            placement.count = share.saturating_sub(listed).max(1) as u32;
        }
    }
    // Listed groups: new roots where their old ones were.
    let listed: Vec<usize> = (0..style.groups.len())
        .filter(|&g| style.groups[g].scalp.is_none() && now[g] > 0)
        .collect();
    let wanted: usize = listed.iter().map(|&g| shares[g]).sum();
    if wanted == 0 {
        return;
    }
    let old: Vec<Vec<Root>> = listed
        .iter()
        .map(|&g| std::mem::take(&mut style.groups[g].roots))
        .collect();
    for (turn, candidate) in scalp_roots(head, wanted).into_iter().enumerate() {
        let distance = |roots: &[Root]| {
            roots
                .iter()
                .map(|r| r.position_m.distance(candidate.position_m))
                .fold(f64::INFINITY, f64::min)
        };
        let nearest = old
            .iter()
            .map(|r| distance(r))
            .fold(f64::INFINITY, f64::min);
        let tied: Vec<usize> = (0..old.len())
            .filter(|&k| distance(&old[k]) <= nearest + 1e-9)
            .collect();
        let k = tied[turn % tied.len()];
        let from = old[k]
            .iter()
            .min_by(|a, b| {
                a.position_m
                    .distance(candidate.position_m)
                    .total_cmp(&b.position_m.distance(candidate.position_m))
            })
            .map_or(candidate, |r| Root {
                position_m: candidate.position_m,
                ..*r
            });
        style.groups[listed[k]].roots.push(from);
    }
}

/// Strands the style grows: listed roots, scalp placements and imported
/// guides (what "guide strands" shows).
pub fn grown_count(style: &Style) -> usize {
    style
        .groups
        .iter()
        .map(|g| g.simulated_count() + g.scalp.as_ref().map_or(0, |p| p.count as usize))
        .sum()
}

/// `count` split in proportion to `weights` (largest remainders), every
/// group with a weight getting at least one; zero weights get zero.
fn proportional_shares(count: usize, weights: &[usize]) -> Vec<usize> {
    let total: usize = weights.iter().sum();
    if total == 0 {
        return vec![0; weights.len()];
    }
    let exact: Vec<f64> = weights
        .iter()
        .map(|&w| count as f64 * w as f64 / total as f64)
        .collect();
    let mut shares: Vec<usize> = exact.iter().map(|x| x.floor() as usize).collect();
    let mut order: Vec<usize> = (0..weights.len()).filter(|&i| weights[i] > 0).collect();
    order.sort_by(|&a, &b| (exact[b] - exact[b].floor()).total_cmp(&(exact[a] - exact[a].floor())));
    let left = count.saturating_sub(shares.iter().sum());
    for &i in order.iter().cycle().take(left.min(order.len())) {
        shares[i] += 1;
    }
    for (share, &w) in shares.iter_mut().zip(weights) {
        if w > 0 {
            *share = (*share).max(1);
        }
    }
    shares
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

    #[test]
    fn regrowing_a_groomed_style_keeps_each_groups_placement_and_share() {
        // Issue 32, item 5: `groomed/wavy.ron` (160 + 30 placed strands)
        // regrown to 380 strands lost its comb, lift and region.
        let src = include_str!("../../../../../assets/styles/groomed/wavy.ron");
        let mut style = Style::from_ron(src, std::path::Path::new("wavy.ron")).unwrap();
        let before = style.clone();
        regrow_roots(&mut style, &default_head(), 380);
        let counts: Vec<u32> = style
            .groups
            .iter()
            .map(|g| g.scalp.as_ref().unwrap().count)
            .collect();
        assert_eq!(counts, vec![320, 60]);
        for (after, was) in style.groups.iter().zip(&before.groups) {
            let (a, b) = (after.scalp.as_ref().unwrap(), was.scalp.as_ref().unwrap());
            assert_eq!(
                (a.comb, a.lift_deg, &a.region, a.seed),
                (b.comb, b.lift_deg, &b.region, b.seed)
            );
            assert_eq!(after.roots, was.roots);
        }
    }

    #[test]
    fn regrown_listed_roots_stay_in_their_groups_regions() {
        // Two groups of listed roots, left and right of the midline: each
        // regrown root lies on its group's side.
        let mut style = default_style(40);
        let mut right = style.groups[0].clone();
        right.name = "right".into();
        right.roots.retain(|r| r.position_m.x > 0.0);
        style.groups[0].roots.retain(|r| r.position_m.x <= 0.0);
        style.groups.push(right);
        regrow_roots(&mut style, &default_head(), 200);
        assert_eq!(style.strand_count(), 200);
        let margin = 0.02;
        assert!(
            style.groups[0]
                .roots
                .iter()
                .all(|r| r.position_m.x < margin)
        );
        assert!(
            style.groups[1]
                .roots
                .iter()
                .all(|r| r.position_m.x > -margin)
        );
        assert!(style.groups.iter().all(|g| g.roots.len() > 60));
    }
}
