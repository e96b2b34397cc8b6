// The Dense kernel's frame chain (appended to common.wgsl, before
// dense.wgsl). One stage:
//   stage_frames   one invocation per strand: the root-to-tip frame chain
//                  (R, ω, α, p, ṗ, p̈ at each element start) and the
//                  element's Jacobians A_Q, B_Q, A_Q about the root (Dense
//                  pairs every element with every other one when it
//                  assembles the off-diagonal blocks, and so needs one
//                  common point) and a zero span.
// Its CPU twin is `stage_frames` in crates/physics/src/gpu/dense_twin.rs
// (twin.rs `frame_chain`).

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> elements_const: array<ElementConst>;
@group(0) @binding(2) var<storage, read> roots: array<RootPose>;
@group(0) @binding(3) var<storage, read_write> q: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> v: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read_write> frames: array<Frame>;
@group(0) @binding(6) var<storage, read_write> jacobians: array<Jacobians>;

@compute @workgroup_size(64)
fn stage_frames(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let strand = flat_index(id, groups);
    if strand >= params.strand_count {
        return;
    }
    let n = params.elements;
    var s = root_state(strand);
    for (var e = 0u; e < n; e++) {
        let i = strand * n + e;
        frames[i] = frame_record(s);
        let adv = advance(s, elements_const[e].stiffness_length.w, q[i].xyz, v[i].xyz);
        jacobians[i] = Jacobians(adv.a, adv.b, vec4<f32>(0.0));
        s = adv.next;
    }
}
