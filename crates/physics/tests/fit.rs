//! Fitting polylines with Super-Helices and the sag-free rest shape,
//! against known answers (docs/import.md): curves sampled from a chain of
//! helices by the physics' own reconstruction are fitted back to their
//! strains and element count; the equilibrium of a heavy straight strand,
//! computed by the dynamics, imported sag-free gives straight natural
//! strains and stays put; Greenhill's self-weight column decides which
//! upright strands the stability check flags; heavy strands of known
//! natural shape, imported with the elements their sag asks for, relax
//! to that shape without gravity; the sag rotation of a strand held out
//! is α/6; the fit's short series agree with the step's.

use crate::common;

use std::sync::Arc;

use common::*;
use glam::{DMat3, DVec3};
use helixhair_physics::fit::coefficients::FitCoefficients;
use helixhair_physics::fit::resolution::{
    NATURAL_SHAPE_ERROR_CONSTANT, elements_for_sag, sag_load_per_m3, sag_rotation,
};
use helixhair_physics::fit::stiffen::{max_stiffness_scale, stiffened_params};
use helixhair_physics::fit::{
    FitError, FitOptions, SagFreeInputs, SagFreeStatus, StiffenOptions, UniformHelixChain,
    fit_polyline, fit_with_elements, sag_free, sag_free_stiffened,
};
use helixhair_physics::geometry::helix::HelixCoefficients;
use helixhair_physics::{
    Method, NaturalShape, RigidMotion, RootPose, Strand, StrandModel, StrandParams,
};

/// The bar for strains recovered from an exact Super-Helix curve.
const STRAIN_RECOVERY_TOL: f64 = 1e-6;
/// A tolerance no chain with fewer elements than the truth can meet, while
/// the true N fits to round-off (~1e-15 of the length).
const EXACT_FIT_TOL: f64 = 1e-9;

/// The polyline the physics draws for strains `q`: the root, then per
/// element its 4 Gauss samples and its end point (world coordinates).
fn sampled_polyline(model: &StrandModel, q: &[DVec3], root: &RigidMotion) -> Vec<DVec3> {
    let kin = kinematics(model, q, &vec![DVec3::ZERO; q.len()], root);
    let points = model.quadrature.len();
    let mut out = vec![root.position_m + kin.points_m[0]];
    for e in 0..model.elements() {
        for s in &kin.samples[e * points..(e + 1) * points] {
            out.push(root.position_m + s.position_m);
        }
        out.push(root.position_m + kin.points_m[e + 1]);
    }
    out
}

fn relative_strain_error(got: &[DVec3], want: &[DVec3]) -> f64 {
    let scale = want
        .iter()
        .map(|k| k.abs().max_element())
        .fold(0.0, f64::max);
    max_diff(got, want) / scale
}

#[test]
fn a_sampled_super_helix_is_fitted_back_to_its_strains_and_element_count() {
    let mut rng = Rng::new(11);
    for (case, n) in [2usize, 3, 5, 8].into_iter().enumerate() {
        let p = params(0.15 + 0.05 * case as f64, n);
        let model = model(&p, 4);
        let q = random_strains(&mut rng, n, 40.0);
        let direction = rng.vec3(1.0).normalize();
        let reference = rng.vec3(1.0);
        let pose = RootPose::from_direction(rng.vec3(0.1), direction, reference);
        let root = RigidMotion::at_rest(pose.position_m, pose.head_from_root);
        let polyline = sampled_polyline(&model, &q, &root);
        let options = FitOptions {
            tolerance_over_length: EXACT_FIT_TOL,
            max_elements: 20,
            ..FitOptions::default()
        };
        let fit = fit_polyline(&polyline, reference, &options).expect("a clean polyline");
        assert_eq!(fit.chain.elements(), n, "case {case}: wrong N");
        assert!(
            fit.within_tolerance,
            "case {case}: {}",
            fit.error_over_length
        );
        let err = relative_strain_error(&fit.chain.strains_per_m, &q);
        assert!(
            err < STRAIN_RECOVERY_TOL,
            "case {case} (N = {n}): strains off by {err}"
        );
        let length = fit.chain.length_m();
        assert!(
            (length - p.length_m).abs() < STRAIN_RECOVERY_TOL * p.length_m,
            "case {case}: length {length} vs {}",
            p.length_m
        );
        assert!(
            fit.chain
                .root_frame
                .abs_diff_eq(pose.head_from_root, STRAIN_RECOVERY_TOL),
            "case {case}: root frame"
        );
        assert!((fit.root_m - pose.position_m).length() < 1e-15);
    }
}

