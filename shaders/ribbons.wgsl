// Ribbon vertices built on the device from strand points already there
// (helixhair_render::gpu::device_hair; its CPU reference is
// HeadShell::drape then ribbons::ribbon_mesh). One invocation per strand:
//
// 1. drape: root to tip, each point keeps its step from the one before
//    and is pushed out to the head's shell (plus a gap) where that step
//    would enter the head, in head coordinates; then posed into the world
//    by `world_from_head`;
// 2. arc length from the root, for the taper and the shading along;
// 3. tangents by central differences (one-sided at the ends; a repeated
//    point borrows the one before it).
//
// Every point gives two vertices (the ribbon's sides), StrandVertex of
// common.wgsl written as 12 floats: position, tangent, colour,
// (along, side, seed). Compiled alone, not after common.wgsl.

struct RibbonParams {
    world_from_head: mat4x4<f32>,
    // Shell centre (head coordinates, m); w: gap kept from the head, m.
    shell_centre_m: vec4<f32>,
    strand_count: u32,
    has_shell: u32,
    shell_rows: u32,
    shell_columns: u32,
}

struct RibbonStrand {
    first_point: u32,
    point_count: u32,
    first_vertex: u32,
    seed: f32,
    colour: vec4<f32>,
}

@group(0) @binding(0) var<uniform> rp: RibbonParams;
@group(0) @binding(1) var<storage, read> points: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> ribbon_strands: array<RibbonStrand>;
@group(0) @binding(3) var<storage, read> shell_radius_m: array<f32>;
@group(0) @binding(4) var<storage, read_write> vertices: array<f32>;

const PI: f32 = 3.14159265358979;
const TAU: f32 = 6.28318530717959;
const FLOATS: u32 = 12u;

// head_shell::atan_unit: the CPU's polynomial, not the device's atan, so
// both find the same place on the shell.
fn atan_unit(x: f32) -> f32 {
    let x2 = x * x;
    var p = -0.0117212;
    p = p * x2 + 0.05265332;
    p = p * x2 - 0.11643287;
    p = p * x2 + 0.19354346;
    p = p * x2 - 0.33262347;
    p = p * x2 + 0.99997726;
    return p * x;
}

// head_shell::atan2_poly.
fn atan2_poly(y: f32, x: f32) -> f32 {
    let ay = abs(y);
    let ax = abs(x);
    let large = max(ay, ax);
    if large == 0.0 {
        return 0.0;
    }
    var r = atan_unit(min(ay, ax) / large);
    if ay > ax {
        r = 0.5 * PI - r;
    }
    if x < 0.0 {
        r = PI - r;
    }
    if y < 0.0 {
        r = -r;
    }
    return r;
}

fn shell_at(row: u32, column: u32) -> f32 {
    return shell_radius_m[row * rp.shell_columns + column];
}

// HeadShell::radius_m: bilinear between the four nearest cell centres of
// a unit direction (longitude wrapping around).
fn shell_radius(d: vec3<f32>) -> f32 {
    let rows = rp.shell_rows;
    let columns = rp.shell_columns;
    let theta = atan2_poly(sqrt(d.x * d.x + d.z * d.z), d.y);
    var phi = atan2_poly(d.x, d.z);
    if phi < 0.0 {
        phi += TAU;
    }
    let u = clamp(theta / PI * f32(rows) - 0.5, 0.0, f32(rows - 1u));
    let v = phi / TAU * f32(columns) - 0.5;
    let fu = u - floor(u);
    let fv = v - floor(v);
    let row0 = u32(floor(u));
    let row1 = min(row0 + 1u, rows - 1u);
    let column0 = u32((i32(floor(v)) + i32(columns)) % i32(columns));
    let column1 = (column0 + 1u) % columns;
    let top = shell_at(row0, column0) + fv * (shell_at(row0, column1) - shell_at(row0, column0));
    let bottom = shell_at(row1, column0) + fv * (shell_at(row1, column1) - shell_at(row1, column0));
    return top + fu * (bottom - top);
}

// HeadShell::push_out.
fn push_out(p: vec3<f32>) -> vec3<f32> {
    let d = p - rp.shell_centre_m.xyz;
    let r = length(d);
    if r <= 0.0 {
        return p;
    }
    let surface = shell_radius(d / r) + rp.shell_centre_m.w;
    if r < surface {
        return rp.shell_centre_m.xyz + d * (surface / r);
    }
    return p;
}

fn put(vertex: u32, offset: u32, v: vec3<f32>) {
    let b = vertex * FLOATS + offset;
    vertices[b] = v.x;
    vertices[b + 1u] = v.y;
    vertices[b + 2u] = v.z;
}

fn position(vertex: u32) -> vec3<f32> {
    let b = vertex * FLOATS;
    return vec3<f32>(vertices[b], vertices[b + 1u], vertices[b + 2u]);
}

fn put_position(first_vertex: u32, i: u32, head_m: vec3<f32>) {
    let world = (rp.world_from_head * vec4<f32>(head_m, 1.0)).xyz;
    put(first_vertex + 2u * i, 0u, world);
    put(first_vertex + 2u * i + 1u, 0u, world);
}

// glam's normalize_or_zero.
fn unit_or_zero(v: vec3<f32>) -> vec3<f32> {
    let l = length(v);
    if l > 0.0 {
        return v / l;
    }
    return vec3<f32>(0.0);
}

@compute @workgroup_size(64)
fn stage_ribbons(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let strand = id.x + id.y * groups.x * 64u;
    if strand >= rp.strand_count {
        return;
    }
    let st = ribbon_strands[strand];
    let n = st.point_count;
    if n < 2u {
        return;
    }
    let fv = st.first_vertex;
    var before = points[st.first_point].xyz;
    var placed = before;
    put_position(fv, 0u, placed);
    for (var i = 1u; i < n; i++) {
        let p = points[st.first_point + i].xyz;
        let step = p - before;
        before = p;
        placed = placed + step;
        if rp.has_shell != 0u {
            placed = push_out(placed);
        }
        put_position(fv, i, placed);
    }
    var total = 0.0;
    for (var i = 1u; i < n; i++) {
        total += length(position(fv + 2u * i) - position(fv + 2u * (i - 1u)));
    }
    var along = 0.0;
    var tangent = vec3<f32>(0.0);
    for (var i = 0u; i < n; i++) {
        if i > 0u {
            along += length(position(fv + 2u * i) - position(fv + 2u * (i - 1u)));
        }
        let ahead = position(fv + 2u * min(i + 1u, n - 1u));
        let behind = position(fv + 2u * max(i, 1u) - 2u);
        let t = unit_or_zero(ahead - behind);
        if i == 0u || any(t != vec3<f32>(0.0)) {
            tangent = t;
        }
        var fraction = 0.0;
        if total > 0.0 {
            fraction = along / total;
        }
        for (var side = 0u; side < 2u; side++) {
            let v = fv + 2u * i + side;
            put(v, 3u, tangent);
            put(v, 6u, st.colour.xyz);
            put(v, 9u, vec3<f32>(fraction, f32(side) * 2.0 - 1.0, st.seed));
        }
    }
}
