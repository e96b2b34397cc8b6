//! Fused multiply-add in every lane width: the batch arithmetic
//! (`batch::lanes`) fuses where the build has FMA and only there.

use helixhair_physics::batch::lanes::{FUSED, LANES, Lanes, Real};

/// Known answer: (1 + 2⁻¹³)(1 − 2⁻¹³) − 1 = −2⁻²⁶ exactly, which a
/// fused multiply-add returns and a separate multiply (rounding the
/// product to 1) and add turn into 0. Every lane and the scalar twins
/// give the fused answer where the build has FMA and 0 where it has
/// not ([`FUSED`]); in f64 the product 1 − 2⁻²⁶ is exact, so both ways
/// give −2⁻²⁶.
#[test]
fn mul_add_is_fused_where_the_build_has_fma() {
    let e = 2f32.powi(-13);
    let fused = -(2f32.powi(-26));
    let unfused = (1.0 + e) * (1.0 - e) - 1.0f32;
    assert_eq!(unfused, 0.0, "the product rounds to 1 when not fused");
    let expected = if FUSED { fused } else { unfused };
    println!("fused: {FUSED}");
    let lanes = Lanes::splat(1.0 + e).mul_add(Lanes::splat(1.0 - e), Lanes::splat(-1.0));
    assert_eq!(lanes.to_array(), [expected; LANES]);
    assert_eq!(Real::mul_add(1.0 + e, 1.0 - e, -1.0f32), expected);
    assert_eq!(
        Real::mul_add(f64::from(1.0 + e), f64::from(1.0 - e), -1.0),
        f64::from(fused)
    );
}
