// Shared by every physics kernel: the f32 arithmetic of
// crates/physics/src/batch (geometry.rs, forward.rs, suffix.rs), one strand
// per invocation. Each function here has the same name and meaning as its
// Rust twin; the CPU twins of the kernels call the Rust versions, and the
// parity tests compare the two.

struct Params {
    strand_count: u32,
    elements: u32,
    points: u32,
    _pad0: u32,
    h_secs: f32,
    mass_per_length: f32,
    air_drag: f32,
    mass_scale: f32,
    gravity_m_per_s2: vec4<f32>,
    air_velocity_m_per_s: vec4<f32>,
    nodes: array<vec4<f32>, 2>,
    weights: array<vec4<f32>, 2>,
    head_rotation: mat3x3<f32>,
    head_angular_velocity: vec4<f32>,
    head_angular_acceleration: vec4<f32>,
    head_velocity: vec4<f32>,
    head_acceleration: vec4<f32>,
}

// Per-element constants: (K, ℓ) and (qⁿ, γℓ).
struct ElementConst {
    stiffness_length: vec4<f32>,
    natural_friction: vec4<f32>,
}

struct RootPose {
    position_m: vec4<f32>,
    head_from_root: mat3x3<f32>,
}

struct Frame {
    frame: mat3x3<f32>,
    angular_velocity: vec4<f32>,
    angular_acceleration: vec4<f32>,
    point_m: vec4<f32>,
    point_velocity: vec4<f32>,
    point_acceleration: vec4<f32>,
}

struct Jacobians {
    a: mat3x3<f32>,
    b: mat3x3<f32>,
    span: vec4<f32>,
}

struct Own {
    mass_block: mat3x3<f32>,
    inertia: mat3x3<f32>,
    force: vec4<f32>,
    // first moment in xyz, mass in w
    moment: vec4<f32>,
    force_sum: vec4<f32>,
    torque_sum: vec4<f32>,
}

struct Beyond {
    inertia: mat3x3<f32>,
    moment: vec4<f32>,
    force: vec4<f32>,
    torque: vec4<f32>,
}

const SERIES_LIMIT_Y: f32 = 16.0;

fn skew(v: vec3<f32>) -> mat3x3<f32> {
    return mat3x3<f32>(vec3<f32>(0.0, v.z, -v.y), vec3<f32>(-v.z, 0.0, v.x), vec3<f32>(v.y, -v.x, 0.0));
}

fn outer(a: vec3<f32>, b: vec3<f32>) -> mat3x3<f32> {
    return mat3x3<f32>(a * b.x, a * b.y, a * b.z);
}

fn cross_cols(v: vec3<f32>, m: mat3x3<f32>) -> mat3x3<f32> {
    return mat3x3<f32>(cross(v, m[0]), cross(v, m[1]), cross(v, m[2]));
}

fn add_diagonal(m: mat3x3<f32>, d: vec3<f32>) -> mat3x3<f32> {
    var r = m;
    r[0].x += d.x;
    r[1].y += d.y;
    r[2].z += d.z;
    return r;
}

// Inverse of a positive-trace matrix, scaled by 1/trace first (see M3::inverse).
fn inverse3(mm: mat3x3<f32>) -> mat3x3<f32> {
    let scale = 1.0 / (mm[0].x + mm[1].y + mm[2].z);
    let m = mm * scale;
    let r0 = cross(m[1], m[2]);
    let r1 = cross(m[2], m[0]);
    let r2 = cross(m[0], m[1]);
    let inv_det = scale / dot(m[0], r0);
    return transpose(mat3x3<f32>(r0 * inv_det, r1 * inv_det, r2 * inv_det));
}

// Series of A (offset 1), B (2), C (3): (−1)ⁿ/(2n + offset)!, 11 terms
// (the batch geometry's: series below y = 16, see batch/geometry.rs).
fn series_term(offset: u32, n: u32) -> f32 {
    var f = 1.0;
    for (var j = 2u; j <= 2u * n + offset; j++) {
        f *= f32(j);
    }
    return select(1.0, -1.0, n % 2u == 1u) / f;
}

fn horner(offset: u32, y: f32) -> vec3<f32> {
    var p = series_term(offset, 10u);
    var dp = 0.0;
    var half_ddp = 0.0;
    for (var i = 0; i < 10; i++) {
        let n = u32(9 - i);
        half_ddp = half_ddp * y + dp;
        dp = dp * y + p;
        p = p * y + series_term(offset, n);
    }
    return vec3<f32>(p, dp, 2.0 * half_ddp);
}

struct Coefficients {
    a: vec3<f32>,
    b: vec3<f32>,
    c: vec3<f32>,
}

