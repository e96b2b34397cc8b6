//! What the `volume` study measures on a head of hair, from the strands'
//! element boundary points: how far the hair stands off the scalp, how much
//! space it fills, and how many pairs of segments of different strands
//! pass closer than a given distance.
//!
//! All three take the points in head coordinates (the study converts), so
//! a turned head gives the same figures as a still one.

use std::collections::{HashMap, HashSet};

use glam::DVec3;

/// Pieces each element chord is cut into for [`occupied_volume_m3`], so
/// that a chord longer than a cell marks every cell it crosses.
const CHORD_PIECES: usize = 8;

/// Mean distance (metres) of every non-root point of `strands` from the
/// nearest root: the scalp is where the roots grow, and hair that sags
/// onto it comes closer to some root.
pub fn mean_scalp_distance_m(strands: &[Vec<DVec3>]) -> f64 {
    let roots: Vec<DVec3> = strands.iter().filter_map(|s| s.first().copied()).collect();
    let nearest = NearestPoint::new(&roots, 0.03);
    let (mut sum, mut count) = (0.0, 0usize);
    for s in strands {
        for p in s.iter().skip(1) {
            sum += nearest.distance_m(*p);
            count += 1;
        }
    }
    if count == 0 { 0.0 } else { sum / count as f64 }
}

/// Volume (m³) of the cubic cells of `cell_m` (a lattice fixed in head
/// coordinates) that some hair passes through.
pub fn occupied_volume_m3(strands: &[Vec<DVec3>], cell_m: f64) -> f64 {
    let mut cells = HashSet::new();
    for s in strands {
        for pair in s.windows(2) {
            for k in 0..=CHORD_PIECES {
                let p = pair[0].lerp(pair[1], k as f64 / CHORD_PIECES as f64);
                cells.insert(cell_of(p, cell_m));
            }
        }
    }
    cells.len() as f64 * cell_m.powi(3)
}

/// Number of pairs of element chords of different strands whose closest
/// points are less than each of `distances_m` apart (one count per
/// distance, in one pass). Chords are hashed by midpoint on cells at least
/// as large as the longest chord plus the largest distance, so only the 27
/// cells around a chord can hold a partner: O(n) for hair of bounded
/// density.
pub fn close_pairs<const K: usize>(strands: &[Vec<DVec3>], distances_m: [f64; K]) -> [usize; K] {
    let chords: Vec<(usize, DVec3, DVec3)> = strands
        .iter()
        .enumerate()
        .flat_map(|(i, s)| s.windows(2).map(move |w| (i, w[0], w[1])))
        .collect();
    let longest = chords
        .iter()
        .map(|(_, a, b)| a.distance(*b))
        .fold(0.0, f64::max);
    let reach = distances_m.iter().copied().fold(0.0, f64::max);
    let cell_m = (longest + reach).max(1e-6);
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    for (k, (_, a, b)) in chords.iter().enumerate() {
        grid.entry(cell_of(0.5 * (*a + *b), cell_m))
            .or_default()
            .push(k);
    }
    let mut counts = [0; K];
    for (k, (strand, a, b)) in chords.iter().enumerate() {
        let c = cell_of(0.5 * (*a + *b), cell_m);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let Some(others) = grid.get(&[c[0] + dx, c[1] + dy, c[2] + dz]) else {
                        continue;
                    };
                    for &j in others {
                        let (other, p, q) = chords[j];
                        // Each pair once, and never two chords of one strand.
                        if j <= k || other == *strand {
                            continue;
                        }
                        let d = segment_distance_m(*a, *b, p, q);
                        for (count, limit) in counts.iter_mut().zip(distances_m) {
                            if d < limit {
                                *count += 1;
                            }
                        }
                    }
                }
            }
        }
    }
    counts
}

