// Exact step on the GPU (append to common.wgsl): one invocation per strand
// runs the three sweeps of crates/physics/src/batch/step/exact.rs (root to tip:
// element data; tip to root: suffix sums and the 6×6 articulated-inertia
// elimination; root to tip: back-substitution and integration). Per-element
// intermediates live in storage buffers: a strand has up to 200 elements,
// too many for private memory.

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> elements_const: array<ElementConst>;
@group(0) @binding(2) var<storage, read> roots: array<RootPose>;
@group(0) @binding(3) var<storage, read_write> q: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> v: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read_write> jacobians: array<Jacobians>;
@group(0) @binding(6) var<storage, read_write> own: array<Own>;
@group(0) @binding(7) var<storage, read_write> off_diagonal: array<OffDiagonal>;
@group(0) @binding(8) var<storage, read_write> elimination: array<Elimination>;

struct OffDiagonal {
    u: mat3x3<f32>,
    v: mat3x3<f32>,
}

struct Elimination {
    w_top: mat3x3<f32>,
    w_bottom: mat3x3<f32>,
    s_inv: mat3x3<f32>,
    rhs: vec4<f32>,
}

fn mul_mat_t(a: mat3x3<f32>, b: mat3x3<f32>) -> mat3x3<f32> {
    return a * transpose(b);
}

@compute @workgroup_size(64)
fn stage_exact(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let strand = flat_index(id, groups);
    if strand >= params.strand_count {
        return;
    }
    let n = params.elements;
    let base = strand * n;
    var s = root_state(strand);
    for (var e = 0u; e < n; e++) {
        let i = base + e;
        var start = s;
        start.p = vec3<f32>(0.0);
        let sums = own_sums(e, start, q[i].xyz, v[i].xyz, true);
        own[i] = sums.own;
        off_diagonal[i] = OffDiagonal(sums.u, sums.v);
        let adv = advance(s, elements_const[e].stiffness_length.w, q[i].xyz, v[i].xyz);
        jacobians[i] = Jacobians(adv.a_local, adv.b, vec4<f32>(adv.span, 0.0));
        s = adv.next;
    }
    let zero3 = mat3x3<f32>(vec3<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0));
    var b = zero_beyond();
    var h_aa = zero3;
    var h_ab = zero3;
    var h_ba = zero3;
    var h_bb = zero3;
    var carried_a = vec3<f32>(0.0);
    var carried_b = vec3<f32>(0.0);
    let sc = params.mass_scale;
    for (var k = 0u; k < n; k++) {
        let e = n - 1u - k;
        let i = base + e;
        let jac = jacobians[i];
        let el = own[i];
        let uv = off_diagonal[i];
        let terms = element_terms(jac, el, b);
        let st = step_terms(e, terms.force, q[i].xyz, v[i].xyz);
        let hu_top = h_aa * jac.a + h_ab * jac.b;
        let hu_bottom = h_ba * jac.a + h_bb * jac.b;
        let w_top = (uv.u + terms.x_beyond) * sc - hu_top;
        let span = jac.span.xyz;
        let own_v = uv.v - cross_cols(span, uv.u);
        let w_bottom = (own_v + terms.y_beyond) * sc - hu_bottom;
        let s_tilde = add_diagonal(terms.mass_block * sc, st[0])
            - (transpose(jac.a) * hu_top + transpose(jac.b) * hu_bottom);
        let s_inv = inverse3(s_tilde);
        let p_top = w_top * s_inv;
        let p_bottom = w_bottom * s_inv;
        h_aa += mul_mat_t(p_top, w_top);
        h_ab += mul_mat_t(p_top, w_bottom);
        h_ba += mul_mat_t(p_bottom, w_top);
        h_bb += mul_mat_t(p_bottom, w_bottom);
        let r = st[1] - (transpose(jac.a) * carried_a + transpose(jac.b) * carried_b);
        let y = s_inv * r;
        carried_a += w_top * y;
        carried_b += w_bottom * y;
        elimination[i] = Elimination(w_top, w_bottom, s_inv, vec4<f32>(r, 0.0));
        // Move H, the carried wrench and the sums to the element's start.
        let delta = -span;
        let sk = skew(delta);
        let h_aa_s = h_aa * sk;
        let h_ab_old = h_ab;
        h_ab = h_aa_s + h_ab;
        h_bb = h_bb + h_ba * sk - sk * h_ab_old - sk * h_aa_s;
        h_ba = h_ba - sk * h_aa;
        carried_b = carried_b - cross(delta, carried_a);
        shift_beyond(&b, delta);
        add_beyond(&b, el);
    }
    var moved_a = vec3<f32>(0.0);
    var moved_b = vec3<f32>(0.0);
    for (var e = 0u; e < n; e++) {
        let i = base + e;
        let x = elimination[i];
        let jac = jacobians[i];
        moved_a = moved_a - cross(jac.span.xyz, moved_b);
        let dv = x.s_inv * (x.rhs.xyz - (transpose(x.w_top) * moved_a + transpose(x.w_bottom) * moved_b));
        moved_a += jac.a * dv;
        moved_b += jac.b * dv;
        let v_next = v[i].xyz + dv;
        v[i] = vec4<f32>(v_next, 0.0);
        q[i] = vec4<f32>(q[i].xyz + v_next * params.h_secs, 0.0);
    }
}
