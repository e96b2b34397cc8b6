// The guard's measure of every strand at a frame's end, on the device
// that steps them (physics::gpu::measure; CPU twin
// gpu::measure::stage_measure, which is batch/measure.rs measure_state at
// f32, one strand wide): appended to common.wgsl and engine.wgsl, whose
// strands, constants, state and collider it reads. `params` then holds the
// head's motion at the frame's end (not over a step) and the substep's h,
// which the contact's test takes.
//
// One invocation per strand sweeps root to tip as measure_state does
// (batch/forward.rs sweep_samples: each quadrature sample's position
// relative to the root and world velocity, then the element's end) and
// sums the kinetic, elastic and gravitational terms, momentum, angular
// momentum about the root point, the external forces (gravity and drag,
// from the momentum sums), their torque and power, the fastest point
// relative to the root's rigid motion and whether the head's contact acts
// at any sample (the step's own test, implicit_force). Where the frame is
// judged by Block-diagonal's own energy (measure_options.x = 1), it also
// sums T_bd as batch/block_kinetic.rs does: per element a record of the
// velocity u and turn beta its rate adds to its end, its span and its own
// samples' mass moments about its start point (block_records), then a
// tip-to-root pass carrying the suffix moments from each element's end
// point to its start.

struct StrandMeasure {
    // kinetic, strain_kinetic, block_kinetic, elastic (J)
    energies: vec4<f32>,
    // power (W), mass (kg), second moment (kg m^2), fastest (m/s)
    sums: vec4<f32>,
    // momentum (kg m/s); w: 1 where the head's contact acts at a sample
    momentum: vec4<f32>,
    // angular momentum about the root point (kg m^2/s); w: the sum of
    // |q| and |q dot| over every component, finite exactly where the whole
    // state is (the host's finiteness test, as the batch engine's
    // finite_lanes, without reading the state back)
    angular: vec4<f32>,
    force: vec4<f32>,
    torque: vec4<f32>,
    first_moment: vec4<f32>,
}

// batch/block_kinetic.rs ElementRecord: u (w: own samples' mass), beta,
// span, the own samples' first moment and second moment about the
// element's start point.
struct BlockRecord {
    u: vec4<f32>,
    beta: vec4<f32>,
    span: vec4<f32>,
    first: vec4<f32>,
    second: mat3x3<f32>,
}

@group(1) @binding(0) var<uniform> measure_options: vec4<u32>;
@group(1) @binding(1) var<storage, read_write> measures: array<StrandMeasure>;
@group(1) @binding(2) var<storage, read_write> block_records: array<BlockRecord>;

// Moments::rigid_motion_square: sum of m |u + beta x d|^2 over samples of
// mass `mass`, first moment `c` and second moment `s` about a point.
fn rigid_motion_square(mass: f32, c: vec3<f32>, s: mat3x3<f32>, u: vec3<f32>,
        beta: vec3<f32>) -> f32 {
    let trace = s[0].x + s[1].y + s[2].z;
    return mass * dot(u, u) + 2.0 * dot(u, cross(beta, c)) + dot(beta, beta) * trace
        - dot(beta, s * beta);
}

