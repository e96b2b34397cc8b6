// Drawn strands shaped by their guides on the device
// (helixhair_render::gpu::device_shape; CPU reference
// helixhair_render::strand_shape, the same loops in the same order).
// Compiled alone, not after common.wgsl.
//
// 1. stage_guide_shapes, one invocation per guide that strands clump onto
//    or follow: its curl's period from its mean strain, its centreline
//    over that period (into `axes`, at the guide's own points) and its
//    shape resampled at FOLLOW_POINTS as offsets from its root (into
//    `shapes`).
// 2. stage_shape, one invocation per drawn strand: its points copied into
//    `shaped`, then clumped onto its guide (a curl's centreline onto the
//    guide's, its own curl put back turned and scaled; straight hair point
//    by point) and pulled onto its guides' blended shape.
//
// Every curve's points are at curves[c], in one indexing shared by
// `points` (the input), `axes` and `shaped`; drawn strands and guides are
// separate curves, so their ranges never overlap.

struct ShapeParams {
    strand_count: u32,
    guide_count: u32,
    _pad0: u32,
    _pad1: u32,
}

struct Curve {
    first_point: u32,
    point_count: u32,
}

struct ShapeStrand {
    curve: u32,
    clump_guide: u32,
    follow_count: u32,
    _pad0: u32,
    clump_amount: f32,
    phase_rad: f32,
    curl_scale: f32,
    _pad1: f32,
    follow_guide: vec4<u32>,
    follow_weight: vec4<f32>,
}

@group(0) @binding(0) var<uniform> sp: ShapeParams;
@group(0) @binding(1) var<storage, read> curves: array<Curve>;
@group(0) @binding(2) var<storage, read> guides: array<u32>;
@group(0) @binding(3) var<storage, read> shape_strands: array<ShapeStrand>;
@group(0) @binding(4) var<storage, read> points: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> strains: array<f32>;
@group(0) @binding(6) var<storage, read_write> axes: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read_write> shapes: array<vec4<f32>>;
@group(0) @binding(8) var<storage, read_write> shaped: array<vec4<f32>>;

const TAU: f32 = 6.28318530717959;
const FOLLOW_POINTS: u32 = 32u;
const NONE: u32 = 0xffffffffu;
const MIN_POSITIVE: f32 = 1.17549435e-38;

const PATH_POINTS: u32 = 0u;
const PATH_AXES: u32 = 1u;
const PATH_SHAPED: u32 = 2u;
const PATH_BLENDED: u32 = 3u;

// A polyline to read: `count` points of one buffer from `first`, or the
// blended follow shape of drawn strand `strand` from `root`.
struct Path {
    kind: u32,
    first: u32,
    count: u32,
    strand: u32,
    root: vec3<f32>,
}

fn path_point(path: Path, i: u32) -> vec3<f32> {
    switch path.kind {
        case 0u: { return points[path.first + i].xyz; }
        case 1u: { return axes[path.first + i].xyz; }
        case 2u: { return shaped[path.first + i].xyz; }
        default: {
            let st = shape_strands[path.strand];
            var p = path.root;
            for (var j = 0u; j < st.follow_count; j++) {
                p += st.follow_weight[j] * shapes[st.follow_guide[j] * FOLLOW_POINTS + i].xyz;
            }
            return p;
        }
    }
}

// glam's lerp: a (1 - t) + b t.
fn lerp3(a: vec3<f32>, b: vec3<f32>, t: f32) -> vec3<f32> {
    return a * (1.0 - t) + b * t;
}

// strand_shape::curl_period_m; 0 for straight hair.
fn curl_period_m(mean_strain_per_m: f32) -> f32 {
    if mean_strain_per_m > 1.0 {
        return TAU / mean_strain_per_m;
    }
    return 0.0;
}

fn arc_length_m(path: Path) -> f32 {
    var total = 0.0;
    for (var i = 1u; i < path.count; i++) {
        total += distance(path_point(path, i - 1u), path_point(path, i));
    }
    return total;
}

// strand_shape::ArcWalk.
struct Walk {
    segment: u32,
    start_m: f32,
}

fn walk_to(walk: ptr<function, Walk>, path: Path, s_m: f32) -> vec3<f32> {
    loop {
        if (*walk).segment + 2u >= path.count {
            break;
        }
        let d = distance(path_point(path, (*walk).segment), path_point(path, (*walk).segment + 1u));
        if (*walk).start_m + d >= s_m {
            break;
        }
        (*walk).start_m += d;
        (*walk).segment += 1u;
    }
    let a = path_point(path, (*walk).segment);
    let b = path_point(path, (*walk).segment + 1u);
    let span = max(distance(a, b), MIN_POSITIVE);
    return lerp3(a, b, clamp((s_m - (*walk).start_m) / span, 0.0, 1.0));
}

// strand_shape::centreline of `source` into axes[first ..].
fn centreline_into_axes(source: Path, period_m: f32) {
    let n = source.count;
    let half = 0.5 * period_m;
    var lo = 0u;
    var hi = 0u;
    var s_i = 0.0;
    var s_lo = 0.0;
    var s_next = 0.0;
    if n > 1u {
        s_next = distance(path_point(source, 0u), path_point(source, 1u));
    }
    var sum = path_point(source, 0u);
    for (var i = 0u; i < n; i++) {
        if i > 0u {
            s_i += distance(path_point(source, i), path_point(source, i - 1u));
        }
        while s_lo < s_i - half {
            sum -= path_point(source, lo);
            s_lo += distance(path_point(source, lo), path_point(source, lo + 1u));
            lo++;
        }
        loop {
            if hi + 1u >= n || s_next > s_i + half {
                break;
            }
            hi++;
            sum += path_point(source, hi);
            if hi + 1u < n {
                s_next += distance(path_point(source, hi), path_point(source, hi + 1u));
            }
        }
        axes[source.first + i] = vec4<f32>(sum / f32(hi + 1u - lo), 1.0);
    }
}