#[test]
fn the_default_tolerance_picks_fewer_elements_within_half_a_percent() {
    // A gentle arc sampled finely: one element reproduces a circular arc
    // exactly, so the default tolerance must stop at N = 1.
    let radius = 0.1;
    let arc: Vec<DVec3> = (0..=30)
        .map(|i| {
            let t = i as f64 / 30.0 * 1.5;
            DVec3::new(radius * t.sin(), radius * (1.0 - t.cos()), 0.0)
        })
        .collect();
    let fit = fit_polyline(&arc, DVec3::Z, &FitOptions::default()).expect("clean");
    assert_eq!(fit.chain.elements(), 1);
    assert!(
        fit.error_over_length <= 0.1 * 0.005,
        "{}",
        fit.error_over_length
    );
    // Refined to convergence, the fit finds the arc itself (the polyline's
    // chords are shorter than the arc).
    let exact = FitOptions {
        tolerance_over_length: EXACT_FIT_TOL,
        max_elements: 20,
        ..FitOptions::default()
    };
    let fit = fit_polyline(&arc, DVec3::Z, &exact).expect("clean");
    assert_eq!(fit.chain.elements(), 1);
    assert!(
        fit.error_over_length < EXACT_FIT_TOL,
        "{}",
        fit.error_over_length
    );
    assert!((fit.chain.length_m() - radius * 1.5).abs() < 1e-9);
    let kappa = fit.chain.strains_per_m[0];
    assert!((kappa.length() - 1.0 / radius).abs() < 1e-6, "{kappa}");
}

#[test]
fn degenerate_polylines_are_refused_with_a_reason() {
    let o = FitOptions::default();
    assert_eq!(
        fit_polyline(&[DVec3::ZERO], DVec3::Y, &o),
        Err(FitError::TooFewPoints(1))
    );
    let nan = [DVec3::ZERO, DVec3::new(f64::NAN, 0.0, 0.0)];
    assert_eq!(
        fit_polyline(&nan, DVec3::Y, &o),
        Err(FitError::NotFinite(1))
    );
    let repeated = [DVec3::ZERO, DVec3::X, DVec3::X];
    assert_eq!(
        fit_polyline(&repeated, DVec3::Y, &o),
        Err(FitError::RepeatedPoint(1))
    );
}

/// Strains recovered from a settled strand, relative: the fit's accuracy.
const EQUILIBRIUM_FIT_TOL: f64 = 1e-6;
/// Natural strains of the sag-free import, relative to the shape's strains:
/// the fit's accuracy plus how far the settled state is from exact rest.
const SAG_FREE_STRAIGHT_TOL: f64 = 1e-5;
/// Largest movement of any boundary point over 10 s from the imported
/// shape, metres (1 µm: the settled state's own residual motion).
const STAYS_PUT_M: f64 = 1e-6;

