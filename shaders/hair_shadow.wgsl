// The deep opacity map's two passes, drawn from the light (View = the
// light's orthographic view):
//   1. depth: ribbons, depth-tested, writing their depth into a colour
//      texture: the nearest hair per texel.
//   2. opacity: ribbons again, additively into four cumulative layers; a
//      fragment adds its opacity to every layer that ends behind it.
// (common.wgsl comes first.)

struct ShadowOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) coverage: f32,
}

@vertex
fn vs_shadow(v: StrandVertex) -> ShadowOut {
    let r = ribbon_vertex(v);
    var out: ShadowOut;
    out.clip = r.clip;
    out.coverage = r.coverage;
    return out;
}

@fragment
fn fs_first_depth(in: ShadowOut) -> @location(0) vec4<f32> {
    return vec4<f32>(in.clip.z, 0.0, 0.0, 1.0);
}

@fragment
fn fs_opacity(in: ShadowOut) -> @location(0) vec4<f32> {
    let first = textureLoad(shadow_depth, vec2<i32>(in.clip.xy), 0).x;
    let depth_m = max(in.clip.z - first, 0.0) * lighting.shadow.z;
    let alpha = lighting.shadow.y * in.coverage;
    return select(vec4<f32>(0.0), vec4<f32>(alpha), vec4<f32>(depth_m) < layer_ends_m());
}
