//! The Pareto front of (cost, error) points: the settings no other setting
//! beats on both cost and error. A user wanting a given error should pick
//! from the front; everything off it pays more for the same accuracy.

/// Relative improvement in error a dearer point needs to join the front:
/// solvers that give the same answer (Exact and Dense) differ by round-off.
pub const SAME_ERROR_REL: f64 = 1e-6;

/// Indices of the points on the front, cheapest first. A point is on the
/// front when every cheaper point (or equally cheap one listed before it)
/// has a larger error, by more than [`SAME_ERROR_REL`]. Non-finite errors
/// are never on the front.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len())
        .filter(|&i| points[i].0.is_finite() && points[i].1.is_finite())
        .collect();
    order.sort_by(|&a, &b| {
        points[a]
            .0
            .total_cmp(&points[b].0)
            .then(points[a].1.total_cmp(&points[b].1))
    });
    let mut front = Vec::new();
    let mut best = f64::INFINITY;
    for i in order {
        if points[i].1 < best * (1.0 - SAME_ERROR_REL) {
            best = points[i].1;
            front.push(i);
        }
    }
    front
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dominated_and_non_finite_points_are_left_off() {
        let points = [
            (1.0, 0.5),           // cheapest: on the front
            (2.0, 0.6),           // dearer and worse: dominated
            (3.0, 0.1),           // dearer but better: on the front
            (0.5, f64::INFINITY), // blew up
            (3.0, 0.2),           // same cost, worse: dominated
            (4.0, 0.1),           // dearer, no better: dominated
            (5.0, 0.1 - 1e-12),   // better by round-off only: dominated
        ];
        assert_eq!(pareto_front(&points), vec![0, 2]);
    }
}