#[test]
fn a_heavy_straight_strand_at_equilibrium_imports_straight_and_stays_put() {
    // α = ρS g L³/EI = 20: the tip hangs 0.83 L below the root.
    let (p, g) = elastica(20.0, 10);
    let mut s = strand(&p, Method::Dense);
    let root = at_rest(DMat3::IDENTITY);
    settle(&mut s, &root, g, 0.01, 1e-10, 20_000);
    let settled = s.q().to_vec();
    let model = s.model().clone();
    let polyline = sampled_polyline(&model, &settled, &root);

    let options = FitOptions {
        tolerance_over_length: EXACT_FIT_TOL,
        max_elements: 20,
        ..FitOptions::default()
    };
    let fit = fit_polyline(&polyline, DVec3::Y, &options).expect("clean");
    assert_eq!(fit.chain.elements(), 10);
    let err = relative_strain_error(&fit.chain.strains_per_m, &settled);
    assert!(err < EQUILIBRIUM_FIT_TOL, "fit off by {err}");

    let fitted_root = RigidMotion::at_rest(fit.root_m, fit.chain.root_frame);
    let inputs = SagFreeInputs {
        root: &fitted_root,
        gravity_m_per_s2: g,
        support: None,
    };
    let rest = sag_free(&model, &fit.chain.strains_per_m, &inputs);
    assert_eq!(rest.status, SagFreeStatus::Held);
    let scale = settled
        .iter()
        .map(|k| k.abs().max_element())
        .fold(0.0, f64::max);
    let bent = rest
        .natural_per_m
        .iter()
        .map(|k| k.abs().max_element())
        .fold(0.0, f64::max);
    assert!(
        bent < SAG_FREE_STRAIGHT_TOL * scale,
        "natural strains {bent} vs shape {scale}"
    );

    // Simulate the import: natural shape q⁰, starting at the fitted shape.
    let drift = drift_over(
        &p,
        &rest.natural_per_m,
        &fit.chain.strains_per_m,
        &fitted_root,
        g,
    );
    assert!(drift < STAYS_PUT_M, "sag-free strand moved {drift} m");
    // Without sag-free the fitted shape is the rest shape and it sags again.
    let sagged = drift_over(
        &p,
        &fit.chain.strains_per_m,
        &fit.chain.strains_per_m,
        &fitted_root,
        g,
    );
    assert!(sagged > 0.01, "the control should sag, moved {sagged} m");
}

/// Largest boundary-point movement over 10 s at 60 Hz of a strand with
/// natural strains `natural`, started at rest in shape `start`.
fn drift_over(
    p: &StrandParams,
    natural: &[DVec3],
    start: &[DVec3],
    root: &RigidMotion,
    g: DVec3,
) -> f64 {
    let mut p = p.clone();
    p.natural_shape = NaturalShape::PerElement(natural.iter().map(|k| k.to_array()).collect());
    let model = Arc::new(model(&p, 4));
    let pose = RootPose {
        position_m: DVec3::ZERO,
        head_from_root: root.world_from_body,
    };
    let mut s = Strand::new(model, pose, Method::Exact);
    s.set_state(start, &vec![DVec3::ZERO; start.len()]);
    // The strand steps with its root where the fit put it (the pose above
    // is only its record).
    let motion = *root;
    let before = s.boundary_points_world(&motion);
    let mut worst: f64 = 0.0;
    for _ in 0..600 {
        s.step(&motion, g, DVec3::ZERO, 1.0 / 60.0);
        let now = s.boundary_points_world(&motion);
        for (a, b) in now.iter().zip(&before) {
            worst = worst.max((*a - *b).length());
        }
    }
    worst
}

#[test]
fn upright_strands_are_flagged_unstable_past_greenhills_column() {
    // A vertical strand under its own weight buckles at ρS g L³/EI = 7.8373
    // (7.8616 with N = 10 elements, docs/physics.md section 7). Straight
    // and upright, it needs no natural curvature: only the stability check
    // tells the two apart.
    let up = RigidMotion::at_rest(DVec3::ZERO, DMat3::from_cols(DVec3::Y, DVec3::Z, DVec3::X));
    for (alpha, status) in [(7.5, SagFreeStatus::Held), (8.2, SagFreeStatus::Unstable)] {
        let (p, g) = elastica(alpha, 10);
        let model = model(&p, 4);
        let q = vec![DVec3::ZERO; 10];
        let inputs = SagFreeInputs {
            root: &up,
            gravity_m_per_s2: g,
            support: None,
        };
        let rest = sag_free(&model, &q, &inputs);
        assert_eq!(
            rest.status, status,
            "α = {alpha}: stability {}",
            rest.stability
        );
        assert!(
            rest.natural_per_m
                .iter()
                .all(|k| k.abs().max_element() < 1e-12)
        );
    }
}