fn coefficients(y_in: f32, with_a: bool) -> Coefficients {
    var co: Coefficients;
    if y_in < SERIES_LIMIT_Y {
        if with_a {
            co.a = horner(1u, y_in);
        }
        co.b = horner(2u, y_in);
        co.c = horner(3u, y_in);
        return co;
    }
    let y = y_in;
    let x = sqrt(y);
    let s = sin(x);
    let cs = cos(x);
    let two_y = y + y;
    let a = s / x;
    let b = (1.0 - cs) / y;
    let c = (x - s) / (x * y);
    let c1 = (b - 3.0 * c) / two_y;
    let b1 = (a - 2.0 * b) / two_y;
    let a1 = -c - y * c1;
    let c2 = (b1 - 5.0 * c1) / two_y;
    let b2 = (a1 - 4.0 * b1) / two_y;
    let a2 = -2.0 * c1 - y * c2;
    co.a = vec3<f32>(a, a1, a2);
    co.b = vec3<f32>(b, b1, b2);
    co.c = vec3<f32>(c, c1, c2);
    return co;
}

struct PhiJet {
    phi: vec3<f32>,
    phi_dot: vec3<f32>,
    y: f32,
    y_dot: f32,
    y_ddot: f32,
    co: Coefficients,
}

fn phi_jet(sigma: f32, k: vec3<f32>, k_dot: vec3<f32>, with_a: bool) -> PhiJet {
    var j: PhiJet;
    j.phi = k * sigma;
    j.phi_dot = k_dot * sigma;
    j.y = dot(j.phi, j.phi);
    let pd = dot(j.phi, j.phi_dot);
    let dd = dot(j.phi_dot, j.phi_dot);
    j.y_dot = pd + pd;
    j.y_ddot = dd + dd;
    j.co = coefficients(j.y, with_a);
    return j;
}

fn coefficient_jet(f: vec3<f32>, j: PhiJet) -> vec3<f32> {
    return vec3<f32>(f.x, f.y * j.y_dot, f.z * j.y_dot * j.y_dot + f.y * j.y_ddot);
}

struct LocalPoint {
    h: vec3<f32>,
    h_dot: vec3<f32>,
    h_ddot: vec3<f32>,
    jacobian: mat3x3<f32>,
}

fn point_from_jet(sigma: f32, j: PhiJet) -> LocalPoint {
    let phi = j.phi;
    let pd = j.phi_dot;
    let bj = coefficient_jet(j.co.b, j);
    let cj = coefficient_jet(j.co.c, j);
    let b = bj.x;
    let c = cj.x;
    let g1 = vec3<f32>(0.0, phi.z, -phi.y);
    let g1d = vec3<f32>(0.0, pd.z, -pd.y);
    let g2 = vec3<f32>(phi.x * phi.x - j.y, phi.x * phi.y, phi.x * phi.z);
    let g2d = pd * phi.x + phi * pd.x - vec3<f32>(j.y_dot, 0.0, 0.0);
    let g2dd = pd * (pd.x + pd.x) - vec3<f32>(j.y_ddot, 0.0, 0.0);
    let f = vec3<f32>(1.0, 0.0, 0.0) + g1 * b + g2 * c;
    let fd = g1 * bj.y + g1d * b + g2 * cj.y + g2d * c;
    let fdd = g1 * bj.z + g1d * (bj.y + bj.y) + g2 * cj.z + g2d * (cj.y + cj.y) + g2dd * c;
    let u = g1 * (2.0 * j.co.b.y) + g2 * (2.0 * j.co.c.y) - vec3<f32>(2.0 * c, 0.0, 0.0);
    let cx = c * phi.x;
    let s2 = sigma * sigma;
    let col0 = u * phi.x + vec3<f32>(cx, 0.0, 0.0) + phi * c;
    let col1 = u * phi.y + vec3<f32>(0.0, cx, -b);
    let col2 = u * phi.z + vec3<f32>(0.0, b, cx);
    var lp: LocalPoint;
    lp.h = f * sigma;
    lp.h_dot = fd * sigma;
    lp.h_ddot = fdd * sigma;
    lp.jacobian = mat3x3<f32>(col0 * s2, col1 * s2, col2 * s2);
    return lp;
}

fn local_point(sigma: f32, k: vec3<f32>, k_dot: vec3<f32>) -> LocalPoint {
    return point_from_jet(sigma, phi_jet(sigma, k, k_dot, false));
}

struct FrameState {
    frame: mat3x3<f32>,
    w: vec3<f32>,
    alpha: vec3<f32>,
    p: vec3<f32>,
    pv: vec3<f32>,
    pa: vec3<f32>,
}

// p + R h with its velocity and acceleration: returns (r, ṙ, r̈) as columns.
// The flat invocation index of a 2D dispatch of 64-wide workgroups (the
// host splits large counts over y).
fn flat_index(id: vec3<u32>, groups: vec3<u32>) -> u32 {
    return id.x + id.y * groups.x * 64u;
}

