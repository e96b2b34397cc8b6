//! The strand's geometry against closed forms: the helix's series and
//! their derivatives, its Jacobians' time rates, Gauss-Legendre
//! quadrature, second-order jets, and the frames of a whole strand.

mod helix {
    use glam::{DMat3, DVec3};
    use helixhair_physics::geometry::helix::{
        HelixCoefficients, centreline_and_jacobian, rotation,
    };

    /// Agreement of the series and closed forms where both are accurate.
    const COEFFICIENT_TOL: f64 = 1e-13;

    fn closed(y: f64) -> [f64; 3] {
        let x = y.sqrt();
        [x.sin() / x, (1.0 - x.cos()) / y, (x - x.sin()) / (x * y)]
    }

    #[test]
    fn series_match_closed_forms_and_derivatives() {
        for &y in &[0.5, 1.0, 2.0, 3.9, 4.1, 9.0, 30.0] {
            let co = HelixCoefficients::at(y);
            let exact = closed(y);
            let got = [co.a, co.b, co.c];
            for i in 0..3 {
                assert!(
                    (got[i][0] - exact[i]).abs() < COEFFICIENT_TOL,
                    "y={y} i={i}"
                );
                // Derivatives against central differences of the closed form.
                let e = 1e-4;
                let d1 = (closed(y + e)[i] - closed(y - e)[i]) / (2.0 * e);
                let d2 = (closed(y + e)[i] - 2.0 * exact[i] + closed(y - e)[i]) / (e * e);
                assert!(
                    (got[i][1] - d1).abs() < 1e-9,
                    "y={y} i={i}: {} vs {d1}",
                    got[i][1]
                );
                assert!(
                    (got[i][2] - d2).abs() < 1e-5,
                    "y={y} i={i}: {} vs {d2}",
                    got[i][2]
                );
            }
        }
    }

    #[test]
    fn straight_element_has_no_nan_and_no_jump() {
        let (h0, j0) = centreline_and_jacobian(0.1, DVec3::ZERO);
        let (h1, j1) = centreline_and_jacobian(0.1, DVec3::new(1e-9, -1e-9, 1e-9));
        assert!(h0.is_finite() && j0.is_finite());
        assert!((h0 - DVec3::new(0.1, 0.0, 0.0)).length() < 1e-15);
        assert!((h1 - h0).length() < 1e-10 && (j1 - j0).abs_diff_eq(DMat3::ZERO, 1e-12));
        assert!(rotation(DVec3::ZERO).abs_diff_eq(DMat3::IDENTITY, 0.0));
    }
}

mod helix_rates {
    use glam::DVec3;
    use helixhair_physics::geometry::helix::{
        HelixCoefficients, centreline_jacobian_with, left_jacobian_with,
    };
    use helixhair_physics::geometry::helix_rates::{centreline_jacobian_rate, left_jacobian_rate};

    /// Central differences in time of the Jacobians along a straight-line
    /// motion φ(t) = φ + tφ̇ must match the closed-form rates, on both sides
    /// of the series/closed-form switch (y = 4) and at a straight element.
    #[test]
    fn rates_match_time_differences() {
        let rate = DVec3::new(0.7, -1.3, 0.4);
        for phi in [
            DVec3::ZERO,
            DVec3::new(0.3, -0.2, 0.5),
            DVec3::new(1.2, 0.9, -0.8),
            DVec3::new(2.5, -1.5, 2.0),
        ] {
            let sigma = 0.02;
            let at = |t: f64| {
                let p = phi + rate * t;
                let co = HelixCoefficients::at(p.length_squared());
                (
                    centreline_jacobian_with(sigma, p, &co),
                    left_jacobian_with(p, &co),
                )
            };
            let e = 1e-5;
            let (hp, lp) = at(e);
            let (hm, lm) = at(-e);
            let co = HelixCoefficients::at(phi.length_squared());
            let h_rate = centreline_jacobian_rate(sigma, phi, rate, &co);
            let l_rate = left_jacobian_rate(phi, rate, &co);
            let h_fd = (hp - hm) * (0.5 / e);
            let l_fd = (lp - lm) * (0.5 / e);
            assert!(
                h_rate.abs_diff_eq(h_fd, 1e-9 * sigma * sigma),
                "phi {phi}: {h_rate} vs {h_fd}"
            );
            assert!(
                l_rate.abs_diff_eq(l_fd, 1e-9),
                "phi {phi}: {l_rate} vs {l_fd}"
            );
        }
    }
}

