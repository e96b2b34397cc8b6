// The GPU engine's step (appended to common.wgsl): the CPU engines' one
// step, Exact or Block-diagonal (params.method), one strand per
// invocation, every strand with its own constants and element count.
// Stages and functions keep the names of their Rust originals, whose f32
// instance at width one is the CPU twin
// (crates/physics/src/gpu/engine_twin.rs):
//   forward_with, own_sums_into   batch/forward.rs (sweep 1, root to tip,
//                                 with the head's implicit contact at each
//                                 quadrature sample: batch/contact,
//                                 collision/contact.rs implicit_force)
//   eliminate, back_substitute,   batch/step/exact.rs (sweeps 2 and 3, and
//   solve_again                   P⁻¹ b with the stored elimination)
//   blocks_tip_to_root            batch/step/block_diagonal.rs (each
//                                 element's block, with the loads'
//                                 stiffness of batch/step/load_stiffness.rs)
//   block_correction,             batch/block_terms.rs (Block-diagonal's
//   beyond_terms                  own velocity terms, F_true − F_bd)
//   velocity_product              batch/velocity_terms.rs (G z by
//                                 polarisation)
//   block_product                 batch/step/block_implicit.rs (G_bd z)
//   add_contact_coupling          batch/step/block_contact.rs ((C − C_bd) z,
//                                 the contact Block's blocks leave out)
//   gmres_correct                 gmres.rs correct (right-preconditioned
//                                 GMRES on (P + θhG) Δv = rhs)
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
    // METHOD_EXACT or METHOD_BLOCK.
    method: u32,
    // Vectors per element in `krylov`: KRYLOV_SLOTS, or BLOCK_SLOTS for
    // Block-diagonal.
    slots: u32,
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
    // θ h: the step Block-diagonal's GMRES takes its velocity terms with
    // (batch/step/block_implicit.rs BLOCK_THETA), rounded once from f64.
    block_h_secs: f32,
    _pad2: f32,
    _pad3: f32,
    _pad4: f32,
}

