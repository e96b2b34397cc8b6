// Shared by every pass; the renderer puts this file in front of each pass's
// own file (crates/render/src/gpu/shaders.rs). The structs mirror
// crates/render/src/gpu/gpu_data.rs, and a test compares their sizes.

// One point of view: the camera, or the light (orthographic).
struct View {
    clip_from_world: mat4x4<f32>,
    // xyz: eye position when w = 1; unit direction towards the eye when
    // w = 0 (orthographic).
    eye: vec4<f32>,
    // x, y: target size in pixels; z: pixels per metre at unit clip w
    // (focal length in pixels); w: narrowest ribbon drawn, pixels.
    viewport: vec4<f32>,
    // x: ribbon width at the root, metres; y: at the tip; z, w: unused.
    ribbon: vec4<f32>,
}

// Lights, materials and the deep opacity map's parameters.
struct Lighting {
    light_clip_from_world: mat4x4<f32>,
    // xyz: unit direction towards the light; w: intensity.
    light_direction: vec4<f32>,
    // rgb: light colour.
    light_colour: vec4<f32>,
    // rgb: ambient (sky) colour; w: ambient strength.
    ambient: vec4<f32>,
    // x: first opacity layer thickness, metres (layers double: 1, 2, 4, 8
    // times it); y: opacity one strand fragment adds; z: light-space depth
    // range in metres (ndc depth 0..1 maps onto it); w: unused.
    shadow: vec4<f32>,
    // rgb: the scalp's tint (the hair's mean colour); w: unused.
    scalp: vec4<f32>,
    // x, y: shifts of the primary (R) and secondary (TRT) highlights along
    // the strand normal; z, w: their exponents.
    specular: vec4<f32>,
}

@group(0) @binding(0) var<uniform> view: View;
@group(1) @binding(0) var<uniform> lighting: Lighting;
// Depth of the first hair the light meets, per texel (in a half-float
// colour texture, not a depth texture: GL cannot load from depth textures).
@group(1) @binding(1) var shadow_depth: texture_2d<f32>;
@group(2) @binding(0) var opacity_map: texture_2d<f32>;
@group(2) @binding(1) var opacity_sampler: sampler;

// One point of a strand, duplicated for the two sides of its ribbon.
struct StrandVertex {
    @location(0) position: vec3<f32>,
    @location(1) tangent: vec3<f32>,
    @location(2) colour: vec3<f32>,
    // x: position along the strand (0 root, 1 tip); y: side (-1 or 1);
    // z: per-strand random number in [0, 1).
    @location(3) params: vec3<f32>,
}

struct Ribbon {
    clip: vec4<f32>,
    // Fraction of the drawn width the true width covers (<= 1).
    coverage: f32,
}

// Expands a strand point sideways in screen space, perpendicular to the
// strand's projected tangent, to the ribbon's width at `along`; ribbons
// narrower than the viewport's minimum are drawn at the minimum and report
// the fraction they really cover.
fn ribbon_vertex(v: StrandVertex) -> Ribbon {
    let clip = view.clip_from_world * vec4<f32>(v.position, 1.0);
    let ahead = view.clip_from_world * vec4<f32>(v.position + v.tangent * 1e-3, 1.0);
    let half_size = view.viewport.xy * 0.5;
    var along_px = (ahead.xy / ahead.w - clip.xy / clip.w) * half_size;
    if length(along_px) < 1e-6 {
        along_px = vec2<f32>(1.0, 0.0);
    }
    let across_px = normalize(vec2<f32>(-along_px.y, along_px.x));
    let width_m = mix(view.ribbon.x, view.ribbon.y, v.params.x);
    let half_px = 0.5 * width_m * view.viewport.z / max(clip.w, 1e-6);
    let drawn_half_px = max(half_px, 0.5 * view.viewport.w);
    let offset_ndc = across_px * drawn_half_px * v.params.y / half_size;
    var out: Ribbon;
    out.clip = vec4<f32>(clip.xy + offset_ndc * clip.w, clip.zw);
    out.coverage = half_px / drawn_half_px;
    return out;
}

// Texture coordinates and ndc depth of a world point in the light's view.
fn light_uv_depth(world: vec3<f32>) -> vec3<f32> {
    let c = lighting.light_clip_from_world * vec4<f32>(world, 1.0);
    let ndc = c.xyz / c.w;
    return vec3<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5, ndc.z);
}

// Depths (metres behind the first hair) where the opacity layers end.
fn layer_ends_m() -> vec4<f32> {
    return vec4<f32>(1.0, 2.0, 4.0, 8.0) * lighting.shadow.x;
}

// How much hair lies between the light and `world`: the deep opacity map's
// cumulative layers, read piecewise linearly at the point's depth behind
// the first hair the light sees.
fn hair_opacity(world: vec3<f32>) -> f32 {
    let p = light_uv_depth(world);
    if any(p.xy < vec2<f32>(0.0)) || any(p.xy > vec2<f32>(1.0)) {
        return 0.0;
    }
    let size = vec2<i32>(textureDimensions(shadow_depth));
    let texel = clamp(vec2<i32>(p.xy * vec2<f32>(size)), vec2<i32>(0), size - 1);
    let first = textureLoad(shadow_depth, texel, 0).x;
    let depth_m = (p.z - first) * lighting.shadow.z;
    if depth_m <= 0.0 {
        return 0.0;
    }
    let layers = textureSampleLevel(opacity_map, opacity_sampler, p.xy, 0.0);
    let ends = layer_ends_m();
    if depth_m < ends.x {
        return layers.x * depth_m / ends.x;
    }
    if depth_m < ends.y {
        return mix(layers.x, layers.y, (depth_m - ends.x) / (ends.y - ends.x));
    }
    if depth_m < ends.z {
        return mix(layers.y, layers.z, (depth_m - ends.y) / (ends.z - ends.y));
    }
    if depth_m < ends.w {
        return mix(layers.z, layers.w, (depth_m - ends.z) / (ends.w - ends.z));
    }
    return layers.w;
}

// Whether the hair's self-shadow is read: a pipeline constant, false for
// quick previews (the renderer's `shadows: false`), whose pipelines then
// read no shadow texture at all (texture reads are the dearest part of a
// fragment on a CPU rasteriser).
override SHADOWS: bool = true;

// Fraction of the light that reaches `world` through the hair.
fn light_transmittance(world: vec3<f32>) -> f32 {
    if !SHADOWS {
        return 1.0;
    }
    return exp(-hair_opacity(world));
}

// Display curve: linear light to [0, 1) with a soft shoulder
// (1 - exp(-exposure c)), so bright highlights roll off instead of
// clipping. The target's sRGB encoding comes after.
fn tone_map(c: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(1.0) - exp(-1.3 * c);
}

// A hash of a float in [0, 1) to [0, 1).
fn hash1(x: f32) -> f32 {
    return fract(sin(x * 12.9898 + 78.233) * 43758.5453);
}