/// Distance between segments [a, b] and [c, d] (Ericson, "Real-Time
/// Collision Detection", 5.1.9: closest points of two segments).
pub fn segment_distance_m(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    let (d1, d2, r) = (b - a, d - c, a - c);
    let (aa, ee, f) = (d1.length_squared(), d2.length_squared(), d2.dot(r));
    let tiny = 1e-30;
    let (s, t) = if aa <= tiny && ee <= tiny {
        (0.0, 0.0)
    } else if aa <= tiny {
        (0.0, (f / ee).clamp(0.0, 1.0))
    } else {
        let cc = d1.dot(r);
        if ee <= tiny {
            ((-cc / aa).clamp(0.0, 1.0), 0.0)
        } else {
            let bb = d1.dot(d2);
            let denom = aa * ee - bb * bb;
            let mut s = if denom > tiny {
                ((bb * f - cc * ee) / denom).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let mut t = (bb * s + f) / ee;
            if t < 0.0 {
                t = 0.0;
                s = (-cc / aa).clamp(0.0, 1.0);
            } else if t > 1.0 {
                t = 1.0;
                s = ((bb - cc) / aa).clamp(0.0, 1.0);
            }
            (s, t)
        }
    };
    (a + d1 * s).distance(c + d2 * t)
}

fn cell_of(p: DVec3, cell_m: f64) -> [i64; 3] {
    (p / cell_m).floor().as_i64vec3().to_array()
}

/// Nearest of a fixed set of points, by a hash grid searched in growing
/// shells of cells.
struct NearestPoint<'a> {
    points: &'a [DVec3],
    cell_m: f64,
    grid: HashMap<[i64; 3], Vec<usize>>,
}

impl<'a> NearestPoint<'a> {
    fn new(points: &'a [DVec3], cell_m: f64) -> Self {
        let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
        for (i, p) in points.iter().enumerate() {
            grid.entry(cell_of(*p, cell_m)).or_default().push(i);
        }
        Self {
            points,
            cell_m,
            grid,
        }
    }

    /// Distance from `p` to the nearest point (infinite without points).
    fn distance_m(&self, p: DVec3) -> f64 {
        let c = cell_of(p, self.cell_m);
        let mut best = f64::INFINITY;
        // Shell r holds every point within r cells; once the best found is
        // within r cells, no farther shell can beat it.
        for r in 0i64..64 {
            for dx in -r..=r {
                for dy in -r..=r {
                    for dz in -r..=r {
                        if dx.abs().max(dy.abs()).max(dz.abs()) != r {
                            continue;
                        }
                        if let Some(list) = self.grid.get(&[c[0] + dx, c[1] + dy, c[2] + dz]) {
                            for &i in list {
                                best = best.min(self.points[i].distance(p));
                            }
                        }
                    }
                }
            }
            if best <= r as f64 * self.cell_m {
                break;
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segment_distance_known_cases() {
        let d = segment_distance_m(
            DVec3::ZERO,
            DVec3::X,
            DVec3::new(0.5, 1.0, -1.0),
            DVec3::new(0.5, 1.0, 1.0),
        );
        assert!((d - 1.0).abs() < 1e-12);
        let d = segment_distance_m(
            DVec3::ZERO,
            DVec3::X,
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(3.0, 0.0, 0.0),
        );
        assert!((d - 1.0).abs() < 1e-12);
    }

    #[test]
    fn crossing_strands_count_once_and_a_strand_never_with_itself() {
        let a = vec![
            DVec3::new(-1.0, 0.0, 0.0),
            DVec3::ZERO,
            DVec3::new(1.0, 0.0, 0.0),
        ];
        let b = vec![DVec3::new(0.5, -1.0, 1e-4), DVec3::new(0.5, 1.0, 1e-4)];
        assert_eq!(close_pairs(&[a.clone(), b], [2e-4, 5e-5]), [1, 0]);
        assert_eq!(close_pairs(&[a], [1.0]), [0]);
    }

    #[test]
    fn scalp_distance_and_occupied_volume_of_a_straight_strand() {
        let s = vec![
            DVec3::ZERO,
            DVec3::new(0.1, 0.0, 0.0),
            DVec3::new(0.19, 0.0, 0.0),
        ];
        assert!((mean_scalp_distance_m(std::slice::from_ref(&s)) - 0.145).abs() < 1e-12);
        // 0 to 0.19 m along x at y = z = 0 crosses cells 0 to 9 of 2 cm.
        let v = occupied_volume_m3(&[s], 0.02);
        assert!((v - 10.0 * 8e-6).abs() < 1e-12, "{v}");
    }
}
