//! Diagnostic: which explicit part of the step makes a 30 cm strand blow up
//! under a head shake at 1/60 s? A Dense step whose matrix may also carry
//! −h ∂Q/∂q̇ and −h² ∂Q/∂q (both by central differences of the forces stage).
//!
//! `cargo run --release -p helixhair-physics --example implicit_probe -- MODE [substeps] [wavy]`
//! MODE: `old` (today's step), `vel` (+ velocity terms), `pos` (+ position
//! terms), `both`.

use std::sync::Arc;

use glam::DVec3;
use helixhair_physics::motion::HeadTrajectory;
use helixhair_physics::step::forces::{ForceInputs, generalized_forces};
use helixhair_physics::step::mass::{MassData, dense_mass, mass_blocks};
use helixhair_physics::step::reconstruct::{Kinematics, reconstruct};
use helixhair_physics::{
    ElementLayout, NaturalShape, Oscillation, RigidMotion, RootPose, StrandModel, StrandParams,
};
use nalgebra::{DMatrix, DVector};

fn forces(model: &StrandModel, q: &[DVec3], v: &[DVec3], root: &RigidMotion) -> DVector<f64> {
    let mut kin = Kinematics::default();
    reconstruct(model, q, v, root, &mut kin);
    let inputs = ForceInputs {
        root,
        gravity_m_per_s2: DVec3::new(0.0, -9.81, 0.0),
        air_velocity_m_per_s: DVec3::ZERO,
        external_n_per_m: &[],
        contact: None,
        volume: None,
    };
    let mut out = vec![DVec3::ZERO; model.elements()];
    generalized_forces(model, &kin, &inputs, &mut out);
    DVector::from_iterator(3 * out.len(), out.iter().flat_map(|x| x.to_array()))
}

