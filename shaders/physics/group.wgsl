// The uniform group's parts of the Block-diagonal, Exact and Dense
// kernels of GpuSystem (crates/physics/src/gpu/kernels.rs), after
// common.wgsl: strands that share one strand's constants (ρS, ν in the
// uniforms, element constants indexed by element), the head's motion in
// the uniforms and the roots in a buffer. The engine's step (engine.wgsl)
// reads each strand's own constants instead.

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

struct RootPose {
    position_m: vec4<f32>,
    head_from_root: mat3x3<f32>,
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
    return carried_root(roots[strand].position_m.xyz, roots[strand].head_from_root);
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