mod quadrature {
    use helixhair_physics::geometry::quadrature::Quadrature;

    /// Tolerance of a quadrature against a closed-form integral.
    const QUADRATURE_TOL: f64 = 1e-14;

    #[test]
    fn integrates_polynomials_of_degree_2n_minus_1_exactly() {
        for n in 1..=8 {
            let q = Quadrature::gauss_legendre(n);
            assert!((q.weights.iter().sum::<f64>() - 1.0).abs() < QUADRATURE_TOL);
            for degree in 0..(2 * n) {
                let integral: f64 = q
                    .nodes
                    .iter()
                    .zip(&q.weights)
                    .map(|(x, w)| w * x.powi(degree as i32))
                    .sum();
                let exact = 1.0 / (degree as f64 + 1.0);
                assert!(
                    (integral - exact).abs() < QUADRATURE_TOL,
                    "n = {n}, degree {degree}: {integral} vs {exact}"
                );
            }
            assert!(q.nodes.windows(2).all(|w| w[0] < w[1]));
        }
    }
}

mod jet {
    use helixhair_physics::geometry::jet::Jet;

    #[test]
    fn product_rule_matches_a_known_polynomial() {
        // x(t) = t², y(t) = t³ at t = 2: (xy)(t) = t⁵ → 32, 80, 160.
        let t = 2.0;
        let x = Jet::new(t * t, 2.0 * t, 2.0);
        let y = Jet::new(t * t * t, 3.0 * t * t, 6.0 * t);
        let p = x * y;
        assert_eq!((p.v, p.d, p.dd), (32.0, 80.0, 160.0));
    }

    #[test]
    fn chain_rule_matches_sin_of_square() {
        // sin(t²) at t = 0.7.
        let t: f64 = 0.7;
        let u = Jet::new(t * t, 2.0 * t, 2.0);
        let s = u.chain([u.v.sin(), u.v.cos(), -u.v.sin()]);
        let exact_d = 2.0 * t * (t * t).cos();
        let exact_dd = 2.0 * (t * t).cos() - 4.0 * t * t * (t * t).sin();
        assert!((s.d - exact_d).abs() < 1e-15);
        assert!((s.dd - exact_dd).abs() < 1e-15);
    }
}

mod shape {
    use glam::{DMat3, DVec3};
    use helixhair_physics::geometry::shape::frames_and_points;
    use helixhair_physics::motion::RigidMotion;
    use helixhair_physics::step::reconstruct::{Kinematics, reconstruct};
    use helixhair_physics::{NaturalShape, StrandModel, StrandParams};

    #[test]
    fn equals_the_full_reconstruction() {
        let params = StrandParams {
            elements: 9,
            natural_shape: NaturalShape::Helix {
                radius_m: 0.01,
                step_m: 0.03,
            },
            ..StrandParams::default()
        };
        let model = StrandModel::new(&params, 3).expect("valid");
        let q: Vec<DVec3> = (0..9)
            .map(|i| model.natural[i] + DVec3::new(0.3 * i as f64, -2.0, 1.5))
            .collect();
        let v = vec![DVec3::new(0.1, 0.2, -0.3); 9];
        let root = RigidMotion::at_rest(
            DVec3::new(0.01, 0.1, 0.0),
            DMat3::from_rotation_y(0.7) * DMat3::from_rotation_x(-0.2),
        );
        let mut kin = Kinematics::default();
        reconstruct(&model, &q, &v, &root, &mut kin);
        let (frames, points) = frames_and_points(&model, &q, &root);
        assert_eq!(frames.len(), kin.frames.len());
        for (a, b) in frames.iter().zip(&kin.frames) {
            assert!((*a - *b).abs().to_cols_array().iter().all(|&e| e < 1e-13));
        }
        for (a, b) in points.iter().zip(&kin.points_m) {
            assert!(a.distance(*b) < 1e-14, "{a} vs {b}");
        }
    }
}
