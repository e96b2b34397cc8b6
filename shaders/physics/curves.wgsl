// Centrelines for a renderer, on the device that steps the strands
// (physics::gpu::curves; CPU twin gpu::curves::stage_curves): appended to
// common.wgsl and engine.wgsl, whose `q` it reads.
//
// Each curve is a strand grown from its own root frame whose element e
// bends by the blend k_e = base_e + sum of weight * q[element] over its
// sources: a simulated strand drawn as it is (one source of weight 1, its
// own element) or a drawn strand between guides. Element e is cut into
// `samples` equal pieces; every piece of one element is the same piece of
// helix turned by the frames before it, so the sweep carries the frame
// across each piece with `advance` (R <- R exp([sigma k]x),
// p <- p + R h(sigma, k)) and writes the point at every piece's start,
// then the tip. Head coordinates, metres, w = 1; curve c's points are
// curve_strands[c].first_point .. + elements * samples + 1, and
// curve_strains[c] is the mean of |k_e| over its elements, 1/m.

struct CurveStrand {
    first_point: u32,
    samples: u32,
    first_element: u32,
    elements: u32,
    root_m: vec4<f32>,
    head_from_root: mat3x3<f32>,
}

struct CurveElement {
    // xyz: the strain added to the blend, 1/m; w: the element's length, m.
    base_length: vec4<f32>,
    first_source: u32,
    source_count: u32,
    _pad0: u32,
    _pad1: u32,
}

struct CurveSource {
    element: u32,
    weight: f32,
}

@group(1) @binding(0) var<storage, read> curve_strands: array<CurveStrand>;
@group(1) @binding(1) var<storage, read> curve_elements: array<CurveElement>;
@group(1) @binding(2) var<storage, read> curve_sources: array<CurveSource>;
@group(1) @binding(3) var<storage, read_write> curve_points: array<vec4<f32>>;
@group(1) @binding(4) var<storage, read_write> curve_strains: array<f32>;

@compute @workgroup_size(64)
fn stage_curves(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let curve = flat_index(id, groups);
    if curve >= arrayLength(&curve_strains) {
        return;
    }
    let cs = curve_strands[curve];
    var s: FrameState;
    s.frame = cs.head_from_root;
    s.w = vec3<f32>(0.0);
    s.alpha = vec3<f32>(0.0);
    s.p = vec3<f32>(0.0);
    s.pv = vec3<f32>(0.0);
    s.pa = vec3<f32>(0.0);
    let pieces = max(cs.samples, 1u);
    var out = cs.first_point;
    var strain_sum = 0.0;
    for (var e = 0u; e < cs.elements; e++) {
        let element = curve_elements[cs.first_element + e];
        var k = element.base_length.xyz;
        for (var i = 0u; i < element.source_count; i++) {
            let source = curve_sources[element.first_source + i];
            k += source.weight * q[source.element].xyz;
        }
        strain_sum += length(k);
        let piece_m = element.base_length.w / f32(pieces);
        for (var j = 0u; j < pieces; j++) {
            curve_points[out] = vec4<f32>(cs.root_m.xyz + s.p, 1.0);
            out++;
            s = advance(s, piece_m, k, vec3<f32>(0.0)).next;
        }
    }
    curve_points[out] = vec4<f32>(cs.root_m.xyz + s.p, 1.0);
    curve_strains[curve] = strain_sum / f32(max(cs.elements, 1u));
}
