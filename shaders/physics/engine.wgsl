// The GPU engine's step (appended to common.wgsl): the CPU engines' one
// Exact step, one strand per invocation, every strand with its own
// constants and element count. Stages and functions keep the names of
// their Rust originals, whose f32 instance at width one is the CPU twin
// (crates/physics/src/gpu/engine_twin.rs):
//   forward_with, own_sums_into   batch/forward.rs (sweep 1, root to tip,
//                                 with the head's implicit contact at each
//                                 quadrature sample: batch/contact,
//                                 collision/contact.rs implicit_force)
//   eliminate, back_substitute,   batch/step/exact.rs (sweeps 2 and 3, and
//   solve_again                   P⁻¹ b with the stored elimination)
//   velocity_product              batch/velocity_terms.rs (G z by
//                                 polarisation)
//   gmres_correct                 gmres.rs correct (right-preconditioned
//                                 GMRES on (P + hG) Δv = rhs)
//   integrate                     batch/suffix.rs
// Per-element data lives in storage buffers (a strand has up to 200
// elements, too many for private memory): the sweep's element data, the
// elimination, and GMRES's vectors in `krylov`, KRYLOV_SLOTS vectors of
// the strand's N elements each, starting at the strand's first element
// times KRYLOV_SLOTS.

struct Params {
    strand_count: u32,
    points: u32,
    iterations: u32,
    has_collider: u32,
    h_secs: f32,
    gmres_tolerance: f32,
    skin_m: f32,
    implicit_stiffness_ratio: f32,
    max_acceleration_m_per_s2: f32,
    field_cell_m: f32,
    _pad0: f32,
    _pad1: f32,
    field_dims: vec4<u32>,
    field_origin_m: vec4<f32>,
    gravity_m_per_s2: vec4<f32>,
    air_velocity_m_per_s: vec4<f32>,
    nodes: array<vec4<f32>, 2>,
    weights: array<vec4<f32>, 2>,
    head_rotation: mat3x3<f32>,
    head_position_m: vec4<f32>,
    head_angular_velocity: vec4<f32>,
    head_angular_acceleration: vec4<f32>,
    head_velocity: vec4<f32>,
    head_acceleration: vec4<f32>,
}

// One strand: its elements first..first + elements in every per-element
// buffer, its own ρS and ν, and its root on the head.
struct Strand {
    first: u32,
    elements: u32,
    _pad0: u32,
    _pad1: u32,
    mass_per_length: f32,
    air_drag: f32,
    _pad2: f32,
    _pad3: f32,
    position_m: vec4<f32>,
    head_from_root: mat3x3<f32>,
}

// batch::layout::ElementData: what sweep 1 leaves for each element.
struct ElementData {
    a: mat3x3<f32>,
    b: mat3x3<f32>,
    own_mass_block: mat3x3<f32>,
    inertia: mat3x3<f32>,
    u: mat3x3<f32>,
    v: mat3x3<f32>,
    // ContactInertia: Σ a aᵀ, Σ a (d × a)ᵀ, Σ (d × a) aᵀ, Σ (d × a)(d × a)ᵀ.
    contact: array<mat3x3<f32>, 4>,
    own_force: vec4<f32>,
    // first moment in xyz, mass in w
    moment: vec4<f32>,
    force_sum: vec4<f32>,
    torque_sum: vec4<f32>,
    // end point minus start point in xyz; w is 1 where a sample touched
    span: vec4<f32>,
}

struct Elimination {
    w_top: mat3x3<f32>,
    w_bottom: mat3x3<f32>,
    s_inv: mat3x3<f32>,
    rhs: vec4<f32>,
}

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> strands: array<Strand>;
@group(0) @binding(2) var<storage, read> elements_const: array<ElementConst>;
@group(0) @binding(3) var<storage, read_write> q: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> v: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read_write> scratch: array<ElementData>;
@group(0) @binding(6) var<storage, read_write> elimination: array<Elimination>;
@group(0) @binding(7) var<storage, read_write> krylov: array<vec4<f32>>;
@group(0) @binding(8) var<storage, read> field: array<f32>;