fn perturb(x: &[DVec3], i: usize, e: f64) -> Vec<DVec3> {
    let mut y = x.to_vec();
    y[i / 3][i % 3] += e;
    y
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let mode = args.get(1).cloned().unwrap_or("old".into());
    let substeps: u32 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(1);
    let wavy = args.get(3).map(|s| s == "wavy").unwrap_or(false);
    let params = StrandParams {
        length_m: 0.3,
        elements: 12,
        layout: ElementLayout::Graded {
            tip_to_root_ratio: 3.0,
        },
        radius_m: 40e-6,
        natural_shape: if wavy {
            NaturalShape::Helix {
                radius_m: 0.025,
                step_m: 0.12,
            }
        } else {
            NaturalShape::Straight
        },
        ..StrandParams::default()
    };
    let model = Arc::new(StrandModel::new(&params, 3).unwrap());
    let n = model.elements();
    let root = RootPose::from_direction(
        DVec3::new(0.0966, 0.0259, 0.0),
        DVec3::new(0.9659, 0.2588, 0.0),
        DVec3::Z,
    );
    let shake = Oscillation {
        axis: DVec3::Y,
        amplitude_rad: 0.5,
        frequency_hz: 1.5,
    };
    let h = 1.0 / 60.0 / f64::from(substeps);
    let mut q = model.natural.clone();
    let mut v = vec![DVec3::ZERO; n];
    let drag_rate = model.air_drag / model.mass_per_length;
    let mut t = 0.0;
    let mut kin = Kinematics::default();
    let mut mass = MassData::default();
    for step in 0..(600 * substeps) {
        let motion = shake.motion_at(t).carry(&root);
        reconstruct(&model, &q, &v, &motion, &mut kin);
        mass_blocks(&model, &kin, &mut mass);
        let m = dense_mass(&kin, &mass);
        let f0 = forces(&model, &q, &v, &motion);
        let mut a = &m * (1.0 + h * drag_rate);
        let vv = DVector::from_iterator(3 * n, v.iter().flat_map(|x| x.to_array()));
        let qq = DVector::from_iterator(3 * n, q.iter().flat_map(|x| x.to_array()));
        let qn = DVector::from_iterator(3 * n, model.natural.iter().flat_map(|x| x.to_array()));
        let kd = DVector::from_iterator(3 * n, model.stiffness.iter().flat_map(|x| x.to_array()));
        let cd = DVector::from_iterator(3 * n, model.friction.iter().flat_map(|&c| [c; 3]));
        for i in 0..3 * n {
            a[(i, i)] += h * cd[i] + h * h * kd[i];
        }
        let mut rhs = (&f0
            - kd.component_mul(&(&qq - &qn))
            - (&cd + &kd * h).component_mul(&vv)
            - &m * &vv * drag_rate)
            * h;
        let a_old = a.clone();
        if mode.starts_with("vel") || mode.starts_with("rich") || mode == "both" {
            let mut dv = DMatrix::zeros(3 * n, 3 * n);
            for i in 0..3 * n {
                let e = 1e-3 * (1.0 + v[i / 3][i % 3].abs());
                let col = (forces(&model, &q, &perturb(&v, i, e), &motion)
                    - forces(&model, &q, &perturb(&v, i, -e), &motion))
                    / (2.0 * e);
                dv.set_column(i, &col);
            }
            let dv = match mode.as_str() {
                "velsym" => (&dv + dv.transpose()) * 0.5,
                "velskew" => (&dv - dv.transpose()) * 0.5,
                _ => dv,
            };
            if mode == "velcount" && step % 10 == 0 {
                let p = a.clone();
                let g = -&dv * h;
                let plu = p.clone().lu();
                let pinv_g = plu.solve(&g).unwrap();
                let eig = pinv_g.complex_eigenvalues();
                let rho = eig.iter().map(|z| z.norm()).fold(0.0, f64::max);
                // Right-preconditioned GMRES iteration count to 1e-8.
                let full = &p + &g;
                let b = rhs.clone();
                let mut basis: Vec<DVector<f64>> = vec![b.normalize()];
                let beta = b.norm();
                let mut hess = DMatrix::<f64>::zeros(40, 40);
                let mut iters = 0;
                for k in 0..39 {
                    let w0 = &full * plu.solve(&basis[k]).unwrap();
                    let mut w = w0.clone();
                    for (j, bj) in basis.iter().enumerate() {
                        let hj = bj.dot(&w);
                        hess[(j, k)] = hj;
                        w -= bj * hj;
                    }
                    let hn = w.norm();
                    hess[(k + 1, k)] = hn;
                    // least squares residual
                    let hk = hess.view((0, 0), (k + 2, k + 1)).clone_owned();
                    let mut e1 = DVector::zeros(k + 2);
                    e1[0] = beta;
                    let y = hk.clone().svd(true, true).solve(&e1, 1e-300).unwrap();
                    let res = (&e1 - &hk * &y).norm() / beta;
                    iters = k + 1;
                    if res < 1e-8 || hn < 1e-300 {
                        break;
                    }
                    basis.push(w / hn);
                }
                println!("t = {t:.3}  rho(P^-1 hG) = {rho:.3}  gmres iters {iters}");
            }
            a -= dv * h;
        }
        if mode == "pos" || mode == "both" {
            let mut dq = DMatrix::zeros(3 * n, 3 * n);
            for i in 0..3 * n {
                let e = 1e-6;
                let col = (forces(&model, &perturb(&q, i, e), &v, &motion)
                    - forces(&model, &perturb(&q, i, -e), &v, &motion))
                    / (2.0 * e);
                dq.set_column(i, &col);
            }
            rhs += &dq * &vv * (h * h);
            a -= dq * (h * h);
        }
        let dvel = if let Some(k) = mode.strip_prefix("rich") {
            // Richardson on (P + hG) x = rhs, preconditioned by P (today's matrix).
            let k: usize = k.parse().unwrap();
            let plu = a_old.clone().lu();
            let g = &a - &a_old;
            let mut x = plu.solve(&rhs).unwrap();
            for _ in 0..k {
                x = plu.solve(&(&rhs - &g * &x)).unwrap();
            }
            x
        } else {
            a.lu().solve(&rhs).expect("solvable")
        };
        for e in 0..n {
            v[e] += DVec3::new(dvel[3 * e], dvel[3 * e + 1], dvel[3 * e + 2]);
            q[e] += h * v[e];
        }
        t += h;
        if !q.iter().all(|x| x.is_finite()) || v.iter().any(|x| x.length() > 1e6) {
            println!("{mode}: blew up at t = {t:.3} s");
            return;
        }
        if (step + 1) % (60 * substeps) == 0 {
            let speed: f64 = kin
                .point_velocities_m_per_s
                .iter()
                .map(|x| x.length())
                .fold(0.0, f64::max);
            println!(
                "{mode}: t = {t:.1} s  tip-ish speed {speed:.3} m/s  |v|max {:.3e}",
                v.iter().map(|x| x.length()).fold(0.0, f64::max)
            );
        }
    }
}
