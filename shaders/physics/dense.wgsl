// Dense step on the GPU (appended to common.wgsl and chain.wgsl): the whole 3N×3N step
// matrix S = s·M + diag(D) assembled and Cholesky-factored by one workgroup
// per strand. The arithmetic is crates/physics/src/batch/step/dense.rs; the CPU
// twins are crates/physics/src/gpu/dense_twin.rs. Three stages per step:
//   stage_frames   (chain.wgsl) one invocation per strand: the root-to-tip
//                  frame chain and A_Q (about the root: Dense keeps root
//                  moments), B_Q
//   stage_elements one invocation per element: own sums, with U_Q and V_Q
//   stage_dense    one workgroup (DENSE_WORKGROUP invocations) per strand:
//                  (1) invocation 0 runs the tip-to-root suffix: X_Q, Y_Q
//                      into workgroup memory, the diagonal blocks of S into
//                      the matrix, the right-hand side into `solution`;
//                  (2) all invocations assemble the blocks below the
//                      diagonal, s·(X_Qᵀ A_P + Y_Qᵀ B_P) for P < Q;
//                  (3) right-looking square-root-free Cholesky
//                      S = L D Lᵀ, column k: all update the trailing lower
//                      triangle and the right-hand side (the forward
//                      substitution), one row per invocation, one barrier;
//                  (4) back substitution, one entry per barrier;
//                  (5) integrate, one element per invocation.
// The matrix lives in a storage buffer (9N² floats per strand, row-major,
// the factors overwriting the lower triangle): at N = 20 it is 14.4 KB, too
// big for wgpu's default 16 KiB of workgroup memory once X and Y are there
// too. X, Y and the two solution vectors sit in workgroup memory, which
// caps N at MAX_DENSE_ELEMENTS = 64 (7.5 KiB).

@group(0) @binding(7) var<storage, read_write> own: array<DenseOwn>;
@group(0) @binding(8) var<storage, read_write> matrix: array<f32>;

// An element's own sums with U_Q = Σ wρS G and V_Q = Σ wρS [r]×G.
struct DenseOwn {
    own: Own,
    u: mat3x3<f32>,
    v: mat3x3<f32>,
}

const DENSE_WORKGROUP: u32 = 32u;
const MAX_DENSE_ELEMENTS: u32 = 64u;

var<workgroup> column_x: array<mat3x3<f32>, MAX_DENSE_ELEMENTS>;
var<workgroup> column_y: array<mat3x3<f32>, MAX_DENSE_ELEMENTS>;
// 3 · MAX_DENSE_ELEMENTS each: rhs (then z, then partial sums of the back
// substitution), and Δv.
var<workgroup> solution: array<f32, 192>;
var<workgroup> delta_v: array<f32, 192>;

@compute @workgroup_size(64)
fn stage_elements(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = flat_index(id, groups);
    if i >= params.strand_count * params.elements {
        return;
    }
    let e = i % params.elements;
    let sums = own_sums(e, frame_state(frames[i]), q[i].xyz, v[i].xyz, true);
    own[i] = DenseOwn(sums.own, sums.u, sums.v);
}

// Row-major index of entry (row, col) of strand `base`'s matrix.
fn at(base: u32, dim: u32, row: u32, col: u32) -> u32 {
    return base + row * dim + col;
}

@compute @workgroup_size(DENSE_WORKGROUP)
fn stage_dense(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let strand = group.x + group.y * groups.x;
    if strand >= params.strand_count {
        return;
    }
    let n = params.elements;
    let dim = 3u * n;
    let first = strand * n;
    let base = strand * dim * dim;
    let sc = params.mass_scale;

    // (1) Tip-to-root suffix: X, Y, diagonal blocks, right-hand side.
    if lid == 0u {
        var b = zero_beyond();
        for (var k = 0u; k < n; k++) {
            let e = n - 1u - k;
            let i = first + e;
            let el = own[i];
            let terms = element_terms(jacobians[i], el.own, b);
            column_x[e] = el.u + terms.x_beyond;
            column_y[e] = el.v + terms.y_beyond;
            let st = step_terms(e, terms.force, q[i].xyz, v[i].xyz);
            let block = add_diagonal(terms.mass_block * sc, st[0]);
            for (var r = 0u; r < 3u; r++) {
                for (var c = 0u; c < 3u; c++) {
                    matrix[at(base, dim, 3u * e + r, 3u * e + c)] = block[c][r];
                }
                solution[3u * e + r] = st[1][r];
            }
            add_beyond(&b, el.own);
        }
    }
    workgroupBarrier();
    storageBarrier();

    // (2) Blocks below the diagonal: rows of element `child`, columns of
    // element `parent` < `child`.
    for (var t = lid; t < n * n; t += DENSE_WORKGROUP) {
        let child = t / n;
        let parent = t % n;
        if parent < child {
            let jac = jacobians[first + parent];
            let block = (transpose(column_x[child]) * jac.a + transpose(column_y[child]) * jac.b) * sc;
            for (var r = 0u; r < 3u; r++) {
                for (var c = 0u; c < 3u; c++) {
                    matrix[at(base, dim, 3u * child + r, 3u * parent + c)] = block[c][r];
                }
            }
        }
    }
    storageBarrier();

    // (3) S = L D Lᵀ (square-root-free Cholesky) with L z = rhs folded
    // in. Column k is read, never written, while rows i > k update: one
    // barrier per column.
    for (var k = 0u; k < dim; k++) {
        let d_k = matrix[at(base, dim, k, k)];
        let z_k = solution[k];
        for (var i = k + 1u + lid; i < dim; i += DENSE_WORKGROUP) {
            let c = matrix[at(base, dim, i, k)] / d_k;
            for (var j = k + 1u; j <= i; j++) {
                matrix[at(base, dim, i, j)] -= c * matrix[at(base, dim, j, k)];
            }
            solution[i] -= c * z_k;
        }
        workgroupBarrier();
        storageBarrier();
    }

    // (4) Back substitution D Lᵀ Δv = z, last row first: every invocation
    // forms x_k, invocation 0 keeps it, the others fold it into rows < k.
    for (var t = 0u; t < dim; t++) {
        let k = dim - 1u - t;
        let x_k = solution[k] / matrix[at(base, dim, k, k)];
        for (var i = lid; i < k; i += DENSE_WORKGROUP) {
            solution[i] -= matrix[at(base, dim, k, i)] * x_k;
        }
        if lid == 0u {
            delta_v[k] = x_k;
        }
        workgroupBarrier();
    }

    // (5) Integrate.
    for (var e = lid; e < n; e += DENSE_WORKGROUP) {
        let i = first + e;
        let dv = vec3<f32>(delta_v[3u * e], delta_v[3u * e + 1u], delta_v[3u * e + 2u]);
        let v_next = v[i].xyz + dv;
        v[i] = vec4<f32>(v_next, 0.0);
        q[i] = vec4<f32>(q[i].xyz + v_next * params.h_secs, 0.0);
    }
}