#[test]
fn absurd_rest_curvature_is_clamped_and_reported() {
    // A 1 m strand of thin hair held out horizontally would need a rest
    // curvature of ρS g L²/(2EI) ≈ 2000 m⁻¹ at the root.
    let mut p = params(1.0, 10);
    p.radius_m = 20e-6;
    let model = model(&p, 4);
    let q = vec![DVec3::ZERO; 10];
    let root = at_rest(DMat3::IDENTITY);
    let inputs = SagFreeInputs {
        root: &root,
        gravity_m_per_s2: DVec3::new(0.0, -9.81, 0.0),
        support: None,
    };
    let rest = sag_free(&model, &q, &inputs);
    // So far beyond its stiffness (α ≈ 3e4) the strand is also unstable,
    // which takes precedence in the status; the clamp happens either way.
    assert_ne!(rest.status, SagFreeStatus::Held);
    assert!(rest.max_strain_per_m > 1000.0, "{}", rest.max_strain_per_m);
    assert!(
        rest.natural_per_m
            .iter()
            .all(|k| k.abs().max_element() <= 1000.0)
    );
}

/// The stiffened column's stability against the margin asked for: the
/// closed form is exact, and the check's central differences are good to
/// about 1e-8.
const STIFFENED_MARGIN_TOL: f64 = 1e-6;
/// The buckling load ratio 7.8616 (N = 10) is known to five digits, so the
/// scale it predicts is good to about 1e-5; a tenth of a per mille.
const STIFFENING_SCALE_TOL: f64 = 1e-4;

#[test]
fn an_unstable_column_is_stiffened_by_its_load_ratio_and_then_stands() {
    // Upright at twice Greenhill's load (α_c = 7.8616 at N = 10): the
    // energy's scaled Hessian is I − A with λ_max(A) = α/α_c = 2, so the
    // margin m needs the moduli scaled by s = 2/(1 − m).
    let up = RigidMotion::at_rest(DVec3::ZERO, DMat3::from_cols(DVec3::Y, DVec3::Z, DVec3::X));
    let (p, g) = elastica(2.0 * 7.8616, 10);
    let q = vec![DVec3::ZERO; 10];
    let inputs = SagFreeInputs {
        root: &up,
        gravity_m_per_s2: g,
        support: None,
    };
    let options = StiffenOptions::default();
    let stiff = sag_free_stiffened(&p, 4, &q, &inputs, &options).expect("valid parameters");
    assert_eq!(stiff.rest.status, SagFreeStatus::Stiffened);
    let want = 2.0 / (1.0 - options.margin);
    assert!(
        (stiff.stiffness_scale / want - 1.0).abs() < STIFFENING_SCALE_TOL,
        "scale {} against {want}",
        stiff.stiffness_scale
    );
    assert!(
        (stiff.rest.stability - options.margin).abs() < STIFFENED_MARGIN_TOL,
        "stability {} against the margin {}",
        stiff.rest.stability,
        options.margin
    );
    // What holding it takes, read back from the stability it got, and from
    // the same column left as it is (no stiffening allowed): 2/(1 − m) both
    // times.
    let kept =
        sag_free_stiffened(&p, 4, &q, &inputs, &StiffenOptions::none()).expect("valid parameters");
    assert_eq!(kept.rest.status, SagFreeStatus::Unstable);
    for rest in [&stiff, &kept] {
        let needed = rest.needed_scale(options.margin).expect("a number");
        assert!(
            (needed / want - 1.0).abs() < STIFFENING_SCALE_TOL,
            "needed scale {needed} against {want}"
        );
    }
    // A column standing past its load does not need stiffening to be at
    // rest, only to stay there: nudged by a slight bend (tip off by about
    // 0.1% of the length), the original falls over, the stiffened one
    // sways about upright.
    let length_m = p.length_m;
    let nudge = vec![DVec3::new(0.0, 2e-3 / length_m, 0.0); 10];
    let fell = drift_over(&p, &q, &nudge, &up_root(), g);
    let stood = drift_over(
        &stiffened_params(&p, stiff.stiffness_scale),
        &q,
        &nudge,
        &up_root(),
        g,
    );
    assert!(
        fell > 0.3 * length_m,
        "the original should fall: moved {fell} m"
    );
    assert!(
        stood < 0.01 * length_m,
        "the stiffened column should stand: moved {stood} m"
    );
}

/// The upright root of the column tests.
fn up_root() -> RigidMotion {
    RigidMotion::at_rest(DVec3::ZERO, DMat3::from_cols(DVec3::Y, DVec3::Z, DVec3::X))
}

