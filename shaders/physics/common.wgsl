// Shared by every physics kernel: the f32 arithmetic of
// crates/physics/src/batch (geometry.rs, forward.rs, suffix.rs), one strand
// per invocation. Each function here has the same name and meaning as its
// Rust twin; the CPU twins of the kernels call the Rust versions, and the
// parity tests compare the two.

// Per-element constants: (K, ℓ) and (qⁿ, γℓ).
struct ElementConst {
    stiffness_length: vec4<f32>,
    natural_friction: vec4<f32>,
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
// (the batch geometry's: series below y = 16, see batch/geometry.rs), each
// the f64 coefficient rounded once to f32, as the CPU's splat_f64 does.
const A_SERIES = array<f32, 11>(
    1.0,
    -0.1666666716337204,
    0.008333333767950535,
    -0.00019841270113829523,
    2.7557318844628753e-06,
    -2.5052107943679403e-08,
    1.6059044372074283e-10,
    -7.647163609812713e-13,
    2.8114573589663704e-15,
    -8.220635078476521e-18,
    1.9572941524685808e-20,
);
const B_SERIES = array<f32, 11>(
    0.5,
    -0.0416666679084301,
    0.0013888889225199819,
    -2.4801587642286904e-05,
    2.755731998149713e-07,
    -2.0876755879584152e-09,
    1.147074536050896e-11,
    -4.7794772561329454e-14,
    1.5619206814541513e-16,
    -4.110317590937049e-19,
    8.896790959566848e-22,
);
const C_SERIES = array<f32, 11>(
    0.1666666716337204,
    -0.008333333767950535,
    0.00019841270113829523,
    -2.7557318844628753e-06,
    2.5052107943679403e-08,
    -1.6059044372074283e-10,
    7.647163609812713e-13,
    -2.8114573589663704e-15,
    8.220635078476521e-18,
    -1.9572941524685808e-20,
    3.868170297964731e-23,
);

// One Horner step on (p, p′, p″/2): batch/geometry.rs horner's loop body.
fn horner_step(s: vec3<f32>, y: f32, c: f32) -> vec3<f32> {
    return vec3<f32>(fma(s.x, y, c), fma(s.y, y, s.x), fma(s.z, y, s.y));
}

// f(y), f′(y), f″(y) of the series c, written out: no loop, since
// lavapipe bounds the loop iterations of a whole invocation (65,535 in
// all), and the engine's step evaluates the series at every sample.
fn horner(c: array<f32, 11>, y: f32) -> vec3<f32> {
    var s = vec3<f32>(c[10], 0.0, 0.0);
    s = horner_step(s, y, c[9]);
    s = horner_step(s, y, c[8]);
    s = horner_step(s, y, c[7]);
    s = horner_step(s, y, c[6]);
    s = horner_step(s, y, c[5]);
    s = horner_step(s, y, c[4]);
    s = horner_step(s, y, c[3]);
    s = horner_step(s, y, c[2]);
    s = horner_step(s, y, c[1]);
    s = horner_step(s, y, c[0]);
    return vec3<f32>(s.x, s.y, 2.0 * s.z);
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
            co.a = horner(A_SERIES, y_in);
        }
        co.b = horner(B_SERIES, y_in);
        co.c = horner(C_SERIES, y_in);
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
    // The end point's local rates ḣ(ℓ), ḧ(ℓ) (Block-diagonal's own terms).
    end_h_dot: vec3<f32>,
    end_h_ddot: vec3<f32>,
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
    out.end_h_dot = end.h_dot;
    out.end_h_ddot = end.h_ddot;
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

// The frame of a root at `position_m` (head coordinates) with frame
// `head_from_root`, carried by the head moving as the kernel's uniforms
// say (RigidMotion::carry, as batch FrameState::at_root takes it).
fn carried_root(position_m: vec3<f32>, head_from_root: mat3x3<f32>) -> FrameState {
    let offset = params.head_rotation * position_m;
    let w = params.head_angular_velocity.xyz;
    let alpha = params.head_angular_acceleration.xyz;
    var s: FrameState;
    s.frame = params.head_rotation * head_from_root;
    s.w = w;
    s.alpha = alpha;
    s.p = vec3<f32>(0.0);
    s.pv = params.head_velocity.xyz + cross(w, offset);
    s.pa = params.head_acceleration.xyz + cross(alpha, offset) + cross(w, cross(w, offset));
    return s;
}
