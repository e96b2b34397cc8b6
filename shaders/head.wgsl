// The head: wrapped Lambert diffuse, a soft skin highlight, a sky/ground
// ambient, and the hair's shadow from the deep opacity map. The scalp is
// tinted towards the hair's colour so thin hair over it reads fuller.
// (common.wgsl comes first.)

struct MeshVertex {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) scalp: f32,
}

struct HeadOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) scalp: f32,
}

@vertex
fn vs_head(v: MeshVertex) -> HeadOut {
    var out: HeadOut;
    out.clip = view.clip_from_world * vec4<f32>(v.position, 1.0);
    out.world = v.position;
    out.normal = v.normal;
    out.scalp = v.scalp;
    return out;
}

@fragment
fn fs_head(in: HeadOut) -> @location(0) vec4<f32> {
    let n = normalize(in.normal);
    let to_light = lighting.light_direction.xyz;
    let to_eye = normalize(view.eye.xyz - in.world);
    let skin = vec3<f32>(0.62, 0.42, 0.33);
    let albedo = mix(skin, lighting.scalp.rgb * 0.8, in.scalp);
    let wrap = max((dot(n, to_light) + 0.3) / 1.3, 0.0);
    let h = normalize(to_light + to_eye);
    let highlight = 0.08 * pow(max(dot(n, h), 0.0), 24.0) * (1.0 - in.scalp);
    let shadow = light_transmittance(in.world + n * 0.002);
    let light = lighting.light_colour.rgb * lighting.light_direction.w;
    let direct = (albedo * wrap + vec3<f32>(highlight)) * light * shadow;
    let sky = mix(0.55, 1.0, n.y * 0.5 + 0.5);
    let ambient = albedo * lighting.ambient.rgb * lighting.ambient.w * sky;
    return vec4<f32>(tone_map(direct + ambient), 1.0);
}