// gmres.rs MAX_GMRES.
const MAX_GMRES: u32 = 8u;
// GMRES's vectors per element: the basis v₀…v₈, the directions z₀…z₇, Δv,
// the product G x, and the three partial sums of velocity_product.
const BASIS: u32 = 0u;
const DIRECTIONS: u32 = 9u;
const DELTA_V: u32 = 17u;
const PRODUCT: u32 = 18u;
const OWN_PRODUCT: u32 = 19u;
const OWN_FORCE: u32 = 20u;
const OWN_TORQUE: u32 = 21u;
const KRYLOV_SLOTS: u32 = 22u;

fn slot(st: Strand, which: u32, e: u32) -> u32 {
    return st.first * KRYLOV_SLOTS + which * st.elements + e;
}

fn zero3() -> mat3x3<f32> {
    return mat3x3<f32>(vec3<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0));
}

// M3::symmetric from the upper triangle (00, 01, 02, 11, 12, 22).
fn symmetric(u: array<f32, 6>) -> mat3x3<f32> {
    return mat3x3<f32>(vec3<f32>(u[0], u[1], u[2]), vec3<f32>(u[1], u[3], u[4]),
        vec3<f32>(u[2], u[4], u[5]));
}

fn root_state(st: Strand) -> FrameState {
    return carried_root(st.position_m.xyz, st.head_from_root);
}

fn lerp(a: f32, b: f32, t: f32) -> f32 {
    return a + (b - a) * t;
}

// SignedDistanceField::sample: trilinear distance and its unit gradient at
// `local` (head coordinates); the w component is 0 outside the grid.
fn sample_field(local: vec3<f32>) -> vec4<f32> {
    let dims = params.field_dims.xyz;
    let g = (local - params.field_origin_m.xyz) / params.field_cell_m;
    let top = vec3<f32>(dims - vec3<u32>(1u));
    if min(g.x, min(g.y, g.z)) < 0.0 || g.x > top.x || g.y > top.y || g.z > top.z {
        return vec4<f32>(0.0);
    }
    let i = min(vec3<u32>(g), dims - vec3<u32>(2u));
    let t = g - vec3<f32>(i);
    let row = dims.x;
    let plane = dims.x * dims.y;
    let first = i.x + row * (i.y + dims.y * i.z);
    let c000 = field[first];
    let c100 = field[first + 1u];
    let c010 = field[first + row];
    let c110 = field[first + 1u + row];
    let c001 = field[first + plane];
    let c101 = field[first + 1u + plane];
    let c011 = field[first + row + plane];
    let c111 = field[first + 1u + row + plane];
    let c00 = lerp(c000, c100, t.x);
    let c10 = lerp(c010, c110, t.x);
    let c01 = lerp(c001, c101, t.x);
    let c11 = lerp(c011, c111, t.x);
    let c0 = lerp(c00, c10, t.y);
    let c1 = lerp(c01, c11, t.y);
    let value = lerp(c0, c1, t.z);
    let gx = lerp(lerp(c100 - c000, c110 - c010, t.y), lerp(c101 - c001, c111 - c011, t.y), t.z);
    let gy = lerp(lerp(c010 - c000, c110 - c100, t.x), lerp(c011 - c001, c111 - c101, t.x), t.z);
    let gz = c1 - c0;
    let gradient = vec3<f32>(gx, gy, gz) / params.field_cell_m;
    let length_squared = dot(gradient, gradient);
    if !(length_squared > 0.0) {
        return vec4<f32>(0.0, 0.0, 0.0, value);
    }
    return vec4<f32>(gradient * inverseSqrt(length_squared), value);
}

// ContactInputs::implicit_force as LaneContact hands it to the sweep: the
// predicted push per unit length (xyz, N/m) and the gain axis
// n √(h (h k + c)) (returned as the second column); both zero out of
// contact. `p_m` world, `velocity` world.
fn implicit_force(p_m: vec3<f32>, velocity: vec3<f32>, rho_s: f32) -> mat2x3<f32> {
    let none = mat2x3<f32>(vec3<f32>(0.0), vec3<f32>(0.0));
    let offset = p_m - params.head_position_m.xyz;
    let local = transpose(params.head_rotation) * offset;
    let sampled = sample_field(local);
    let gradient = sampled.xyz;
    if all(gradient == vec3<f32>(0.0)) {
        return none;
    }
    let d = sampled.w;
    let n = params.head_rotation * gradient;
    let w = params.head_angular_velocity.xyz;
    let surface_velocity = params.head_velocity.xyz + cross(w, offset);
    let approach = dot(velocity - surface_velocity, n);
    let h = params.h_secs;
    let skin = params.skin_m;
    if d + h * min(approach, 0.0) >= skin {
        return none;
    }
    let alpha = params.implicit_stiffness_ratio;
    let k = alpha * rho_s / (h * h);
    let c = 2.0 * sqrt(alpha) * rho_s / h;
    let spring = k * (skin - d - h * approach) - c * approach;
    let cap = rho_s * params.max_acceleration_m_per_s2;
    var push = spring;
    var gain = h * k + c;
    if spring > cap {
        push = cap;
        gain = 0.0;
    }
    if !(push > 0.0) {
        return none;
    }
    return mat2x3<f32>(n * push, n * sqrt(h * gain));
}