#[test]
fn stable_strands_are_not_stiffened() {
    let (p, g) = elastica(7.5, 10);
    let q = vec![DVec3::ZERO; 10];
    let up = up_root();
    let inputs = SagFreeInputs {
        root: &up,
        gravity_m_per_s2: g,
        support: None,
    };
    let stiff = sag_free_stiffened(&p, 4, &q, &inputs, &StiffenOptions::default())
        .expect("valid parameters");
    assert_eq!(stiff.rest.status, SagFreeStatus::Held);
    assert_eq!(stiff.stiffness_scale, 1.0);
}

/// Issue 30's bar: an imported strand with gravity off relaxes to the
/// natural shape of the hair that hung in the groom's shape within 1% of
/// its length.
const NATURAL_SHAPE_TOL_OVER_LENGTH: f64 = 0.01;

#[test]
fn imported_hair_relaxes_without_gravity_to_the_natural_shape_it_hung_from() {
    // The groom: heavy strands (α = ρS g L³/EI = 20) of known natural
    // shape, settled under gravity at 20 elements by the reference's
    // Dense step, sampled at 32 points evenly by arc length (a groom's
    // resolution). Imported as `import` does (default tolerances, the
    // elements the sag load asks for, sag-free for the same gravity and
    // material), the strand at rest without
    // gravity sits at its natural strains, from its fitted root frame:
    // compared with the true natural shape from the true root.
    let elements = 20;
    let cases = [
        ("straight", NaturalShape::Straight),
        (
            "planar curl",
            NaturalShape::Uniform {
                twist_per_m: 0.0,
                curvature1_per_m: 20.0,
                curvature2_per_m: 0.0,
            },
        ),
        (
            "helix",
            NaturalShape::Helix {
                radius_m: 0.02,
                step_m: 0.03,
            },
        ),
    ];
    let mut failures = 0;
    for (name, shape) in cases {
        let (mut p, g) = elastica(20.0, elements);
        p.natural_shape = shape;
        let mut s = strand(&p, Method::Dense);
        let root = at_rest(DMat3::IDENTITY);
        settle(&mut s, &root, g, 0.01, 1e-10, 40_000);
        let l = p.length_m;
        let element_m = l / elements as f64;
        let hung = UniformHelixChain {
            root_frame: DMat3::IDENTITY,
            element_length_m: element_m,
            strains_per_m: s.q().to_vec(),
        };
        let samples: Vec<f64> = (0..32).map(|i| l * i as f64 / 31.0).collect();
        let groom = hung.positions(&samples);
        let options = FitOptions {
            sag_load_per_m3: sag_load_per_m3(&p, g),
            ..FitOptions::default()
        };
        let fit = fit_polyline(&groom, DVec3::Y, &options).expect("clean");
        let fitted = &fit.chain;
        let fitted_params = StrandParams {
            length_m: fitted.length_m(),
            elements: fitted.elements(),
            ..p.clone()
        };
        let fitted_model = StrandModel::new(&fitted_params, 4).expect("valid");
        let fitted_root = RigidMotion::at_rest(fit.root_m, fitted.root_frame);
        let inputs = SagFreeInputs {
            root: &fitted_root,
            gravity_m_per_s2: g,
            support: None,
        };
        let rest = sag_free(&fitted_model, &fitted.strains_per_m, &inputs);
        let relaxed = UniformHelixChain {
            root_frame: fitted.root_frame,
            element_length_m: fitted.element_length_m,
            strains_per_m: rest.natural_per_m.clone(),
        };
        let truth = UniformHelixChain {
            root_frame: DMat3::IDENTITY,
            element_length_m: element_m,
            strains_per_m: p.natural_shape.strains(elements),
        };
        let compare: Vec<f64> = (0..=200)
            .map(|i| fitted.length_m().min(l) * i as f64 / 200.0)
            .collect();
        let off = relaxed
            .positions(&compare)
            .iter()
            .zip(truth.positions(&compare))
            .map(|(a, b)| a.distance(b))
            .fold(0.0, f64::max);
        let measured = format!(
            "{name}: {} elements fitted ({:?}, fit error {:.2e} of L, root tangent {:.2e} rad off), \
             relaxed {:.3}% of L from its natural shape",
            fitted.elements(),
            rest.status,
            fit.error_over_length,
            fitted.root_frame.x_axis.angle_between(DVec3::X),
            100.0 * off / l
        );
        eprintln!("{measured}");
        failures += usize::from(off >= NATURAL_SHAPE_TOL_OVER_LENGTH * l);
    }
    assert_eq!(failures, 0, "see the measurements above");
}

