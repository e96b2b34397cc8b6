// The strands' centrelines for a renderer, on the device that steps them
// (physics::gpu::curves; CPU twin gpu::curves::stage_curves): appended to
// common.wgsl and engine.wgsl, whose `params`, `strands`, `elements_const`
// and `q` it reads.
//
// Each strand's element e is cut into `samples` equal pieces; every piece
// of one element is the same piece of helix turned by the frames before
// it, so the sweep carries the frame across each piece with `advance`
// (R ← R exp([σ k]×), p ← p + R h(σ, k)) and writes the point at every
// piece's start, then the tip. Head coordinates (the root at rest in the
// head), metres, w = 1; strand s's points are
// curve_strands[s].first_point .. + elements · samples + 1.

struct CurveStrand {
    first_point: u32,
    samples: u32,
    _pad0: u32,
    _pad1: u32,
}

@group(1) @binding(0) var<storage, read> curve_strands: array<CurveStrand>;
@group(1) @binding(1) var<storage, read_write> curve_points: array<vec4<f32>>;

@compute @workgroup_size(64)
fn stage_curves(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let strand = flat_index(id, groups);
    if strand >= params.strand_count {
        return;
    }
    let st = strands[strand];
    let cs = curve_strands[strand];
    let root_m = st.position_m.xyz;
    var s: FrameState;
    s.frame = st.head_from_root;
    s.w = vec3<f32>(0.0);
    s.alpha = vec3<f32>(0.0);
    s.p = vec3<f32>(0.0);
    s.pv = vec3<f32>(0.0);
    s.pa = vec3<f32>(0.0);
    let pieces = max(cs.samples, 1u);
    var out = cs.first_point;
    for (var e = 0u; e < st.elements; e++) {
        let length_m = elements_const[st.first + e].stiffness_length.w;
        let k = q[st.first + e].xyz;
        let piece_m = length_m / f32(pieces);
        for (var j = 0u; j < pieces; j++) {
            curve_points[out] = vec4<f32>(root_m + s.p, 1.0);
            out++;
            s = advance(s, piece_m, k, vec3<f32>(0.0)).next;
        }
    }
    curve_points[out] = vec4<f32>(root_m + s.p, 1.0);
}
