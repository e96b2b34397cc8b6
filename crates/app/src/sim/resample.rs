//! Keeps a strand's shape when its element count, layout or length
//! changes.
//!
//! A Super-Helix's state is one strain triple q = (τ, κ₁, κ₂) per element,
//! constant along the element; the shape is the curve those strains
//! integrate to. With a new set of elements, each new element takes the
//! strains (and strain rates) of the old element under its arc-length
//! midpoint. Where new element boundaries fall on old ones (doubling the
//! count, or any count when the strains are uniform) the shape is the same
//! curve exactly; otherwise it is the nearest piecewise-constant curve,
//! off by at most half an old element's worth of bending.

use glam::DVec3;

/// Values per element (`old`, on elements `old_lengths_m` long) carried to
/// elements `new_lengths_m` long: each new element gets the value of the
/// old element under its midpoint.
pub fn resample_per_element(
    old: &[DVec3],
    old_lengths_m: &[f64],
    new_lengths_m: &[f64],
) -> Vec<DVec3> {
    let old_total: f64 = old_lengths_m.iter().sum();
    let new_total: f64 = new_lengths_m.iter().sum();
    // A length change stretches the profile: compare fractions of length.
    let scale = if new_total > 0.0 {
        old_total / new_total
    } else {
        1.0
    };
    resample(old, old_lengths_m, new_lengths_m, scale)
}

/// Values per element carried to a strand cut or grown to new element
/// lengths, by arc length from the root (no stretch): each new element
/// gets the value of the old element under its midpoint, and past the old
/// tip the tip element's value (a grown strand continues its tip's curl).
/// A cut keeps the rest of the strand exactly where its new boundaries
/// fall on old ones.
pub fn resample_by_arc_length(
    old: &[DVec3],
    old_lengths_m: &[f64],
    new_lengths_m: &[f64],
) -> Vec<DVec3> {
    resample(old, old_lengths_m, new_lengths_m, 1.0)
}

/// Each new element's value: the old element's under the new element's
/// midpoint, its arc length times `scale` (the tip's value beyond).
fn resample(old: &[DVec3], old_lengths_m: &[f64], new_lengths_m: &[f64], scale: f64) -> Vec<DVec3> {
    let mut out = Vec::with_capacity(new_lengths_m.len());
    let mut start_m = 0.0;
    for &length_m in new_lengths_m {
        let middle_m = (start_m + 0.5 * length_m) * scale;
        start_m += length_m;
        let mut end_m = 0.0;
        let mut value = old.last().copied().unwrap_or(DVec3::ZERO);
        for (&q, &l) in old.iter().zip(old_lengths_m) {
            end_m += l;
            if middle_m < end_m {
                value = q;
                break;
            }
        }
        out.push(value);
    }
    out
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use helixhair_physics::{
        Method, NaturalShape, RigidMotion, RootPose, Strand, StrandModel, StrandParams,
    };

    use super::*;

    fn strand(params: &StrandParams) -> Strand {
        let model = Arc::new(StrandModel::new(params, 4).unwrap());
        let root = RootPose::from_direction(DVec3::ZERO, DVec3::X, DVec3::Z);
        Strand::new(model, root, Method::Exact)
    }

    fn tip(s: &Strand) -> DVec3 {
        *s.boundary_points_world(&RigidMotion::default())
            .last()
            .unwrap()
    }

    #[test]
    fn doubling_the_elements_keeps_a_bent_shape_exactly() {
        let params = StrandParams {
            elements: 5,
            ..StrandParams::default()
        };
        let mut coarse = strand(&params);
        // A made-up bent state: different strains in every element.
        let q: Vec<DVec3> = (0..5)
            .map(|i| DVec3::new(3.0 * i as f64, 20.0 - 7.0 * i as f64, 4.0))
            .collect();
        coarse.set_state(&q, &[DVec3::ZERO; 5]);
        let fine_params = StrandParams {
            elements: 10,
            ..params.clone()
        };
        let mut fine = strand(&fine_params);
        let q_fine = resample_per_element(
            &q,
            &params.element_lengths(),
            &fine_params.element_lengths(),
        );
        fine.set_state(&q_fine, &[DVec3::ZERO; 10]);
        let (a, b) = (tip(&coarse), tip(&fine));
        assert!((a - b).length() < 1e-12, "{a} vs {b}");
        // The tip is really off the straight line: the test bends the strand.
        assert!((a - DVec3::new(0.2, 0.0, 0.0)).length() > 0.02);
    }

    #[test]
    fn a_uniform_curl_survives_any_count_and_a_graded_layout() {
        let params = StrandParams {
            elements: 7,
            natural_shape: NaturalShape::Helix {
                radius_m: 0.02,
                step_m: 0.05,
            },
            ..StrandParams::default()
        };
        let coarse = strand(&params);
        let fine_params = StrandParams {
            elements: 13,
            layout: helixhair_physics::ElementLayout::Graded {
                tip_to_root_ratio: 3.0,
            },
            ..params.clone()
        };
        let mut fine = strand(&StrandParams {
            natural_shape: NaturalShape::Straight,
            ..fine_params.clone()
        });
        let q = resample_per_element(
            coarse.q(),
            &params.element_lengths(),
            &fine_params.element_lengths(),
        );
        fine.set_state(&q, &[DVec3::ZERO; 13]);
        assert!((tip(&coarse) - tip(&fine)).length() < 1e-12);
    }
}
