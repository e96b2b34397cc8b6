// Block-diagonal step on the GPU (appended to common.wgsl and chain.wgsl).
// Four stages per step, each a dispatch:
//   stage_frames   (chain.wgsl) one invocation per strand: the root-to-tip
//                  frame chain (R, ω, α, p, ṗ, p̈ at each element start) and
//                  A_Q (about the element's end), B_Q
//   stage_elements one invocation per element: its quadrature samples and
//                  own sums (forces, D_Q, mass moments)
//   stage_suffix   one invocation per strand: tip-to-root suffix sums
//   stage_solve    one invocation per element: M_QQ and Q_Q from the sums,
//                  the 3×3 solve, integrate
// The chain and the suffix are sequential per strand (N ≤ 200 steps of a
// few hundred flops); the per-element stages carry the bulk of the work.

// Moments about each element's end (see chain.wgsl).
const LOCAL_MOMENTS: bool = true;

@group(0) @binding(7) var<storage, read_write> own: array<Own>;
@group(0) @binding(8) var<storage, read_write> beyond: array<Beyond>;

@compute @workgroup_size(64)
fn stage_elements(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = flat_index(id, groups);
    if i >= params.strand_count * params.elements {
        return;
    }
    let e = i % params.elements;
    // Moments about the element's start (local moments).
    var s = frame_state(frames[i]);
    s.p = vec3<f32>(0.0);
    own[i] = own_sums(e, s, q[i].xyz, v[i].xyz, false).own;
}

@compute @workgroup_size(64)
fn stage_suffix(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let strand = flat_index(id, groups);
    if strand >= params.strand_count {
        return;
    }
    let n = params.elements;
    var b = zero_beyond();
    for (var k = 0u; k < n; k++) {
        let i = strand * n + (n - 1u - k);
        beyond[i] = b;
        shift_beyond(&b, -jacobians[i].span.xyz);
        add_beyond(&b, own[i]);
    }
}

@compute @workgroup_size(64)
fn stage_solve(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = flat_index(id, groups);
    if i >= params.strand_count * params.elements {
        return;
    }
    let e = i % params.elements;
    let terms = element_terms(jacobians[i], own[i], beyond[i]);
    let qi = q[i].xyz;
    let vi = v[i].xyz;
    let st = step_terms(e, terms.force, qi, vi);
    let m = add_diagonal(terms.mass_block * params.mass_scale, st[0]);
    let v_next = vi + inverse3(m) * st[1];
    v[i] = vec4<f32>(v_next, 0.0);
    q[i] = vec4<f32>(qi + v_next * params.h_secs, 0.0);
}
