//! Gauss–Legendre quadrature on an element.
//!
//! Mass and force integrals along an element are smooth (sines and cosines
//! of σ|k|), so a few Gauss points per element integrate them to round-off
//! for the curvatures hair has. Nodes are computed once per point count by
//! Newton's method on the Legendre polynomial.

/// Nodes in [0, 1] and weights summing to 1 of an n-point Gauss rule.
#[derive(Clone, Debug, PartialEq)]
pub struct Quadrature {
    /// Node positions as fractions of the element length, increasing.
    pub nodes: Vec<f64>,
    /// Weights as fractions of the element length; they sum to 1.
    pub weights: Vec<f64>,
}

impl Quadrature {
    /// The n-point Gauss–Legendre rule mapped to [0, 1], exact for
    /// polynomials of degree 2n − 1.
    pub fn gauss_legendre(n: usize) -> Self {
        assert!(n >= 1, "a quadrature needs at least one point");
        let mut nodes = vec![0.0; n];
        let mut weights = vec![0.0; n];
        for i in 0..n {
            // Chebyshev guess for the i-th largest root, then Newton on P_n.
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            for _ in 0..100 {
                let (p, dp) = legendre(n, x);
                let dx = p / dp;
                x -= dx;
                if dx.abs() < 1e-16 {
                    break;
                }
            }
            let (_, dp) = legendre(n, x);
            // Map [-1, 1] to [0, 1]; x decreases with i, so nodes increase.
            nodes[i] = 0.5 * (1.0 - x);
            weights[i] = 1.0 / ((1.0 - x * x) * dp * dp);
        }
        Self { nodes, weights }
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the rule has no points (never, for a constructed rule).
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }
}

/// P_n(x) and P_n'(x) by the three-term recurrence.
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    if n == 0 {
        return (1.0, 0.0);
    }
    for k in 2..=n {
        let k = k as f64;
        let p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
    }
    let dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
    (p1, dp)
}
