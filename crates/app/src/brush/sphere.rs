//! The brush's reach: which points it holds and how strongly.
//!
//! A brush is a sphere of radius r. A moving tool (Comb, Grab) uses the
//! sphere where the stroke has brought it; a dab tool (Cut, Curl, Freeze, …)
//! the sphere swept along the whole path, a capsule: a point's distance is
//! then its distance to the path's polyline. Either way a point at distance
//! d has the weight
//!
//! - 1 for d ≤ (1 − f) r, with f the stroke's `falloff`;
//! - 1 − s²(3 − 2s), s = (d − (1 − f) r) / (f r), between there and the rim
//!   (a smoothstep: the weight and its slope are continuous at both ends);
//! - 0 outside the sphere.
//!
//! So `falloff: 0` is a hard brush (full weight inside) and `falloff: 1` a
//! soft one fading from its centre.

use glam::DVec3;

/// A brush's reach: a sphere or a capsule along a path.
#[derive(Clone, Debug, PartialEq)]
pub struct Reach {
    /// The centre (one point) or the path the sphere sweeps.
    pub path: Vec<DVec3>,
    /// The radius, metres.
    pub radius_m: f64,
    /// The faded fraction of the radius, 0 to 1.
    pub falloff: f64,
}

impl Reach {
    /// A sphere at `centre_m`.
    pub fn sphere(centre_m: DVec3, radius_m: f64, falloff: f64) -> Self {
        Self {
            path: vec![centre_m],
            radius_m,
            falloff,
        }
    }

    /// The distance from `point_m` to the sphere's centre or the path.
    pub fn distance_m(&self, point_m: DVec3) -> f64 {
        match self.path.as_slice() {
            [] => f64::INFINITY,
            [centre] => point_m.distance(*centre),
            path => path
                .windows(2)
                .map(|pair| distance_to_segment(point_m, pair[0], pair[1]))
                .fold(f64::INFINITY, f64::min),
        }
    }

    /// The weight of the point `point_m`, 0 to 1 (see the module docs).
    pub fn weight(&self, point_m: DVec3) -> f64 {
        weight_at(self.distance_m(point_m) / self.radius_m, self.falloff)
    }
}

/// The weight at `d` radii from the centre for a brush fading over
/// `falloff` of its radius.
pub fn weight_at(d: f64, falloff: f64) -> f64 {
    let inner = 1.0 - falloff;
    if d.is_nan() || d >= 1.0 {
        0.0
    } else if d <= inner {
        1.0
    } else {
        let s = (d - inner) / falloff;
        1.0 - s * s * (3.0 - 2.0 * s)
    }
}

/// The distance from `p` to the segment from `a` to `b`.
pub fn distance_to_segment(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    p.distance(closest_on_segment(p, a, b))
}

/// The point of the segment from `a` to `b` nearest to `p`.
pub fn closest_on_segment(p: DVec3, a: DVec3, b: DVec3) -> DVec3 {
    let ab = b - a;
    let length2 = ab.length_squared();
    if length2 <= 0.0 {
        return a;
    }
    a + ab * ((p - a).dot(ab) / length2).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_hard_brush_is_one_inside_and_zero_outside() {
        let reach = Reach::sphere(DVec3::ZERO, 0.1, 0.0);
        assert_eq!(reach.weight(DVec3::new(0.0999, 0.0, 0.0)), 1.0);
        assert_eq!(reach.weight(DVec3::new(0.1, 0.0, 0.0)), 0.0);
    }

    #[test]
    fn a_soft_brush_fades_smoothly_to_its_rim() {
        // Smoothstep: 1 at the centre, 1/2 half way, 0 at the rim.
        assert_eq!(weight_at(0.0, 1.0), 1.0);
        assert!((weight_at(0.5, 1.0) - 0.5).abs() < 1e-15);
        assert!(weight_at(0.999_999, 1.0) < 1e-10);
        // Half faded: full weight to half the radius.
        assert_eq!(weight_at(0.5, 0.5), 1.0);
        assert!((weight_at(0.75, 0.5) - 0.5).abs() < 1e-15);
    }

    #[test]
    fn a_swept_brush_measures_to_the_path() {
        let reach = Reach {
            path: vec![DVec3::ZERO, DVec3::new(1.0, 0.0, 0.0)],
            radius_m: 0.1,
            falloff: 0.0,
        };
        assert!((reach.distance_m(DVec3::new(0.5, 0.05, 0.0)) - 0.05).abs() < 1e-15);
        assert!((reach.distance_m(DVec3::new(1.3, 0.0, 0.0)) - 0.3).abs() < 1e-15);
        assert_eq!(reach.weight(DVec3::new(0.5, 0.05, 0.0)), 1.0);
    }
}
