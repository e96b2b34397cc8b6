// A neutral backdrop: one triangle over the whole target, a soft grey
// vertical gradient with a gentle vignette, so hair of any colour stands
// out and nothing distracts from it. (common.wgsl comes first; unused.)

struct BackdropOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) uv: vec2<f32>,
}

@vertex
fn vs_backdrop(@builtin(vertex_index) index: u32) -> BackdropOut {
    let uv = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    var out: BackdropOut;
    out.clip = vec4<f32>(uv * 2.0 - 1.0, 1.0, 1.0);
    out.uv = vec2<f32>(uv.x, 1.0 - uv.y);
    return out;
}

@fragment
fn fs_backdrop(in: BackdropOut) -> @location(0) vec4<f32> {
    let top = vec3<f32>(0.30, 0.31, 0.33);
    let bottom = vec3<f32>(0.12, 0.12, 0.13);
    let centred = in.uv - vec2<f32>(0.5, 0.45);
    let vignette = 1.0 - 0.35 * dot(centred, centred);
    return vec4<f32>(mix(top, bottom, in.uv.y) * vignette, 1.0);
}