/// The fit's short series against the step's twenty terms: round-off.
const SERIES_AGREEMENT_TOL: f64 = 1e-15;

#[test]
fn the_fits_short_series_agree_with_the_steps_to_round_off() {
    // Over every range of y the term count changes at, both sides of it,
    // and past the series' limit (closed forms on both sides).
    for i in 0..=2000 {
        let y = 6.0 * (i as f64 / 2000.0).powi(3);
        let fit = FitCoefficients::at(y);
        let step = HelixCoefficients::at(y);
        let pairs = [
            (fit.a, step.a[0]),
            (fit.b, step.b[0]),
            (fit.c, step.c[0]),
            (fit.b1, step.b[1]),
            (fit.c1, step.c[1]),
        ];
        for (k, (got, want)) in pairs.into_iter().enumerate() {
            assert!(
                (got - want).abs() <= SERIES_AGREEMENT_TOL * want.abs().max(1e-3),
                "y = {y}: coefficient {k} is {got}, the step's {want}"
            );
        }
    }
}

/// The polyline's lumped weights against the integral, relative: the
/// trapezoid rule's error at 1000 segments is about 1e-6.
const SAG_ROTATION_TOL: f64 = 1e-5;

#[test]
fn the_sag_rotation_of_a_strand_held_out_is_a_sixth_of_its_load_and_of_a_hanging_one_none() {
    // Held out along x under gravity along −y: M(s) = w(L − s)²/2 with
    // w = ρS g/EI, so Θ = ∫ M ds = wL³/6 = α/6.
    let p = params(0.2, 10);
    let g = DVec3::new(0.0, -9.81, 0.0);
    let load = sag_load_per_m3(&p, g);
    let alpha = load.length() * p.length_m.powi(3);
    let out: Vec<DVec3> = (0..=1000)
        .map(|i| DVec3::X * (p.length_m * i as f64 / 1000.0))
        .collect();
    let theta = sag_rotation(&out, load);
    assert!(
        (theta / (alpha / 6.0) - 1.0).abs() < SAG_ROTATION_TOL,
        "Θ = {theta} against α/6 = {}",
        alpha / 6.0
    );
    // Hanging straight down, the weight beyond every point pulls along the
    // strand: no moment, no extra elements.
    let down: Vec<DVec3> = out.iter().map(|x| DVec3::new(0.0, -x.x, 0.0)).collect();
    assert!(sag_rotation(&down, load) < 1e-12 * alpha);
    let natural = FitOptions::default().natural_tolerance_over_length;
    assert_eq!(elements_for_sag(&down, load, natural), 1);
    // Held out, N = ⌈√(CΘ/e)⌉; without a sag load the search starts at 1.
    let want = (NATURAL_SHAPE_ERROR_CONSTANT * theta / natural)
        .sqrt()
        .ceil() as usize;
    assert_eq!(elements_for_sag(&out, load, natural), want);
    assert!(want > 1, "{want}");
    assert_eq!(elements_for_sag(&out, DVec3::ZERO, natural), 1);
}

/// The stiffening cap is where the moduli leave their valid range
/// (1e12 Pa): 1e12 / 3.9e9 = 256 for the default hair (its shear
/// modulus, 0.9e9, would allow 1111); a stiffer material gets less room.
#[test]
fn the_stiffening_cap_keeps_the_moduli_in_their_range() {
    let hair = StrandParams::default();
    let cap = max_stiffness_scale(&hair);
    assert!((cap - 1e12 / 3.9e9).abs() < 1e-9, "{cap}");
    assert_eq!(StiffenOptions::default().max_scale, cap);
    let stiff = StrandParams {
        shear_modulus_pa: 4e10,
        ..hair.clone()
    };
    assert!((max_stiffness_scale(&stiff) - 25.0).abs() < 1e-12);
    let scaled = stiffened_params(&hair, cap);
    scaled.validate().expect("the capped moduli are valid");
}

