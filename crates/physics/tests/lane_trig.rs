//! The batch lanes' sin and cos (`Real::sin_cos` on `Lanes`, used by the
//! helix coefficients' closed forms) against f64's, rounded to f32: each
//! result must be the f32 nearest the true value or its neighbour (at most
//! one ulp), across the range a coil reaches and well beyond, and must
//! keep the standard library's answers for non-finite input.

use helixhair_physics::batch::lanes::{LANES, Lanes, Real};

/// Ulps between two f32 of the same sign (or both tiny).
fn ulps(a: f32, b: f32) -> u32 {
    if a == b {
        return 0;
    }
    let key = |x: f32| {
        let bits = x.to_bits() as i64;
        if bits < 0x8000_0000 {
            bits
        } else {
            0x8000_0000 - bits
        }
    };
    (key(a) - key(b)).unsigned_abs() as u32
}

#[test]
fn lane_sin_and_cos_are_within_one_f32_ulp_of_the_true_values() {
    let mut worst = 0;
    let mut checked = 0;
    // x from 2 (below the closed form's start, x = 4) to 1,000 rad, and a sweep
    // of small and negative values, 8 at a time.
    let xs: Vec<f32> = (0..200_000)
        .map(|i| 2.0 + i as f32 * 0.005)
        .chain((0..20_000).map(|i| -50.0 + i as f32 * 0.005))
        .collect();
    for chunk in xs.chunks_exact(LANES) {
        let x = Lanes::from_fn(|i| chunk[i]);
        let (sin, cos) = x.sin_cos();
        for (i, &xi) in chunk.iter().enumerate() {
            let (s, c) = f64::from(xi).sin_cos();
            worst = worst
                .max(ulps(sin.lane(i), s as f32))
                .max(ulps(cos.lane(i), c as f32));
            checked += 2;
        }
    }
    println!("{checked} values, worst {worst} ulp from f64 rounded to f32");
    assert!(worst <= 1, "worst {worst} ulps");
}

#[test]
fn lane_sin_and_cos_of_non_finite_values_are_nan() {
    let x = Lanes::from_fn(|i| [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, 0.0][i % 4]);
    let (sin, cos) = x.sin_cos();
    for i in 0..LANES {
        let finite = i % 4 == 3;
        assert_eq!(sin.lane(i).is_nan(), !finite, "lane {i}");
        assert_eq!(cos.lane(i).is_nan(), !finite, "lane {i}");
    }
    assert_eq!((sin.lane(3), cos.lane(3)), (0.0, 1.0));
}
