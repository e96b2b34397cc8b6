//! The contact Block-diagonal's blocks leave out, (C − C_bd) x
//! (`batch::step::block_contact`), against C assembled point by point:
//! C = Σ_points Jᵀ a aᵀ J, where a point of element k moves with the
//! elements before it, J_i x_i = A_i x_i + (B_i x_i) × (p − end_i).
//! The recursion carries twists and wrenches along the strand through
//! spatial inertias; the assembly reads only the points' positions.

use helixhair_physics::batch::layout::{ElementData, StepEnv};
use helixhair_physics::batch::step::block_contact::add_contact_coupling;
use helixhair_physics::batch::step::block_diagonal::blocks_tip_to_root;
use helixhair_physics::batch::vec::{M3, V3};
use helixhair_physics::model::StrandModel;

use crate::common::{Rng, params};

/// The recursion against the assembly, relative to |C x|: f64 round-off
/// over a handful of 3×3 products per element (measured at most 3.8e-16).
const ASSEMBLY_TOL: f64 = 1e-12;

/// Random vectors and matrices, entries in [−1, 1), from the tests' one
/// generator.
trait Draws {
    fn v3(&mut self) -> V3<f64>;
    fn m3(&mut self) -> M3<f64>;
}

impl Draws for Rng {
    fn v3(&mut self) -> V3<f64> {
        V3::new(self.next(), self.next(), self.next())
    }
    fn m3(&mut self) -> M3<f64> {
        M3::from_cols(self.v3(), self.v3(), self.v3())
    }
}

/// A point in contact: its direction a (√weight · normal) and its position.
struct Point {
    a: V3<f64>,
    position: V3<f64>,
}

/// A chain as [`chain`] makes it: the sweep's element data, each
/// element's contact points, each element's end point.
struct Chain {
    scratch: Vec<ElementData<f64>>,
    points: Vec<Vec<Point>>,
    ends: Vec<V3<f64>>,
}

/// A chain of `n` elements with random Jacobians and spans, and the
/// contact points of each element (some elements none), as the forward
/// sweep leaves them: each element's point inertias about its start.
fn chain(n: usize, numbers: &mut Rng) -> Chain {
    let mut scratch = Vec::new();
    let mut points = Vec::new();
    let mut ends = Vec::new();
    let mut start = V3::zero();
    for e in 0..n {
        let mut el = ElementData::zero();
        el.a = numbers.m3();
        el.b = numbers.m3();
        el.span = numbers.v3().scale(0.01);
        let count = if e % 3 == 1 { 0 } else { 1 + e % 3 };
        let own: Vec<Point> = (0..count)
            .map(|_| {
                let offset = el.span.scale(0.5 + 0.5 * numbers.next()) + numbers.v3().scale(1e-3);
                Point {
                    a: numbers.v3().scale(30.0),
                    position: start + offset,
                }
            })
            .collect();
        for p in &own {
            el.contact.add_point(p.a, p.position - start);
        }
        el.touching = !own.is_empty();
        start += el.span;
        ends.push(start);
        scratch.push(el);
        points.push(own);
    }
    Chain {
        scratch,
        points,
        ends,
    }
}

/// (C x)_i and (C_bd x)_i assembled point by point.
fn assembled(
    scratch: &[ElementData<f64>],
    points: &[Vec<Point>],
    ends: &[V3<f64>],
    x: &[V3<f64>],
) -> (Vec<V3<f64>>, Vec<V3<f64>>) {
    let n = scratch.len();
    let jacobian = |i: usize, p: &Point, z: V3<f64>| {
        let el = &scratch[i];
        el.a.mul_vec(z) + el.b.mul_vec(z).cross(p.position - ends[i])
    };
    // Jᵀw = Aᵀw + Bᵀ((p − end) × w), the adjoint of the map above.
    let transposed = |i: usize, p: &Point, w: V3<f64>| {
        let el = &scratch[i];
        el.a.t_mul_vec(w) + el.b.t_mul_vec((p.position - ends[i]).cross(w))
    };
    let (mut whole, mut diagonal) = (vec![V3::zero(); n], vec![V3::zero(); n]);
    for (k, own) in points.iter().enumerate() {
        for p in own {
            let speed = (0..k).fold(0.0, |s, j| s + p.a.dot(jacobian(j, p, x[j])));
            for i in 0..k {
                whole[i] += transposed(i, p, p.a.scale(speed));
                let own_speed = p.a.dot(jacobian(i, p, x[i]));
                diagonal[i] += transposed(i, p, p.a.scale(own_speed));
            }
        }
    }
    (whole, diagonal)
}