// A stored Frame as the sweep's FrameState, and back.
fn frame_state(f: Frame) -> FrameState {
    var s: FrameState;
    s.frame = f.frame;
    s.w = f.angular_velocity.xyz;
    s.alpha = f.angular_acceleration.xyz;
    s.p = f.point_m.xyz;
    s.pv = f.point_velocity.xyz;
    s.pa = f.point_acceleration.xyz;
    return s;
}

fn frame_record(s: FrameState) -> Frame {
    return Frame(s.frame, vec4<f32>(s.w, 0.0), vec4<f32>(s.alpha, 0.0), vec4<f32>(s.p, 0.0),
        vec4<f32>(s.pv, 0.0), vec4<f32>(s.pa, 0.0));
}

fn carry(s: FrameState, h: vec3<f32>, h_dot: vec3<f32>, h_ddot: vec3<f32>) -> mat3x3<f32> {
    let d = s.frame * h;
    let rel_v = s.frame * h_dot;
    let w_rel_v = cross(s.w, rel_v);
    return mat3x3<f32>(
        s.p + d,
        s.pv + cross(s.w, d) + rel_v,
        s.pa + cross(s.alpha, d) + cross(s.w, cross(s.w, d)) + w_rel_v + w_rel_v + s.frame * h_ddot,
    );
}

// a about the root (Dense), a_local about the end point and span = end
// minus start (Block-diagonal and Exact: batch::forward::advance_local).
struct Advanced {
    next: FrameState,
    a: mat3x3<f32>,
    b: mat3x3<f32>,
    a_local: mat3x3<f32>,
    span: vec3<f32>,
}

fn advance(s: FrameState, length_m: f32, k: vec3<f32>, k_dot: vec3<f32>) -> Advanced {
    let j = phi_jet(length_m, k, k_dot, true);
    let end = point_from_jet(length_m, j);
    let phi = j.phi;
    let pd = j.phi_dot;
    let bj = coefficient_jet(j.co.b, j);
    let cj = coefficient_jet(j.co.c, j);
    let b = bj.x;
    let c = cj.x;
    let a = j.co.a.x;
    let sk = skew(phi);
    let pp = outer(phi, phi);
    let rotation = add_diagonal(sk * a + pp * b, vec3<f32>(1.0 - b * j.y));
    let left_jacobian = add_diagonal(sk * b + pp * c, vec3<f32>(1.0 - c * j.y));
    let m1 = cross(phi, pd);
    let m2 = cross(phi, m1);
    let spin_local = pd + m1 * b + m2 * c;
    let spin_dot_local = m1 * bj.y + m2 * cj.y + cross(pd, m1) * c;
    let moved = carry(s, end.h, end.h_dot, end.h_ddot);
    var out: Advanced;
    out.b = (s.frame * left_jacobian) * length_m;
    out.a_local = s.frame * end.jacobian;
    out.a = out.a_local + cross_cols(moved[0], out.b);
    out.span = s.frame * end.h;
    let spin = s.frame * spin_local;
    out.next.frame = s.frame * rotation;
    out.next.w = s.w + spin;
    out.next.alpha = s.alpha + cross(s.w, spin) + s.frame * spin_dot_local;
    out.next.p = moved[0];
    out.next.pv = moved[1];
    out.next.pa = moved[2];
    return out;
}

fn node(i: u32) -> f32 {
    return params.nodes[i / 4u][i % 4u];
}

fn weight(i: u32) -> f32 {
    return params.weights[i / 4u][i % 4u];
}

// Own sums of element e from its start state; with_uv also sums U and V
// (returned in the last two outputs; zero otherwise).
struct OwnSums {
    own: Own,
    u: mat3x3<f32>,
    v: mat3x3<f32>,
}

