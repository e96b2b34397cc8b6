//! CPU twins of the Dense kernel (`shaders/physics/dense.wgsl`): one
//! function per entry point, same name, bindings in binding order, with the
//! f32 arithmetic of [`crate::batch::step::dense`] at width 1. Dense still takes
//! its moments about the root (A_P must be paired with X_Q, Y_Q of every
//! Q > P, so local moments would move A_P to each Q's end point); its
//! `stage_frames` stores the root-based A_Q and a zero span
//! ([`super::twin::frame_chain`]).

use crate::batch::forward::own_sums;
use crate::batch::layout::ElementData;
use crate::batch::step::dense::{DenseScratch, assemble, columns, ldlt_solve};
use crate::batch::suffix::{integrate, mass_scale, step_terms};
use crate::batch::vec::V3;

use super::layout::{
    DenseOwnGpu, ElementConstGpu, FrameGpu, JacobiansGpu, ParamsGpu, RootPoseGpu, m3, m4, v3, v4,
};
use super::twin::{element_of, frame_chain, frame_of, model_of, own_of};

/// Twin of Dense's `stage_frames`: per strand, the frame chain and A_Q
/// (about the root), B_Q.
pub fn stage_frames(
    params: &ParamsGpu,
    elements: &[ElementConstGpu],
    roots: &[RootPoseGpu],
    q: &[[f32; 4]],
    v: &[[f32; 4]],
    frames: &mut [FrameGpu],
    jacobians: &mut [JacobiansGpu],
) {
    frame_chain(params, elements, roots, (q, v), frames, jacobians);
}

/// Twin of `stage_elements`: per element, its own sums with U_Q and V_Q.
pub fn stage_elements(
    params: &ParamsGpu,
    elements: &[ElementConstGpu],
    q: &[[f32; 4]],
    v: &[[f32; 4]],
    frames: &[FrameGpu],
    own: &mut [DenseOwnGpu],
) {
    let (model, env) = model_of(params, elements);
    let n = params.elements as usize;
    for (i, out) in own.iter_mut().enumerate() {
        let el = own_sums::<f32, true>(
            &model,
            &env,
            i % n,
            &frame_of(&frames[i]),
            v3(q[i]),
            v3(v[i]),
        );
        *out = DenseOwnGpu {
            own: own_of(&el),
            u: m4(&el.u),
            v: m4(&el.v),
        };
    }
}

/// Strand `strand`'s element data (A, B, own sums, U, V) from the buffers.
fn strand_data(
    n: usize,
    strand: usize,
    jacobians: &[JacobiansGpu],
    own: &[DenseOwnGpu],
) -> Vec<ElementData<f32>> {
    (strand * n..(strand + 1) * n)
        .map(|i| ElementData {
            u: m3(&own[i].u),
            v: m3(&own[i].v),
            ..element_of(&jacobians[i], &own[i].own)
        })
        .collect()
}

/// Twin of `stage_dense`: per strand, the suffix, the assembly of S, the
/// L D Lᵀ solve and the integration. `matrix` holds 9N² floats per
/// strand, row-major; afterwards its lower triangle holds the factors, as
/// the kernel leaves it (the kernel leaves the upper triangle unwritten).
pub fn stage_dense(
    params: &ParamsGpu,
    elements: &[ElementConstGpu],
    q: &mut [[f32; 4]],
    v: &mut [[f32; 4]],
    jacobians: &[JacobiansGpu],
    own: &[DenseOwnGpu],
    matrix: &mut [f32],
) {
    let (model, env) = model_of(params, elements);
    let n = params.elements as usize;
    let dim = 3 * n;
    let scale = mass_scale(&model, &env);
    let mut dense = DenseScratch::<f32>::new(n);
    let strands = q.len() / n.max(1);
    for strand in 0..strands {
        let data = strand_data(n, strand, jacobians, own);
        columns(&data, &mut dense.columns);
        for e in 0..n {
            let i = strand * n + e;
            let (diagonal, rhs) =
                step_terms(&model, &env, e, dense.columns[e].force, v3(q[i]), v3(v[i]));
            dense.diagonal[e] = diagonal;
            dense.rhs[3 * e..3 * e + 3].copy_from_slice(&[rhs.x, rhs.y, rhs.z]);
        }
        let s = &mut matrix[strand * dim * dim..(strand + 1) * dim * dim];
        assemble(&data, &dense.columns, scale, &dense.diagonal, s);
        ldlt_solve(dim, s, &mut dense.rhs);
        for e in 0..n {
            let i = strand * n + e;
            let (mut qi, mut vi) = (v3(q[i]), v3(v[i]));
            let x = &dense.rhs[3 * e..3 * e + 3];
            integrate(env.h_secs, &mut qi, &mut vi, V3::new(x[0], x[1], x[2]));
            q[i] = v4(qi);
            v[i] = v4(vi);
        }
    }
}

/// Not a stage: the mass matrix M (row-major 3N×3N, both triangles) of
/// strand `strand` as `stage_dense` assembles it, before the mass scale
/// and the step diagonal are applied; for checking the assembly against
/// the f64 reference's [`crate::step::mass::dense_mass`].
pub fn mass_matrix(
    params: &ParamsGpu,
    strand: usize,
    jacobians: &[JacobiansGpu],
    own: &[DenseOwnGpu],
) -> Vec<f32> {
    let n = params.elements as usize;
    let data = strand_data(n, strand, jacobians, own);
    let mut dense = DenseScratch::<f32>::new(n);
    columns(&data, &mut dense.columns);
    assemble(
        &data,
        &dense.columns,
        1.0,
        &vec![V3::zero(); n],
        &mut dense.matrix,
    );
    dense.matrix
}