// One strand: its elements first..first + elements in every per-element
// buffer, its own ρS and ν, and its root on the head.
struct Strand {
    first: u32,
    elements: u32,
    // Its index among the engine's strands: the table is ordered by
    // element count, so that the invocations of one SIMD group (a warp)
    // take strands of one length and none waits on a longer one.
    index: u32,
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
// Block-diagonal's vectors after those: its own terms at the rates
// (CORRECTION) and at the two polarisation shifts, then block_correction's
// record of each element (RECORD_SLOTS vectors, fields R_*; a 3×3 matrix
// takes three, its columns).
const CORRECTION: u32 = 22u;
const CORRECTION_PLUS: u32 = 23u;
const CORRECTION_MINUS: u32 = 24u;
const RECORD: u32 = 25u;
const R_TURN: u32 = 0u; // Ω_Q, w: t_Q
const R_C: u32 = 1u;
const R_ALPHA: u32 = 2u;
const R_BETA: u32 = 3u;
const R_ALPHA_RATE: u32 = 4u;
const R_BETA_RATE: u32 = 5u;
const R_END: u32 = 6u;
const R_END_VELOCITY: u32 = 7u;
const R_OWN: u32 = 8u;
const R_FORCE: u32 = 9u;
const R_TORQUE: u32 = 10u;
const R_FIRST: u32 = 11u; // Σ m r, w: Σ m
const R_VELOCITY: u32 = 12u;
const R_S: u32 = 13u;
const R_A: u32 = 16u;
const R_B: u32 = 19u;
const R_SECOND: u32 = 22u;
const R_MIXED: u32 = 25u;
const RECORD_SLOTS: u32 = 28u;
const BLOCK_SLOTS: u32 = 53u;

const METHOD_EXACT: u32 = 0u;
const METHOD_BLOCK: u32 = 1u;

fn slot(st: Strand, which: u32, e: u32) -> u32 {
    return st.first * params.slots + which * st.elements + e;
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
    // Capped: spring and damper scaled by cap / spring for the step
    // (collision::contact, "The cap").
    if spring > cap {
        push = cap;
        gain = gain * (cap / spring);
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

// An element's own sums and Jacobians as sweep 1 left them, for the
// tip-to-root sweeps (batch::suffix::element_terms reads both).
fn own_of(el: ElementData) -> Own {
    return Own(el.own_mass_block, el.inertia, el.own_force, el.moment, el.force_sum,
        el.torque_sum);
}

fn jacobians_of(el: ElementData) -> Jacobians {
    return Jacobians(el.a, el.b, vec4<f32>(el.span.xyz, 0.0));
}

fn mul_mat_t(a: mat3x3<f32>, b: mat3x3<f32>) -> mat3x3<f32> {
    return a * transpose(b);
}

// batch::layout::shift_spatial_inertia: a twist-to-wrench matrix H (four
// 3×3 blocks) moved to an origin `delta` from its own, H′ = XᵀHX with
// X = [[𝟙, [δ]×], [0, 𝟙]]. The elimination's H and the contact's point
// inertias move by it.
fn shift_spatial_inertia(h: ptr<function, array<mat3x3<f32>, 4>>, delta: vec3<f32>) {
    let sk = skew(delta);
    let h_aa = (*h)[0];
    let h_ab = (*h)[1];
    let h_ba = (*h)[2];
    let h_aa_s = h_aa * sk;
    (*h)[1] = h_aa_s + h_ab;
    (*h)[3] = (*h)[3] + h_ba * sk - sk * h_ab - sk * h_aa_s;
    (*h)[2] = h_ba - sk * h_aa;
}

// batch::step::exact::eliminate (sweeps 1 and 2) with local moments:
// returns Σ|rhs|².
fn eliminate(st: Strand, root: FrameState) -> f32 {
    forward_with(st, root);
    let sc = 1.0 + params.h_secs * st.air_drag / st.mass_per_length;
    var b = zero_beyond();
    // The articulated inertia H past the element: H_aa, H_ab, H_ba, H_bb.
    var h = array<mat3x3<f32>, 4>(zero3(), zero3(), zero3(), zero3());
    var carried_a = vec3<f32>(0.0);
    var carried_b = vec3<f32>(0.0);
    var rhs_squared = 0.0;
    for (var k = 0u; k < st.elements; k++) {
        let i = st.first + st.elements - 1u - k;
        let el = scratch[i];
        let span = el.span.xyz;
        let own_sums = own_of(el);
        let terms = element_terms(jacobians_of(el), own_sums, b);
        let st_terms = step_terms_of(i, terms.force, q[i].xyz, v[i].xyz);
        rhs_squared += dot(st_terms[1], st_terms[1]);
        let own_v = el.v - cross_cols(span, el.u);
        let hu_top = h[0] * el.a + h[1] * el.b;
        let hu_bottom = h[2] * el.a + h[3] * el.b;
        let w_top = (el.u + terms.x_beyond) * sc - hu_top;
        let w_bottom = (own_v + terms.y_beyond) * sc - hu_bottom;
        let s_tilde = add_diagonal(terms.mass_block * sc
            - (transpose(el.b) * hu_bottom + transpose(el.a) * hu_top), st_terms[0]);
        let s_inv = inverse3(s_tilde);
        let p_top = w_top * s_inv;
        let p_bottom = w_bottom * s_inv;
        h[0] += mul_mat_t(p_top, w_top);
        h[1] += mul_mat_t(p_top, w_bottom);
        h[2] += mul_mat_t(p_bottom, w_top);
        h[3] += mul_mat_t(p_bottom, w_bottom);
        let r = st_terms[1] - (transpose(el.b) * carried_b + transpose(el.a) * carried_a);
        let y = s_inv * r;
        carried_a += w_top * y;
        carried_b += w_bottom * y;
        elimination[i] = Elimination(w_top, w_bottom, s_inv, vec4<f32>(r, 0.0));
        // Move H, the carried wrench and the sums to the element's start
        // (shift_articulated, Beyond::shift).
        let delta = -span;
        shift_spatial_inertia(&h, delta);
        carried_b = carried_b - cross(delta, carried_a);
        shift_beyond(&b, delta);
        if el.span.w != 0.0 {
            // Written out: llvmpipe counts every loop iteration (docs/gpu.md).
            h[0] -= el.contact[0];
            h[1] -= el.contact[1];
            h[2] -= el.contact[2];
            h[3] -= el.contact[3];
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

// batch::velocity_terms::polarisation_shift: c = max(|q̇|∞, 1)/|z|∞ for
// the rates shifted along krylov slot `z`.
fn polarisation_shift(st: Strand, z: u32) -> f32 {
    var v_size = 0.0;
    var z_size = 0.0;
    for (var e = 0u; e < st.elements; e++) {
        v_size = max(v_size, largest_abs3(v[st.first + e].xyz));
        z_size = max(z_size, largest_abs3(krylov[slot(st, z, e)].xyz));
    }
    if z_size < 1.17549435e-38 {
        z_size = 1.0;
    }
    return max(v_size, 1.0) / z_size;
}

// batch::velocity_terms::velocity_product: krylov slot `out` = G (slot `z`).
fn velocity_product(st: Strand, root: FrameState, z: u32, out: u32) {
    let reach = polarisation_shift(st, z);
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

// ContactInertia::project: [A; B]ᵀ (Σ φ φᵀ) [A; B], the block's share of
// the contact's point inertias past the element.
fn project_contact(c: array<mat3x3<f32>, 4>, a: mat3x3<f32>, b: mat3x3<f32>) -> mat3x3<f32> {
    let top = c[0] * a + c[1] * b;
    let bottom = c[2] * a + c[3] * b;
    return transpose(a) * top + transpose(b) * bottom;
}

// batch::step::block_diagonal::blocks_tip_to_root with local moments,
// after forward_with: each element's step matrix s M_QQ + D (+ the
// contact past it) inverted and kept (elimination[i].s_inv), the contact's
// share C_bd kept too (elimination[i].w_top, which Block-diagonal does not
// otherwise use: block_contact::contact_diagonal), Δv₀ = block⁻¹ rhs into
// slot DELTA_V. With `own_terms` (velocity-implicit), Block's own
// velocity terms (slot CORRECTION) join the force and the loads' stiffness
// h²K_Q (load_stiffness::UniformLoad) the block. Returns Σ|rhs|².
fn blocks_tip_to_root(st: Strand, root: FrameState, own_terms: bool) -> f32 {
    let sc = 1.0 + params.h_secs * st.air_drag / st.mass_per_length;
    let h_squared = params.h_secs * params.h_secs;
    // UniformLoad::new: g − a_O per kg and its direction.
    let per_kg = params.gravity_m_per_s2.xyz - root.pa;
    let size = sqrt(dot(per_kg, per_kg));
    let direction = per_kg * (1.0 / max(size, 1e-30));
    var b = zero_beyond();
    var contact = array<mat3x3<f32>, 4>(zero3(), zero3(), zero3(), zero3());
    var touched = false;
    var rhs_squared = 0.0;
    for (var k = 0u; k < st.elements; k++) {
        let e = st.elements - 1u - k;
        let i = st.first + e;
        let el = scratch[i];
        let span = el.span.xyz;
        let own_sums = own_of(el);
        let terms = element_terms(jacobians_of(el), own_sums, b);
        var force = terms.force;
        if own_terms {
            force += krylov[slot(st, CORRECTION, e)].xyz;
        }
        let st_terms = step_terms_of(i, force, q[i].xyz, v[i].xyz);
        var rhs = st_terms[1];
        var step_matrix = add_diagonal(terms.mass_block * sc, st_terms[0]);
        if own_terms {
            // UniformLoad::stiffness about the point a third of the
            // element from its end, plus the own samples' sixth.
            let lever = b.moment.xyz + span * (b.moment.w * (1.0 / 3.0))
                + el.moment.xyz * (1.0 / 6.0);
            let strength = max(dot(per_kg, lever), 0.0);
            let across = transpose(el.b) * direction;
            let stiffness = ((transpose(el.b) * el.b) - outer(across, across)) * strength
                * h_squared;
            rhs = rhs - stiffness * v[i].xyz;
            step_matrix += stiffness;
        }
        var contact_block = zero3();
        if touched {
            contact_block = project_contact(contact, el.a, el.b);
            step_matrix += contact_block;
        }
        elimination[i].w_top = contact_block;
        let inverse = inverse3(step_matrix);
        elimination[i].s_inv = inverse;
        krylov[slot(st, DELTA_V, e)] = vec4<f32>(inverse * rhs, 0.0);
        rhs_squared += dot(rhs, rhs);
        shift_beyond(&b, -span);
        if touched {
            shift_spatial_inertia(&contact, -span);
        }
        add_beyond(&b, own_sums);
        if el.span.w != 0.0 {
            contact[0] += el.contact[0];
            contact[1] += el.contact[1];
            contact[2] += el.contact[2];
            contact[3] += el.contact[3];
            touched = true;
        }
    }
    return rhs_squared;
}

fn record(st: Strand, field: u32, e: u32, x: vec3<f32>, w: f32) {
    krylov[slot(st, RECORD + field, e)] = vec4<f32>(x, w);
}

fn record_m(st: Strand, field: u32, e: u32, m: mat3x3<f32>) {
    record(st, field, e, m[0], 0.0);
    record(st, field + 1u, e, m[1], 0.0);
    record(st, field + 2u, e, m[2], 0.0);
}

fn recorded(st: Strand, field: u32, e: u32) -> vec4<f32> {
    return krylov[slot(st, RECORD + field, e)];
}

fn recorded_m(st: Strand, field: u32, e: u32) -> mat3x3<f32> {
    return mat3x3<f32>(recorded(st, field, e).xyz, recorded(st, field + 1u, e).xyz,
        recorded(st, field + 2u, e).xyz);
}

// batch::block_terms::block_correction: krylov slot `out` = F_true − F_bd
// (N·m²) at the rates q̇ + shift (slot `x`) (shift 0: q̇ itself, `x` not
// read), the forward kinematics with the root held still in its frame.
fn block_correction(st: Strand, root: FrameState, x: u32, shift: f32, out: u32) {
    var s: FrameState;
    s.frame = root.frame;
    s.w = vec3<f32>(0.0);
    s.alpha = vec3<f32>(0.0);
    s.p = vec3<f32>(0.0);
    s.pv = vec3<f32>(0.0);
    s.pa = vec3<f32>(0.0);
    let rho_s = st.mass_per_length;
    var c = vec3<f32>(0.0);
    var s_sum = zero3();
    var t = 0.0;
    for (var e = 0u; e < st.elements; e++) {
        let i = st.first + e;
        let k = q[i].xyz;
        var k_dot = v[i].xyz;
        if shift != 0.0 {
            k_dot = k_dot + krylov[slot(st, x, e)].xyz * shift;
        }
        let length_m = elements_const[i].stiffness_length.w;
        var own_local = vec3<f32>(0.0);
        var force = vec3<f32>(0.0);
        var torque = vec3<f32>(0.0);
        var mass = 0.0;
        var first = vec3<f32>(0.0);
        var velocity = vec3<f32>(0.0);
        var second = zero3();
        var mixed = zero3();
        for (var j = 0u; j < params.points; j++) {
            let lp = local_point(node(j) * length_m, k, k_dot);
            let rva = carry(s, lp.h, lp.h_dot, lp.h_ddot);
            let r = rva[0];
            let acc = rva[2];
            let m = weight(j) * length_m * rho_s;
            // f = c − S r + t r: the turn of the elements before, seen at r.
            let f = r * t + (c - s_sum * r);
            let own = transpose(s.frame) * (acc + f) - lp.h_ddot;
            own_local = transpose(lp.jacobian) * (own * m) + own_local;
            let acc_m = acc * m;
            force += acc_m;
            torque += cross(r, acc_m);
            mass += m;
            first = r * m + first;
            velocity = rva[1] * m + velocity;
            second += outer(r * m, r);
            mixed += outer(rva[1] * m, r);
        }
        let adv = advance(s, length_m, k, k_dot);
        let p = adv.next.p;
        let p_dot = adv.next.pv;
        let beta = adv.next.w - s.w;
        let beta_rate = adv.next.alpha - s.alpha;
        // α = R J_end k̇ + p × β; its rate with q̈ = 0.
        let local_velocity = s.frame * adv.end_h_dot;
        let alpha = local_velocity + cross(p, beta);
        let alpha_rate = cross(s.w, local_velocity) + s.frame * adv.end_h_ddot
            + cross(p_dot, beta) + cross(p, beta_rate);
        record(st, R_TURN, e, s.w, t);
        record(st, R_C, e, c, 0.0);
        record_m(st, R_S, e, s_sum);
        record_m(st, R_A, e, adv.a);
        record_m(st, R_B, e, adv.b);
        record(st, R_ALPHA, e, alpha, 0.0);
        record(st, R_BETA, e, beta, 0.0);
        record(st, R_ALPHA_RATE, e, alpha_rate, 0.0);
        record(st, R_BETA_RATE, e, beta_rate, 0.0);
        record(st, R_END, e, p, 0.0);
        record(st, R_END_VELOCITY, e, p_dot, 0.0);
        record(st, R_OWN, e, own_local, 0.0);
        record(st, R_FORCE, e, force, 0.0);
        record(st, R_TORQUE, e, torque, 0.0);
        record(st, R_FIRST, e, first, mass);
        record(st, R_VELOCITY, e, velocity, 0.0);
        record_m(st, R_SECOND, e, second);
        record_m(st, R_MIXED, e, mixed);
        c += cross(alpha, beta);
        s_sum += outer(beta, beta);
        t += dot(beta, beta);
        s = adv.next;
    }
    beyond_terms(st, out);
}

// block_terms::axial: the axial vector of a matrix's antisymmetric part,
// doubled.
fn axial(c: mat3x3<f32>) -> vec3<f32> {
    return vec3<f32>(c[1].z - c[2].y, c[2].x - c[0].z, c[0].y - c[1].x);
}

// batch::block_terms::beyond_terms: tip to root, each element's own share
// of F_true − F_bd plus its beyond terms from the suffix sums.
fn beyond_terms(st: Strand, out: u32) {
    var m = 0.0;
    var r_sum = vec3<f32>(0.0);
    var v_sum = vec3<f32>(0.0);
    var rr = zero3();
    var vr = zero3();
    var force = vec3<f32>(0.0);
    var torque = vec3<f32>(0.0);
    for (var k = 0u; k < st.elements; k++) {
        let e = st.elements - 1u - k;
        let turn_t = recorded(st, R_TURN, e);
        let turn = turn_t.xyz;
        let t = turn_t.w;
        let alpha = recorded(st, R_ALPHA, e).xyz;
        let beta = recorded(st, R_BETA, e).xyz;
        let end = recorded(st, R_END, e).xyz;
        let bx = skew(beta);
        let k0 = recorded(st, R_ALPHA_RATE, e).xyz - recorded(st, R_C, e).xyz - cross(turn, alpha);
        let l = add_diagonal(skew(recorded(st, R_BETA_RATE, e).xyz) - skew(turn) * bx
            + recorded_m(st, R_S, e), vec3<f32>(-t));
        let pulled = k0 * m + l * r_sum + bx * v_sum;
        let end_turn = turn + beta;
        let d0 = cross(end_turn, end) - recorded(st, R_END_VELOCITY, e).xyz;
        let nn = skew(-end_turn);
        let turned = cross(r_sum, k0) + axial(l * rr) + axial(bx * vr) + cross(v_sum, alpha)
            + axial(bx * transpose(vr)) + cross(d0, alpha) * m + cross(d0, bx * r_sum)
            + cross(nn * r_sum, alpha) + axial(bx * rr * transpose(nn));
        let a = recorded_m(st, R_A, e);
        let b = recorded_m(st, R_B, e);
        krylov[slot(st, out, e)] = vec4<f32>(transpose(b) * (torque - turned)
            + (transpose(a) * (force - pulled) + recorded(st, R_OWN, e).xyz), 0.0);
        let first = recorded(st, R_FIRST, e);
        m += first.w;
        r_sum += first.xyz;
        v_sum += recorded(st, R_VELOCITY, e).xyz;
        rr += recorded_m(st, R_SECOND, e);
        vr += recorded_m(st, R_MIXED, e);
        force += recorded(st, R_FORCE, e).xyz;
        torque += recorded(st, R_TORQUE, e).xyz;
    }
}

// batch::step::block_implicit's product: krylov slot `out`, G (slot `z`)
// on entry, becomes G_bd z = G z − (∂corr/∂q̇) z, the correction's
// derivative by polarisation.
fn block_product(st: Strand, root: FrameState, z: u32, out: u32) {
    let reach = polarisation_shift(st, z);
    block_correction(st, root, z, reach, CORRECTION_PLUS);
    block_correction(st, root, z, -reach, CORRECTION_MINUS);
    let half_over = 1.0 / (reach + reach);
    for (var e = 0u; e < st.elements; e++) {
        let difference = krylov[slot(st, CORRECTION_PLUS, e)].xyz
            - krylov[slot(st, CORRECTION_MINUS, e)].xyz;
        krylov[slot(st, out, e)] = vec4<f32>(krylov[slot(st, out, e)].xyz - difference * half_over,
            0.0);
    }
}

// batch::step::block_contact::add_contact_coupling: krylov slot `out` +=
// ((C − C_bd) z) · scale, the head's contact between elements that the
// blocks leave out (C_bd in elimination[i].w_top, from
// blocks_tip_to_root). Slots CORRECTION_PLUS and CORRECTION_MINUS, free
// once block_product has read them, hold the wrench of each element's own
// samples.
fn add_contact_coupling(st: Strand, z: u32, scale: f32, out: u32) {
    // Root to tip: the twist of z at each element's start point, and the
    // wrench it makes at the element's own samples.
    var linear = vec3<f32>(0.0);
    var angular = vec3<f32>(0.0);
    for (var e = 0u; e < st.elements; e++) {
        let i = st.first + e;
        var force = vec3<f32>(0.0);
        var torque = vec3<f32>(0.0);
        if scratch[i].span.w != 0.0 {
            let c = scratch[i].contact;
            force = c[0] * linear + c[1] * angular;
            torque = c[2] * linear + c[3] * angular;
        }
        krylov[slot(st, CORRECTION_PLUS, e)] = vec4<f32>(force, 0.0);
        krylov[slot(st, CORRECTION_MINUS, e)] = vec4<f32>(torque, 0.0);
        let x = krylov[slot(st, z, e)].xyz;
        linear = linear + cross(angular, scratch[i].span.xyz) + scratch[i].a * x;
        angular += scratch[i].b * x;
    }
    // Tip to root: the wrench of the samples past e about e's end point.
    var f = vec3<f32>(0.0);
    var tau = vec3<f32>(0.0);
    for (var k = 0u; k < st.elements; k++) {
        let e = st.elements - 1u - k;
        let i = st.first + e;
        let x = krylov[slot(st, z, e)].xyz;
        let whole = transpose(scratch[i].a) * f + transpose(scratch[i].b) * tau;
        let coupling = whole - elimination[i].w_top * x;
        krylov[slot(st, out, e)] = vec4<f32>(krylov[slot(st, out, e)].xyz + coupling * scale, 0.0);
        tau = tau + cross(scratch[i].span.xyz, f) + krylov[slot(st, CORRECTION_MINUS, e)].xyz;
        f += krylov[slot(st, CORRECTION_PLUS, e)].xyz;
    }
}

fn dot_slots(st: Strand, a: u32, b: u32) -> f32 {
    var s = 0.0;
    for (var e = 0u; e < st.elements; e++) {
        s += dot(krylov[slot(st, a, e)].xyz, krylov[slot(st, b, e)].xyz);
    }
    return s;
}

// The step's preconditioner: krylov slot `x` = P⁻¹ (slot `b`), with
// Exact's stored elimination or Block-diagonal's inverted blocks.
fn precondition(st: Strand, b: u32, x: u32) {
    if params.method == METHOD_BLOCK {
        for (var e = 0u; e < st.elements; e++) {
            let inverse = elimination[st.first + e].s_inv;
            krylov[slot(st, x, e)] = vec4<f32>(inverse * krylov[slot(st, b, e)].xyz, 0.0);
        }
    } else {
        solve_again(st, b, x);
    }
}

// The step's velocity terms' product: krylov slot `out` = G (slot `z`),
// or Block-diagonal's G_bd with the contact its blocks leave out,
// G_bd + (C − C_bd)/θh (GMRES scales the product by θh).
fn operator_product(st: Strand, root: FrameState, z: u32, out: u32) {
    velocity_product(st, root, z, out);
    if params.method == METHOD_BLOCK {
        block_product(st, root, z, out);
        add_contact_coupling(st, z, 1.0 / params.block_h_secs, out);
    }
}

// gmres::correct for one strand: corrects Δv (slot DELTA_V, P⁻¹ rhs on
// entry) towards (P + hG) Δv = rhs with at most params.iterations
// iterations, h the step the velocity terms take (θh for
// Block-diagonal); returns the iterations run.
fn gmres_correct(st: Strand, root: FrameState, rhs_norm: f32, h: f32) -> u32 {
    // Written without early returns or breaks: a strand that has converged
    // runs the rest of the loop inert (what the lanes of gmres.rs do).
    let k_max = min(params.iterations, MAX_GMRES);
    let tol = rhs_norm * params.gmres_tolerance;
    var beta = 0.0;
    if k_max > 0u {
        operator_product(st, root, DELTA_V, PRODUCT);
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
        precondition(st, BASIS + j, DIRECTIONS + j);
        operator_product(st, root, DIRECTIONS + j, PRODUCT);
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

// One step of every strand, then integrate: Exact
// (batch::step::implicit::step_exact_implicit; velocity-explicit with no
// GMRES iterations, batch::step::exact::step_exact_with) or Block-diagonal
// (batch::step::block_implicit::step_block_implicit; velocity-explicit,
// without its own terms and the loads' stiffness,
// batch::step::block_diagonal::step_block_diagonal_with).
@compute @workgroup_size(64)
fn stage_step(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let strand = flat_index(id, groups);
    if strand >= params.strand_count {
        return;
    }
    let st = strands[strand];
    let root = root_state(st);
    if params.method == METHOD_BLOCK {
        forward_with(st, root);
        let own_terms = params.iterations > 0u;
        if own_terms {
            block_correction(st, root, DELTA_V, 0.0, CORRECTION);
        }
        let rhs_squared = blocks_tip_to_root(st, root, own_terms);
        gmres_correct(st, root, sqrt(rhs_squared), params.block_h_secs);
    } else {
        let rhs_squared = eliminate(st, root);
        back_substitute(st, DELTA_V);
        gmres_correct(st, root, sqrt(rhs_squared), params.h_secs);
    }
    for (var e = 0u; e < st.elements; e++) {
        let i = st.first + e;
        let v_next = v[i].xyz + krylov[slot(st, DELTA_V, e)].xyz;
        v[i] = vec4<f32>(v_next, 0.0);
        q[i] = vec4<f32>(q[i].xyz + v_next * params.h_secs, 0.0);
    }
}