fn own_sums(e: u32, s: FrameState, k: vec3<f32>, k_dot: vec3<f32>, with_uv: bool) -> OwnSums {
    // As batch::forward::own_sums: products with G = R J in the element's
    // frame (GᵀG = JᵀJ, GᵀF = Jᵀ RᵀF), R applied once per element.
    let length_m = elements_const[e].stiffness_length.w;
    let rho_s = params.mass_per_length;
    let nu = params.air_drag;
    let g = params.gravity_m_per_s2.xyz;
    let air = params.air_velocity_m_per_s.xyz;
    var out: OwnSums;
    let zero3 = mat3x3<f32>(vec3<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0));
    out.own.mass_block = zero3;
    out.own.inertia = zero3;
    out.u = zero3;
    out.v = zero3;
    var local_force = vec3<f32>(0.0);
    var u_local = zero3;
    var v_local = zero3;
    for (var i = 0u; i < params.points; i++) {
        let lp = local_point(node(i) * length_m, k, k_dot);
        let rva = carry(s, lp.h, lp.h_dot, lp.h_ddot);
        let r = rva[0];
        let w_len = weight(i) * length_m;
        let w_mass = w_len * rho_s;
        let force = ((g - rva[2]) * rho_s - (rva[1] - air) * nu) * w_len;
        let jac = lp.jacobian;
        local_force += transpose(jac) * (transpose(s.frame) * force);
        out.own.force_sum += vec4<f32>(force, 0.0);
        out.own.torque_sum += vec4<f32>(cross(r, force), 0.0);
        out.own.mass_block += transpose(jac * w_mass) * jac;
        out.own.moment += vec4<f32>(r * w_mass, w_mass);
        let r_w = r * w_mass;
        out.own.inertia += add_diagonal(outer(r_w, r) * -1.0, vec3<f32>(dot(r_w, r)));
        if with_uv {
            let jac_w = jac * w_mass;
            u_local += jac_w;
            v_local += cross_cols(lp.h, jac_w);
        }
    }
    out.own.force = vec4<f32>(local_force, 0.0);
    if with_uv {
        out.u = s.frame * u_local;
        out.v = cross_cols(s.p, out.u) + s.frame * v_local;
    }
    return out;
}

fn root_state(strand: u32) -> FrameState {
    let pose = roots[strand];
    let offset = params.head_rotation * pose.position_m.xyz;
    let w = params.head_angular_velocity.xyz;
    let alpha = params.head_angular_acceleration.xyz;
    var s: FrameState;
    s.frame = params.head_rotation * pose.head_from_root;
    s.w = w;
    s.alpha = alpha;
    s.p = vec3<f32>(0.0);
    s.pv = params.head_velocity.xyz + cross(w, offset);
    s.pa = params.head_acceleration.xyz + cross(alpha, offset) + cross(w, cross(w, offset));
    return s;
}

struct ElementTerms {
    x_beyond: mat3x3<f32>,
    y_beyond: mat3x3<f32>,
    mass_block: mat3x3<f32>,
    force: vec3<f32>,
}

fn element_terms(jac: Jacobians, own: Own, beyond: Beyond) -> ElementTerms {
    var t: ElementTerms;
    t.x_beyond = jac.a * beyond.moment.w - cross_cols(beyond.moment.xyz, jac.b);
    t.y_beyond = cross_cols(beyond.moment.xyz, jac.a) + beyond.inertia * jac.b;
    t.mass_block = own.mass_block + transpose(jac.a) * t.x_beyond + transpose(jac.b) * t.y_beyond;
    t.force = own.force.xyz + transpose(jac.a) * beyond.force.xyz + transpose(jac.b) * beyond.torque.xyz;
    return t;
}

// (D, rhs) of element e: D = hγℓ + h²K, rhs = h[Q − K(q − qⁿ) − (γℓ + hK)q̇].
fn step_terms(e: u32, force: vec3<f32>, q: vec3<f32>, v: vec3<f32>) -> mat2x3<f32> {
    let h = params.h_secs;
    let k = elements_const[e].stiffness_length.xyz;
    let natural = elements_const[e].natural_friction.xyz;
    let friction = elements_const[e].natural_friction.w;
    let diagonal = vec3<f32>(h * friction) + k * (h * h);
    let damping = vec3<f32>(friction) + k * h;
    let rhs = (force - k * (q - natural) - damping * v) * h;
    return mat2x3<f32>(diagonal, rhs);
}

fn add_beyond(b: ptr<function, Beyond>, own: Own) {
    (*b).inertia += own.inertia;
    (*b).moment += own.moment;
    (*b).force += own.force_sum;
    (*b).torque += own.torque_sum;
}

// Moves the sums' origin by delta (new minus old): the parallel-axis rule,
// as batch::suffix::Beyond::shift.
fn shift_beyond(b: ptr<function, Beyond>, delta: vec3<f32>) {
    let c = (*b).moment.xyz;
    let m = (*b).moment.w;
    let m_delta = delta * m;
    let diagonal = dot(m_delta, delta) - (dot(c, delta) + dot(c, delta));
    (*b).inertia = add_diagonal((*b).inertia + outer(c, delta) + outer(delta, c)
        - outer(m_delta, delta), vec3<f32>(diagonal));
    (*b).moment = vec4<f32>(c - m_delta, m);
    (*b).torque = vec4<f32>((*b).torque.xyz - cross(delta, (*b).force.xyz), 0.0);
}

fn zero_beyond() -> Beyond {
    var b: Beyond;
    b.inertia = mat3x3<f32>(vec3<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0));
    return b;
}