@compute @workgroup_size(64)
fn stage_measure(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let index = flat_index(id, groups);
    if index >= params.strand_count {
        return;
    }
    let st = strands[index];
    let block = measure_options.x != 0u;
    let rho_s = st.mass_per_length;
    let nu = st.air_drag;
    let g = params.gravity_m_per_s2.xyz;
    let air = params.air_velocity_m_per_s.xyz;
    let root = root_state(st);
    let root_m = params.head_position_m.xyz + params.head_rotation * st.position_m.xyz;
    var kinetic = 0.0;
    var strain_kinetic = 0.0;
    var elastic = 0.0;
    var fastest_squared = 0.0;
    var mass = 0.0;
    var second_moment = 0.0;
    var momentum = vec3<f32>(0.0);
    var angular = vec3<f32>(0.0);
    var first_moment = vec3<f32>(0.0);
    var touching = 0.0;
    var state_size = 0.0;
    // Block-diagonal's own kinetic energy: the current element's start,
    // twice its own samples' share, and their moments.
    var own_twice = 0.0;
    var s = root;
    for (var e = 0u; e < st.elements; e++) {
        let i = st.first + e;
        let length_m = elements_const[i].stiffness_length.w;
        let k = q[i].xyz;
        let k_dot = v[i].xyz;
        state_size += dot(abs(k), vec3<f32>(1.0)) + dot(abs(k_dot), vec3<f32>(1.0));
        var own_mass = 0.0;
        var own_first = vec3<f32>(0.0);
        var own_second = zero3();
        for (var j = 0u; j < params.points; j++) {
            let lp = local_point(node(j) * length_m, k, k_dot);
            let rva = carry(s, lp.h, lp.h_dot, lp.h_ddot);
            let r = rva[0];
            let vel = rva[1];
            let w_mass = weight(j) * length_m * rho_s;
            if block {
                let d = r - s.p;
                let own = vel - s.pv - cross(s.w, d);
                own_twice = fma(dot(own, own), w_mass, own_twice);
                own_mass += w_mass;
                own_first += d * w_mass;
                own_second += outer(d * w_mass, d);
            }
            kinetic = fma(dot(vel, vel) * w_mass, 0.5, kinetic);
            momentum += vel * w_mass;
            angular += cross(r, vel) * w_mass;
            first_moment += r * w_mass;
            mass += w_mass;
            second_moment = fma(dot(r, r), w_mass, second_moment);
            let rel = vel - (root.pv + cross(root.w, r));
            strain_kinetic = fma(dot(rel, rel) * w_mass, 0.5, strain_kinetic);
            fastest_squared = max(fastest_squared, dot(rel, rel));
            if params.has_collider != 0u && touching == 0.0 {
                let touch = implicit_force(root_m + r, vel, rho_s);
                if any(touch[0] != vec3<f32>(0.0)) {
                    touching = 1.0;
                }
            }
        }
        let next = advance(s, length_m, k, k_dot).next;
        let d = k - elements_const[i].natural_friction.xyz;
        let stiffness = elements_const[i].stiffness_length.xyz;
        elastic += dot(d * d, stiffness) * 0.5;
        if block {
            let span = next.p - s.p;
            var record: BlockRecord;
            record.u = vec4<f32>(next.pv - s.pv - cross(s.w, span), own_mass);
            record.beta = vec4<f32>(next.w - s.w, 0.0);
            record.span = vec4<f32>(span, 0.0);
            record.first = vec4<f32>(own_first, 0.0);
            record.second = own_second;
            block_records[i] = record;
        }
        s = next;
    }
    var block_kinetic = 0.0;
    if block {
        var twice = own_twice;
        var m = 0.0;
        var c = vec3<f32>(0.0);
        var second = zero3();
        for (var e = st.elements; e > 0u; e--) {
            let r = block_records[st.first + e - 1u];
            twice += rigid_motion_square(m, c, second, r.u.xyz, r.beta.xyz);
            // Moments::moved by the span, then plus the element's own.
            let by = r.span.xyz;
            second = second + outer(c, by) + outer(by, c) + outer(by * m, by) + r.second;
            c = c + by * m + r.first.xyz;
            m += r.u.w;
        }
        block_kinetic = twice * 0.5;
    }
    // Gravity and drag from the momentum sums (batch/measure.rs docs).
    let drag_per_mass = nu / rho_s;
    let force = g * mass - (momentum - air * mass) * drag_per_mass;
    let torque = cross(first_moment, g) - (angular - cross(first_moment, air)) * drag_per_mass;
    let power = -(kinetic + kinetic - dot(air, momentum)) * drag_per_mass;
    var out: StrandMeasure;
    out.energies = vec4<f32>(kinetic, strain_kinetic, block_kinetic, elastic);
    out.sums = vec4<f32>(power, mass, second_moment, sqrt(fastest_squared));
    out.momentum = vec4<f32>(momentum, touching);
    out.angular = vec4<f32>(angular, state_size);
    out.force = vec4<f32>(force, 0.0);
    out.torque = vec4<f32>(torque, 0.0);
    out.first_moment = vec4<f32>(first_moment, 0.0);
    measures[st.index] = out;
}