/// 16 points along `curve(s)` for s in [0, 0.15] m, each moved by
/// `noise_m` along the binormal-ish axis with a fixed pattern (a groom's
/// last tenths of a millimetre).
fn noisy_points(curve: impl Fn(f64) -> DVec3, noise_m: f64) -> Vec<DVec3> {
    (0..16)
        .map(|i| {
            let wiggle = if i == 0 {
                0.0
            } else {
                ((i * 7 % 5) as f64 - 2.0) / 2.0
            };
            curve(0.15 * i as f64 / 15.0) + DVec3::Z * noise_m * wiggle
        })
        .collect()
}

/// The largest twist angle of an element, ℓ|τ| (rad).
fn largest_twist_angle(fit: &helixhair_physics::fit::StrandFit) -> f64 {
    let l = fit.chain.element_length_m;
    fit.chain
        .strains_per_m
        .iter()
        .map(|q| (l * q.x).abs())
        .fold(0.0, f64::max)
}

/// A polyline carries no material twist: a nearly straight groom strand
/// keeps only the twist its points need (a planar arc needs none; its
/// noise, a little), and a helix keeps the twist its shape needs.
#[test]
fn fitted_strands_carry_only_the_twist_their_shape_needs() {
    // A gentle arc (radius 0.5 m) in the x–y plane, 0.05 mm off the plane.
    let arc = noisy_points(
        |s| DVec3::new(0.5 * (s / 0.5).sin(), -0.5 * (1.0 - (s / 0.5).cos()), 0.0),
        5e-5,
    );
    let chords = helixhair_physics::fit::initial::chord_arc_lengths(&arc);
    // As import fits it: with the sag's elements (more than the position
    // alone needs), whose spare freedom a position fit spends on twist.
    let sag = sag_load_per_m3(&StrandParams::default(), DVec3::new(0.0, -9.81, 0.0));
    for tolerance in [1e-3, 3e-4] {
        let options = FitOptions {
            tolerance_over_length: tolerance,
            sag_load_per_m3: sag,
            ..FitOptions::default()
        };
        let fit = fit_polyline(&arc, DVec3::Z, &options).expect("clean");
        let n = fit.chain.elements();
        let unrelaxed = fit_with_elements(&arc, n, DVec3::Z, &chords, &options);
        let (angle, before) = (largest_twist_angle(&fit), largest_twist_angle(&unrelaxed));
        println!(
            "arc at {tolerance}: N = {n}, error {:.2e} of L, largest twist angle {angle:.3e} rad \
             (the position fit alone: {before:.3e})",
            fit.error_over_length
        );
        assert!(fit.within_tolerance, "{tolerance}");
        assert!(angle <= ARC_TWIST_RAD, "{tolerance}: {angle} rad");
    }
    // A left-handed helix of radius 1 cm and pitch 2 cm: torsion
    // −c/(r² + c²) with c = pitch/2π, −28.9 rad/m; every element keeps it.
    let (r, c) = (0.01, 0.02 / std::f64::consts::TAU);
    let k = 1.0 / (r * r + c * c).sqrt();
    let helix = noisy_points(
        |s| DVec3::new(r * (s * k).cos() - r, c * s * k, r * (s * k).sin()),
        5e-5,
    );
    let options = FitOptions {
        tolerance_over_length: 1e-3,
        ..FitOptions::default()
    };
    let fit = fit_polyline(&helix, DVec3::X, &options).expect("clean");
    let torsion = -c / (r * r + c * c);
    let twists: Vec<f64> = fit.chain.strains_per_m.iter().map(|q| q.x).collect();
    println!(
        "helix: N = {}, error {:.2e} of L, twists {twists:.1?} against the torsion {torsion:.1}",
        fit.chain.elements(),
        fit.error_over_length
    );
    assert!(fit.within_tolerance);
    for t in twists {
        assert!(
            (t / torsion - 1.0).abs() < HELIX_TWIST_TOL,
            "{t} against {torsion}"
        );
    }
}

/// The arc's largest element twist angle, fitted with the sag's nine
/// elements: a planar arc needs none, its 0.05 mm of noise almost none.
/// Measured 0.037 rad at both tolerances, where the position fit alone at
/// the same N spends 3.5 rad (210 rad/m) on the noise.
const ARC_TWIST_RAD: f64 = 0.1;
/// The helix's fitted twists against its torsion: the noise and six
/// elements' fit move them by a few per cent (measured at most 8%).
const HELIX_TWIST_TOL: f64 = 0.1;