// strand_shape::clump_onto of shaped[first .. first + n] onto `guide`.
fn clump_onto(first: u32, n: u32, guide: Path, amount: f32) {
    let total_m = arc_length_m(Path(PATH_SHAPED, first, n, 0u, vec3<f32>(0.0)));
    if total_m <= 0.0 || guide.count < 2u {
        return;
    }
    var walk = Walk(0u, 0.0);
    var s_m = 0.0;
    var before = shaped[first].xyz;
    for (var i = 0u; i < n; i++) {
        let p = shaped[first + i].xyz;
        s_m += distance(p, before);
        before = p;
        let goal = walk_to(&walk, guide, s_m);
        shaped[first + i] = vec4<f32>(lerp3(p, goal, amount * s_m / total_m), 1.0);
    }
}

// strand_shape::turn_about.
fn turn_about(axis: vec3<f32>, angle_rad: f32, v: vec3<f32>) -> vec3<f32> {
    if all(axis == vec3<f32>(0.0)) {
        return v;
    }
    let s = sin(angle_rad);
    let c = cos(angle_rad);
    return v * c + cross(axis, v) * s + axis * (dot(axis, v) * (1.0 - c));
}

fn normalize_or_zero(v: vec3<f32>) -> vec3<f32> {
    let l = length(v);
    if l > 0.0 && l < 3.4e38 {
        return v / l;
    }
    return vec3<f32>(0.0);
}

// strand_shape::clump_curl_onto_axis of shaped[first .. first + n].
fn clump_curl_onto(first: u32, n: u32, guide_axis: Path, st: ShapeStrand, period_m: f32) {
    if n < 3u || guide_axis.count < 2u {
        return;
    }
    let own = Path(PATH_SHAPED, first, n, 0u, vec3<f32>(0.0));
    centreline_into_axes(own, period_m);
    let axis_total_m = arc_length_m(Path(PATH_AXES, first, n, 0u, vec3<f32>(0.0)));
    var walk = Walk(0u, 0.0);
    var s_m = 0.0;
    var before = shaped[first].xyz;
    var s_axis_m = 0.0;
    var axis_before = axes[first].xyz;
    for (var i = 0u; i < n; i++) {
        let p = shaped[first + i].xyz;
        s_m += distance(p, before);
        before = p;
        let axis = axes[first + i].xyz;
        s_axis_m += distance(axis, axis_before);
        axis_before = axis;
        var goal = axis;
        if axis_total_m > 0.0 {
            let on_guide = walk_to(&walk, guide_axis, s_axis_m);
            goal = lerp3(axis, on_guide, st.clump_amount * s_axis_m / axis_total_m);
        }
        let ramp = min(s_m / period_m, 1.0);
        let next = axes[first + min(i + 1u, n - 1u)].xyz;
        let prev = axes[first + max(i, 1u) - 1u].xyz;
        let along = normalize_or_zero(next - prev);
        let scale = 1.0 + (st.curl_scale - 1.0) * ramp;
        let curl = turn_about(along, ramp * st.phase_rad, p - axis);
        shaped[first + i] = vec4<f32>(goal + scale * curl, 1.0);
    }
}

@compute @workgroup_size(64)
fn stage_guide_shapes(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let g = id.x + id.y * groups.x * 64u;
    if g >= sp.guide_count {
        return;
    }
    let c = curves[guides[g]];
    let curve = Path(PATH_POINTS, c.first_point, c.point_count, 0u, vec3<f32>(0.0));
    let period_m = curl_period_m(strains[guides[g]]);
    if period_m > 0.0 && c.point_count > 0u {
        centreline_into_axes(curve, period_m);
    }
    // interpolate::resampled_shape.
    let out = g * FOLLOW_POINTS;
    if c.point_count < 2u {
        for (var k = 0u; k < FOLLOW_POINTS; k++) {
            shapes[out + k] = vec4<f32>(0.0);
        }
        return;
    }
    let root = path_point(curve, 0u);
    let total_m = arc_length_m(curve);
    var walk = Walk(0u, 0.0);
    for (var k = 0u; k < FOLLOW_POINTS; k++) {
        let s_m = total_m * f32(k) / f32(FOLLOW_POINTS - 1u);
        shapes[out + k] = vec4<f32>(walk_to(&walk, curve, s_m) - root, 0.0);
    }
}

@compute @workgroup_size(64)
fn stage_shape(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let strand = id.x + id.y * groups.x * 64u;
    if strand >= sp.strand_count {
        return;
    }
    let st = shape_strands[strand];
    let c = curves[st.curve];
    let first = c.first_point;
    let n = c.point_count;
    for (var i = 0u; i < n; i++) {
        shaped[first + i] = points[first + i];
    }
    if st.clump_guide != NONE {
        let gc = curves[guides[st.clump_guide]];
        let period_m = curl_period_m(strains[guides[st.clump_guide]]);
        if period_m > 0.0 {
            let guide_axis = Path(PATH_AXES, gc.first_point, gc.point_count, 0u, vec3<f32>(0.0));
            clump_curl_onto(first, n, guide_axis, st, period_m);
        } else {
            let guide = Path(PATH_POINTS, gc.first_point, gc.point_count, 0u, vec3<f32>(0.0));
            clump_onto(first, n, guide, st.clump_amount);
        }
    }
    if st.follow_count > 0u && n > 0u {
        let blended = Path(PATH_BLENDED, 0u, FOLLOW_POINTS, strand, shaped[first].xyz);
        clump_onto(first, n, blended, 1.0);
    }
}
