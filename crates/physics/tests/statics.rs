//! Rest states against known answers (docs/physics.md section 7): the heavy
//! elastica table, the small-deflection law of element-averaged curvature,
//! and Dense and Block-diagonal agreeing at rest.

use crate::common;

use common::*;
use glam::{DMat3, DVec3};
use helixhair_physics::Method;

/// Table values are quoted to 5 decimals; Richardson extrapolation from
/// N = 20 and 40 removes the O(1/N²) discretisation error, leaving O(1/N⁴).
const ELASTICA_EXTRAPOLATED_TOL: f64 = 2e-5;
/// Without extrapolation the N = 40 rest state is within ~1/(3N²)·(value).
const ELASTICA_N40_TOL: f64 = 1.5e-3;
/// Settled when strain rates fall below this, m⁻¹/s.
const REST_RATE: f64 = 1e-10;
/// h for settling: Block-diagonal settles for h ≤ 0.01 s on all four rows
/// (at h = 0.02 s it keeps thrashing at α = 100, N = 40; docs/solvers.md).
const SETTLE_H: f64 = 0.01;

/// (α, y_tip/L, (L − x_tip)/L, tip angle) from docs/physics.md section 7.
const HEAVY_ELASTICA: [(f64, f64, f64, f64); 4] = [
    (1.0, 0.12347, 0.00875, 0.16512),
    (5.0, 0.49591, 0.15334, 0.69700),
    (20.0, 0.82988, 0.55477, 1.33950),
    (100.0, 0.93752, 0.84078, 1.56411),
];

fn rest_measures(alpha: f64, n: usize, method: Method) -> [f64; 3] {
    let (p, g) = elastica(alpha, n);
    let mut s = strand(&p, method);
    settle(
        &mut s,
        &at_rest(DMat3::IDENTITY),
        g,
        SETTLE_H,
        REST_RATE,
        20_000,
    );
    let (y, x, a) = tip_measures(&s);
    [y, x, a]
}

#[test]
fn heavy_elastica_rest_states_match_the_table_for_both_solvers() {
    for method in [Method::Dense, Method::BlockDiagonal] {
        for (alpha, y, x, angle) in HEAVY_ELASTICA {
            let coarse = rest_measures(alpha, 20, method);
            let fine = rest_measures(alpha, 40, method);
            for (i, want) in [y, x, angle].into_iter().enumerate() {
                let extrapolated = fine[i] + (fine[i] - coarse[i]) / 3.0;
                assert!(
                    (extrapolated - want).abs() < ELASTICA_EXTRAPOLATED_TOL,
                    "{method:?} α = {alpha}, measure {i}: extrapolated {extrapolated} vs {want}"
                );
                assert!(
                    (fine[i] - want).abs() < ELASTICA_N40_TOL,
                    "{method:?} α = {alpha}: N=40 {}",
                    fine[i]
                );
            }
        }
    }
}

/// The linear law holds to O(α²) relative; at α = 1e-3 that is ~1e-8.
const SMALL_DEFLECTION_TOL: f64 = 1e-7;

#[test]
fn small_deflection_follows_the_element_averaged_curvature_law() {
    // δ_N/δ = 1 − 1/(3N²) with δ = ρS g L⁴/(8EI): 0.98667 at N = 5,
    // 0.99667 at N = 10.
    let alpha = 1e-3;
    for n in [1usize, 2, 5, 10] {
        let (p, g) = elastica(alpha, n);
        let mut s = strand(&p, Method::Dense);
        settle(
            &mut s,
            &at_rest(DMat3::IDENTITY),
            g,
            SETTLE_H,
            1e-14,
            20_000,
        );
        let (y, _, _) = tip_measures(&s);
        let ratio = y / (alpha / 8.0);
        let law = 1.0 - 1.0 / (3.0 * (n * n) as f64);
        assert!(
            (ratio - law).abs() < SMALL_DEFLECTION_TOL,
            "N = {n}: {ratio} vs {law}"
        );
    }
}

/// Two solvers at rest differ only by how closely each has settled.
const SAME_REST_TOL: f64 = 1e-8;

#[test]
fn dense_and_block_diagonal_reach_the_same_rest_state() {
    // A curly strand on an oblique root under gravity: the mass matrix
    // drops out at rest, so every method must find the same equilibrium.
    let (p, root) = curl_on_oblique_root();
    let gravity = DVec3::new(0.0, -9.81, 0.0);
    let rest: Vec<Vec<DVec3>> = [Method::Dense, Method::BlockDiagonal]
        .into_iter()
        .map(|method| {
            let mut s = strand(&p, method);
            settle(&mut s, &root, gravity, SETTLE_H, REST_RATE, 50_000);
            s.q().to_vec()
        })
        .collect();
    let scale = rest[0]
        .iter()
        .map(|q| q.abs().max_element())
        .fold(0.0, f64::max);
    for other in &rest[1..] {
        let diff = max_diff(&rest[0], other);
        assert!(
            diff < SAME_REST_TOL * scale,
            "rest states differ by {diff} (scale {scale})"
        );
    }
    // And the curl sagged: gravity moved the state off its natural shape.
    let natural = p.natural_shape.strains(12);
    assert!(max_diff(&rest[0], &natural) > 1e-3 * scale);
}