fn length(x: &[V3<f64>]) -> f64 {
    x.iter().map(|v| v.dot(*v)).sum::<f64>().sqrt()
}

#[test]
fn the_coupling_is_the_assembled_contact_less_its_diagonal_blocks() {
    let mut numbers = Rng::new(7);
    for n in [1, 3, 5, 12] {
        let Chain {
            scratch,
            points,
            ends,
        } = chain(n, &mut numbers);
        let x: Vec<V3<f64>> = (0..n).map(|_| numbers.v3()).collect();
        let (whole, diagonal) = assembled(&scratch, &points, &ends, &x);
        let blocks = contact_blocks(&scratch);
        let from_blocks: Vec<V3<f64>> = blocks.iter().zip(&x).map(|(b, x)| b.mul_vec(*x)).collect();
        // Starting from the diagonal share, scale 1, `out` becomes C x.
        let mut out = from_blocks.clone();
        add_coupling(&scratch, &blocks, &x, &mut out);
        let size = length(&whole).max(f64::MIN_POSITIVE);
        let diagonal_error: Vec<V3<f64>> = from_blocks
            .iter()
            .zip(&diagonal)
            .map(|(a, b)| *a - *b)
            .collect();
        let whole_error: Vec<V3<f64>> = out.iter().zip(&whole).map(|(a, b)| *a - *b).collect();
        println!(
            "{n} elements: C_bd x off by {:.1e}, C x by {:.1e} of |C x|",
            length(&diagonal_error) / size,
            length(&whole_error) / size
        );
        assert!(
            length(&diagonal_error) <= ASSEMBLY_TOL * size,
            "{n} elements: C_bd x off by {:e} of |C x|",
            length(&diagonal_error) / size
        );
        assert!(
            length(&whole_error) <= ASSEMBLY_TOL * size,
            "{n} elements: C x off by {:e} of |C x|",
            length(&whole_error) / size
        );
        if n > 2 {
            // Not vacuous: the joint motion's share is of the order of the whole.
            let coupling = length(
                &whole_error
                    .iter()
                    .zip(&whole)
                    .zip(&diagonal)
                    .map(|((_, w), d)| *w - *d)
                    .collect::<Vec<_>>(),
            );
            assert!(
                coupling > 0.1 * size,
                "{n} elements: coupling {coupling:e} of {size:e}"
            );
        }
    }
}

#[test]
fn no_contact_adds_nothing() {
    let mut numbers = Rng::new(11);
    let mut scratch = chain(6, &mut numbers).scratch;
    for el in &mut scratch {
        el.contact = ElementData::<f64>::zero().contact;
        el.touching = false;
    }
    let x: Vec<V3<f64>> = (0..6).map(|_| numbers.v3()).collect();
    let blocks = contact_blocks(&scratch);
    let mut out = vec![V3::zero(); 6];
    add_coupling(&scratch, &blocks, &x, &mut out);
    assert_eq!(length(&out), 0.0);
}

/// Each element's C_bd as the Block-diagonal step's block sweep hands it
/// on (the element data alone decide it; the strand's constants only
/// its other terms).
fn contact_blocks(scratch: &[ElementData<f64>]) -> Vec<M3<f64>> {
    let n = scratch.len();
    let model = StrandModel::new(&params(0.2, n), 4).expect("valid params");
    let env = StepEnv {
        h_secs: 1.0 / 60.0,
        gravity_m_per_s2: [0.0, -9.81, 0.0],
        air_velocity_m_per_s: [0.0; 3],
    };
    let (mut q, mut v) = (vec![V3::zero(); n], vec![V3::zero(); n]);
    let mut blocks = vec![M3::zero(); n];
    blocks_tip_to_root::<f64, true>(
        &model,
        &env,
        scratch,
        0.0,
        &mut q,
        &mut v,
        None,
        None,
        |e, _, contact, _, _, _| blocks[e] = contact,
    );
    blocks
}

/// `out += (C − C_bd) x` at scale 1, with scratch wrench buffers.
fn add_coupling(
    scratch: &[ElementData<f64>],
    blocks: &[M3<f64>],
    x: &[V3<f64>],
    out: &mut [V3<f64>],
) {
    let (mut force, mut torque) = (vec![V3::zero(); x.len()], vec![V3::zero(); x.len()]);
    add_contact_coupling(scratch, blocks, x, 1.0, &mut force, &mut torque, out);
}