// batch::forward::own_sums_into with U_Q, V_Q and the contact hook, for
// global element i from its start state `s` (point at the element's
// start); `hook_origin` is that start relative to the root, `root_m` the
// root's world position.
fn own_sums_into(st: Strand, i: u32, s: FrameState, k: vec3<f32>, k_dot: vec3<f32>,
        hook_origin: vec3<f32>, root_m: vec3<f32>) {
    let length_m = elements_const[i].stiffness_length.w;
    let rho_s = st.mass_per_length;
    let nu = st.air_drag;
    let g = params.gravity_m_per_s2.xyz;
    let air = params.air_velocity_m_per_s.xyz;
    var force_sum = vec3<f32>(0.0);
    var torque_sum = vec3<f32>(0.0);
    var first_moment = vec3<f32>(0.0);
    var mass = 0.0;
    var second = array<f32, 6>(0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    var gram = array<f32, 6>(0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    var local_force = vec3<f32>(0.0);
    var u_local = zero3();
    var v_local = zero3();
    var contact = array<mat3x3<f32>, 4>(zero3(), zero3(), zero3(), zero3());
    var touching = 0.0;
    let inverse_sqrt_scale = 1.0 / sqrt(1.0 + params.h_secs * (nu / rho_s));
    for (var j = 0u; j < params.points; j++) {
        let sigma = node(j) * length_m;
        let lp = local_point(sigma, k, k_dot);
        let rva = carry(s, lp.h, lp.h_dot, lp.h_ddot);
        let r = rva[0];
        let vel = rva[1];
        let w_len = weight(j) * length_m;
        let w_mass = w_len * rho_s;
        var per_length = (g - rva[2]) * rho_s + (air - vel) * nu;
        let jac = lp.jacobian;
        if params.has_collider != 0u {
            let touch = implicit_force(root_m + hook_origin + r, vel, rho_s);
            if any(touch[0] != vec3<f32>(0.0)) {
                per_length += touch[0];
                let a = touch[1] * sqrt(w_len);
                let turn = cross(r, a);
                contact[0] += outer(a, a);
                contact[1] += outer(a, turn);
                contact[2] += outer(turn, a);
                contact[3] += outer(turn, turn);
                touching = 1.0;
                let a_local = (transpose(s.frame) * a) * inverse_sqrt_scale;
                let psi = transpose(jac) * a_local;
                gram[0] = fma(psi.x, psi.x, gram[0]);
                gram[1] = fma(psi.x, psi.y, gram[1]);
                gram[2] = fma(psi.x, psi.z, gram[2]);
                gram[3] = fma(psi.y, psi.y, gram[3]);
                gram[4] = fma(psi.y, psi.z, gram[4]);
                gram[5] = fma(psi.z, psi.z, gram[5]);
                u_local += outer(a_local, psi);
                v_local += outer(cross(lp.h, a_local), psi);
            }
        }
        let force = per_length * w_len;
        local_force += transpose(jac) * (transpose(s.frame) * force);
        gram[0] = fma(w_mass, dot(jac[0], jac[0]), gram[0]);
        gram[1] = fma(w_mass, dot(jac[0], jac[1]), gram[1]);
        gram[2] = fma(w_mass, dot(jac[0], jac[2]), gram[2]);
        gram[3] = fma(w_mass, dot(jac[1], jac[1]), gram[3]);
        gram[4] = fma(w_mass, dot(jac[1], jac[2]), gram[4]);
        gram[5] = fma(w_mass, dot(jac[2], jac[2]), gram[5]);
        force_sum += force;
        torque_sum += cross(r, force);
        mass += w_mass;
        let r_w = r * w_mass;
        first_moment += r_w;
        second[0] = fma(r_w.x, r.x, second[0]);
        second[1] = fma(r_w.x, r.y, second[1]);
        second[2] = fma(r_w.x, r.z, second[2]);
        second[3] = fma(r_w.y, r.y, second[3]);
        second[4] = fma(r_w.y, r.z, second[4]);
        second[5] = fma(r_w.z, r.z, second[5]);
        let jac_w = jac * w_mass;
        u_local += jac_w;
        v_local += cross_cols(lp.h, jac_w);
    }
    let trace = second[0] + second[3] + second[5];
    let minus_second = array<f32, 6>(-second[0], -second[1], -second[2], -second[3],
        -second[4], -second[5]);
    scratch[i].inertia = add_diagonal(symmetric(minus_second), vec3<f32>(trace));
    scratch[i].own_force = vec4<f32>(local_force, 0.0);
    scratch[i].own_mass_block = symmetric(gram);
    scratch[i].moment = vec4<f32>(first_moment, mass);
    scratch[i].force_sum = vec4<f32>(force_sum, 0.0);
    scratch[i].torque_sum = vec4<f32>(torque_sum, 0.0);
    scratch[i].contact = contact;
    let u = s.frame * u_local;
    scratch[i].u = u;
    scratch[i].v = cross_cols(s.p, u) + s.frame * v_local;
    scratch[i].span.w = touching;
}

// batch::forward::forward_with with local moments: sweep 1, root to tip.
fn forward_with(st: Strand, root: FrameState) {
    let root_m = params.head_position_m.xyz + params.head_rotation * st.position_m.xyz;
    var s = root;
    for (var e = 0u; e < st.elements; e++) {
        let i = st.first + e;
        var origin = s;
        origin.p = vec3<f32>(0.0);
        let k = q[i].xyz;
        let k_dot = v[i].xyz;
        own_sums_into(st, i, origin, k, k_dot, s.p, root_m);
        let adv = advance(s, elements_const[i].stiffness_length.w, k, k_dot);
        scratch[i].a = adv.a_local;
        scratch[i].b = adv.b;
        scratch[i].span = vec4<f32>(adv.span, scratch[i].span.w);
        s = adv.next;
    }
}

// batch::suffix::step_terms of global element i: (D, rhs).
fn step_terms_of(i: u32, force: vec3<f32>, qi: vec3<f32>, vi: vec3<f32>) -> mat2x3<f32> {
    let h = params.h_secs;
    let kv = elements_const[i].stiffness_length.xyz;
    let natural = elements_const[i].natural_friction.xyz;
    let friction = elements_const[i].natural_friction.w;
    let diagonal = vec3<f32>(h * friction) + (h * h) * kv;
    let damping = vec3<f32>(friction) + h * kv;
    let rhs = (force - kv * (qi - natural) - damping * vi) * h;
    return mat2x3<f32>(diagonal, rhs);
}

fn mul_mat_t(a: mat3x3<f32>, b: mat3x3<f32>) -> mat3x3<f32> {
    return a * transpose(b);
}

// batch::step::exact::eliminate (sweeps 1 and 2) with local moments:
// returns Σ|rhs|².
fn eliminate(st: Strand, root: FrameState) -> f32 {
    forward_with(st, root);
    let sc = 1.0 + params.h_secs * st.air_drag / st.mass_per_length;
    var b = zero_beyond();
    var h_aa = zero3();
    var h_ab = zero3();
    var h_ba = zero3();
    var h_bb = zero3();
    var carried_a = vec3<f32>(0.0);
    var carried_b = vec3<f32>(0.0);
    var rhs_squared = 0.0;
    for (var k = 0u; k < st.elements; k++) {
        let i = st.first + st.elements - 1u - k;
        let el = scratch[i];
        let span = el.span.xyz;
        let jac = Jacobians(el.a, el.b, vec4<f32>(span, 0.0));
        let own_sums = Own(el.own_mass_block, el.inertia, el.own_force, el.moment, el.force_sum,
            el.torque_sum);
        let terms = element_terms(jac, own_sums, b);
        let st_terms = step_terms_of(i, terms.force, q[i].xyz, v[i].xyz);
        rhs_squared += dot(st_terms[1], st_terms[1]);
        let own_v = el.v - cross_cols(span, el.u);
        let hu_top = h_aa * el.a + h_ab * el.b;
        let hu_bottom = h_ba * el.a + h_bb * el.b;
        let w_top = (el.u + terms.x_beyond) * sc - hu_top;
        let w_bottom = (own_v + terms.y_beyond) * sc - hu_bottom;
        let s_tilde = add_diagonal(terms.mass_block * sc
            - (transpose(el.b) * hu_bottom + transpose(el.a) * hu_top), st_terms[0]);
        let s_inv = inverse3(s_tilde);
        let p_top = w_top * s_inv;
        let p_bottom = w_bottom * s_inv;
        h_aa += mul_mat_t(p_top, w_top);
        h_ab += mul_mat_t(p_top, w_bottom);
        h_ba += mul_mat_t(p_bottom, w_top);
        h_bb += mul_mat_t(p_bottom, w_bottom);
        let r = st_terms[1] - (transpose(el.b) * carried_b + transpose(el.a) * carried_a);
        let y = s_inv * r;
        carried_a += w_top * y;
        carried_b += w_bottom * y;
        elimination[i] = Elimination(w_top, w_bottom, s_inv, vec4<f32>(r, 0.0));
        // Move H, the carried wrench and the sums to the element's start
        // (shift_articulated, Beyond::shift).
        let delta = -span;
        let sk = skew(delta);
        let h_aa_s = h_aa * sk;
        let h_ab_old = h_ab;
        h_ab = h_aa_s + h_ab;
        h_bb = h_bb + h_ba * sk - sk * h_ab_old - sk * h_aa_s;
        h_ba = h_ba - sk * h_aa;
        carried_b = carried_b - cross(delta, carried_a);
        shift_beyond(&b, delta);
        if el.span.w != 0.0 {
            h_aa -= el.contact[0];
            h_ab -= el.contact[1];
            h_ba -= el.contact[2];
            h_bb -= el.contact[3];
        }
        add_beyond(&b, own_sums);
    }
    return rhs_squared;
}

// batch::step::exact::back_substitute, Δv into krylov slot `out`.
fn back_substitute(st: Strand, out: u32) {
    var moved_a = vec3<f32>(0.0);
    var moved_b = vec3<f32>(0.0);
    for (var e = 0u; e < st.elements; e++) {
        let i = st.first + e;
        let x = elimination[i];
        let el_a = scratch[i].a;
        let el_b = scratch[i].b;
        moved_a = moved_a - cross(scratch[i].span.xyz, moved_b);
        let dv = x.s_inv * (x.rhs.xyz - (transpose(x.w_bottom) * moved_b
            + transpose(x.w_top) * moved_a));
        moved_a += el_a * dv;
        moved_b += el_b * dv;
        krylov[slot(st, out, e)] = vec4<f32>(dv, 0.0);
    }
}

// batch::step::exact::solve_again: krylov slot `x` = P⁻¹ (slot `b`).
fn solve_again(st: Strand, b: u32, x: u32) {
    var carried_a = vec3<f32>(0.0);
    var carried_b = vec3<f32>(0.0);
    for (var k = 0u; k < st.elements; k++) {
        let e = st.elements - 1u - k;
        let i = st.first + e;
        let el_a = scratch[i].a;
        let el_b = scratch[i].b;
        let stored = elimination[i];
        let r = krylov[slot(st, b, e)].xyz - (transpose(el_b) * carried_b
            + transpose(el_a) * carried_a);
        let y = stored.s_inv * r;
        carried_a += stored.w_top * y;
        carried_b += stored.w_bottom * y;
        elimination[i].rhs = vec4<f32>(r, 0.0);
        carried_b += cross(scratch[i].span.xyz, carried_a);
    }
    back_substitute(st, x);
}

fn largest_abs3(x: vec3<f32>) -> f32 {
    let a = abs(x);
    return max(a.x, max(a.y, a.z));
}

// batch::velocity_terms::velocity_product: krylov slot `out` = G (slot `z`).
fn velocity_product(st: Strand, root: FrameState, z: u32, out: u32) {
    // polarisation_shift: c = max(|q̇|∞, 1)/|z|∞.
    var v_size = 0.0;
    var z_size = 0.0;
    for (var e = 0u; e < st.elements; e++) {
        v_size = max(v_size, largest_abs3(v[st.first + e].xyz));
        z_size = max(z_size, largest_abs3(krylov[slot(st, z, e)].xyz));
    }
    if z_size < 1.17549435e-38 {
        z_size = 1.0;
    }
    let reach = max(v_size, 1.0) / z_size;
    let factor = st.mass_per_length / (reach + reach);
    var plus = root;
    plus.alpha = vec3<f32>(0.0);
    plus.pv = vec3<f32>(0.0);
    plus.pa = vec3<f32>(0.0);
    var minus = plus;
    for (var e = 0u; e < st.elements; e++) {
        let i = st.first + e;
        let k = q[i].xyz;
        let shift = krylov[slot(st, z, e)].xyz * reach;
        let k_plus = v[i].xyz + shift;
        let k_minus = v[i].xyz - shift;
        let length_m = elements_const[i].stiffness_length.w;
        var origin_plus = plus;
        origin_plus.p = vec3<f32>(0.0);
        var origin_minus = minus;
        origin_minus.p = vec3<f32>(0.0);
        var force = vec3<f32>(0.0);
        var torque = vec3<f32>(0.0);
        var local = vec3<f32>(0.0);
        for (var j = 0u; j < params.points; j++) {
            let sigma = node(j) * length_m;
            let lp = local_point(sigma, k, k_plus);
            let lm = local_point(sigma, k, k_minus);
            let rp = carry(origin_plus, lp.h, lp.h_dot, lp.h_ddot);
            let rm = carry(origin_minus, lm.h, lm.h_dot, lm.h_ddot);
            let f = (rp[2] - rm[2]) * (factor * (weight(j) * length_m));
            local = transpose(lp.jacobian) * (transpose(plus.frame) * f) + local;
            force += f;
            torque += cross(rp[0], f);
        }
        krylov[slot(st, OWN_PRODUCT, e)] = vec4<f32>(local, 0.0);
        krylov[slot(st, OWN_FORCE, e)] = vec4<f32>(force, 0.0);
        krylov[slot(st, OWN_TORQUE, e)] = vec4<f32>(torque, 0.0);
        plus = advance(plus, length_m, k, k_plus).next;
        let next_minus = advance(minus, length_m, k, k_minus).next;
        minus = next_minus;
        minus.frame = plus.frame;
        minus.p = plus.p;
    }
    var force = vec3<f32>(0.0);
    var torque = vec3<f32>(0.0);
    for (var k = 0u; k < st.elements; k++) {
        let e = st.elements - 1u - k;
        let i = st.first + e;
        let el_a = scratch[i].a;
        let el_b = scratch[i].b;
        let own_product = krylov[slot(st, OWN_PRODUCT, e)].xyz;
        krylov[slot(st, out, e)] = vec4<f32>(transpose(el_b) * torque
            + (transpose(el_a) * force + own_product), 0.0);
        torque = torque + cross(scratch[i].span.xyz, force)
            + krylov[slot(st, OWN_TORQUE, e)].xyz;
        force += krylov[slot(st, OWN_FORCE, e)].xyz;
    }
}

fn dot_slots(st: Strand, a: u32, b: u32) -> f32 {
    var s = 0.0;
    for (var e = 0u; e < st.elements; e++) {
        s += dot(krylov[slot(st, a, e)].xyz, krylov[slot(st, b, e)].xyz);
    }
    return s;
}

// gmres::correct for one strand: corrects Δv (slot DELTA_V, P⁻¹ rhs on
// entry) towards (P + hG) Δv = rhs with at most params.iterations
// iterations; returns the iterations run.
fn gmres_correct(st: Strand, root: FrameState, rhs_norm: f32) -> u32 {
    // Written without early returns or breaks: a strand that has converged
    // runs the rest of the loop inert (what the lanes of gmres.rs do).
    let k_max = min(params.iterations, MAX_GMRES);
    let h = params.h_secs;
    let tol = rhs_norm * params.gmres_tolerance;
    var beta = 0.0;
    if k_max > 0u {
        velocity_product(st, root, DELTA_V, PRODUCT);
        beta = h * sqrt(dot_slots(st, PRODUCT, PRODUCT));
    }
    var running = k_max > 0u && beta > tol;
    if running {
        let scale = -h / beta;
        for (var e = 0u; e < st.elements; e++) {
            krylov[slot(st, BASIS, e)] = krylov[slot(st, PRODUCT, e)] * scale;
        }
    }
    var hessenberg: array<array<f32, 8>, 9>;
    var cosines: array<f32, 8>;
    var sines: array<f32, 8>;
    var g: array<f32, 9>;
    g[0] = beta;
    var used = 0u;
    for (var j = 0u; j < k_max; j++) {
        if !running {
            continue;
        }
        solve_again(st, BASIS + j, DIRECTIONS + j);
        velocity_product(st, root, DIRECTIONS + j, PRODUCT);
        let w = BASIS + j + 1u;
        for (var e = 0u; e < st.elements; e++) {
            krylov[slot(st, w, e)] = krylov[slot(st, BASIS + j, e)]
                + krylov[slot(st, PRODUCT, e)] * h;
        }
        for (var i = 0u; i <= j; i++) {
            let hij = dot_slots(st, w, BASIS + i);
            hessenberg[i][j] = hij;
            for (var e = 0u; e < st.elements; e++) {
                krylov[slot(st, w, e)] = krylov[slot(st, w, e)] - krylov[slot(st, BASIS + i, e)] * hij;
            }
        }
        let w_norm = sqrt(dot_slots(st, w, w));
        hessenberg[j + 1u][j] = w_norm;
        for (var i = 0u; i < j; i++) {
            let a = hessenberg[i][j];
            let b = hessenberg[i + 1u][j];
            hessenberg[i][j] = cosines[i] * a + sines[i] * b;
            hessenberg[i + 1u][j] = cosines[i] * b - sines[i] * a;
        }
        let a = hessenberg[j][j];
        let b = hessenberg[j + 1u][j];
        let r = sqrt(a * a + b * b);
        var c = 1.0;
        var s = 0.0;
        if r > 0.0 {
            c = a / r;
            s = b / r;
            hessenberg[j][j] = r;
        } else {
            hessenberg[j][j] = 1.0;
        }
        cosines[j] = c;
        sines[j] = s;
        hessenberg[j + 1u][j] = 0.0;
        g[j + 1u] = -s * g[j];
        g[j] = c * g[j];
        used = j + 1u;
        running = abs(g[j + 1u]) > tol && w_norm > 0.0;
        if running {
            let inverse = 1.0 / w_norm;
            for (var e = 0u; e < st.elements; e++) {
                krylov[slot(st, w, e)] = krylov[slot(st, w, e)] * inverse;
            }
        }
    }
    // Back substitution for y, then Δv = Δv₀ + Σ y_j z_j (kept as Δv₀
    // where y is not finite).
    var y: array<f32, 8>;
    var finite = true;
    for (var k = 0u; k < used; k++) {
        let i = used - 1u - k;
        var sum = g[i];
        for (var l = i + 1u; l < used; l++) {
            sum -= hessenberg[i][l] * y[l];
        }
        y[i] = sum / hessenberg[i][i];
        finite = finite && abs(y[i]) <= 3.0e38;
    }
    if finite {
        for (var j = 0u; j < used; j++) {
            for (var e = 0u; e < st.elements; e++) {
                krylov[slot(st, DELTA_V, e)] += krylov[slot(st, DIRECTIONS + j, e)] * y[j];
            }
        }
    }
    return used;
}

// One velocity-implicit Exact step of every strand
// (batch::step::implicit::step_exact_implicit), then integrate.
@compute @workgroup_size(64)
fn stage_step(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let strand = flat_index(id, groups);
    if strand >= params.strand_count {
        return;
    }
    let st = strands[strand];
    let root = root_state(st);
    let rhs_squared = eliminate(st, root);
    back_substitute(st, DELTA_V);
    gmres_correct(st, root, sqrt(rhs_squared));
    for (var e = 0u; e < st.elements; e++) {
        let i = st.first + e;
        let v_next = v[i].xyz + krylov[slot(st, DELTA_V, e)].xyz;
        v[i] = vec4<f32>(v_next, 0.0);
        q[i] = vec4<f32>(q[i].xyz + v_next * params.h_secs, 0.0);
    }
}
