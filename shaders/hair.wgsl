// Hair strands as camera-facing ribbons, shaded for fibres.
// (common.wgsl comes first.)
//
// Shading: Kajiya-Kay diffuse (light scattered around the fibre, sin of the
// angle between tangent and light), and Marschner's lobes approximated with
// shifted tangents (Scheuermann 2004): a white primary highlight R shifted
// towards the root, a coloured secondary TRT shifted towards the tip with a
// per-strand sparkle, and forward transmission TT when the light is behind
// the hair. Direct light passes the deep opacity map; the ambient term
// darkens towards the root, where strands are buried in the others.
//
// Shading runs per strand point, in the vertex shader, and is interpolated
// along the ribbon: points lie millimetres apart, so highlights and
// shadows keep their shape, while a software rasteriser (which runs the
// fragment shader on whole blocks of pixels around every thin ribbon) does
// a fraction of the work.

struct HairOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) shade: vec3<f32>,
    // x: position along the strand; y: coverage; z: strand random.
    @location(1) params: vec3<f32>,
}

@vertex
fn vs_hair(v: StrandVertex) -> HairOut {
    let r = ribbon_vertex(v);
    var out: HairOut;
    out.clip = r.clip;
    out.shade = shade_hair(v.position, normalize(v.tangent), v.colour, v.params.x, v.params.z);
    out.params = vec3<f32>(v.params.x, r.coverage, v.params.z);
    return out;
}

// A strand highlight: (sin of the angle between tangent and half vector)^e.
fn strand_highlight(tangent: vec3<f32>, half_vector: vec3<f32>, exponent: f32) -> f32 {
    let th = dot(tangent, half_vector);
    let sin_th = sqrt(max(1.0 - th * th, 0.0));
    return pow(sin_th, exponent) * smoothstep(-1.0, 0.0, th);
}

struct HairFragment {
    @location(0) colour: vec4<f32>,
    @builtin(sample_mask) mask: u32,
}

// Stochastic coverage: `alpha` of the pixel's four samples, chosen at
// random per strand and pixel. Alpha to coverage would pick the same
// samples for every strand of equal alpha, so overlapping thin strands
// could never add up to an opaque head of hair; random samples do (two
// strands of alpha 1/2 cover 3/4 on average, as two real ones would).
fn coverage_mask(alpha: f32, seed: f32, pixel: vec2<f32>) -> u32 {
    let noise = hash1(seed * 91.7 + pixel.x * 0.618 + pixel.y * 1.414);
    let samples = u32(clamp(alpha * 4.0 + noise, 0.0, 4.0));
    let rotate = u32(hash1(noise * 13.1 + seed) * 4.0) & 3u;
    let bits = (1u << samples) - 1u;
    return ((bits << rotate) | (bits >> (4u - rotate))) & 15u;
}

// The colour of a hair point at `world` with unit tangent `t`, `along`
// the strand (0 root, 1 tip), for a strand with random number `seed`.
fn shade_hair(world: vec3<f32>, t: vec3<f32>, albedo: vec3<f32>, along: f32, seed: f32) -> vec3<f32> {
    let to_eye = normalize(view.eye.xyz - world);
    let to_light = lighting.light_direction.xyz;

    var n = to_eye - t * dot(t, to_eye);
    n = select(vec3<f32>(0.0, 1.0, 0.0), normalize(n), length(n) > 1e-4);
    let tl = dot(t, to_light);
    let diffuse = mix(0.25, 1.0, sqrt(max(1.0 - tl * tl, 0.0)));

    let jitter = hash1(seed) - 0.5;
    let h = normalize(to_light + to_eye);
    let t_r = normalize(t + n * (lighting.specular.x + 0.04 * jitter));
    let t_trt = normalize(t + n * (lighting.specular.y + 0.08 * jitter));
    let sparkle = 0.6 + 0.8 * hash1(seed * 7.31 + floor(along * 24.0));
    let r = 0.14 * strand_highlight(t_r, h, lighting.specular.z);
    let trt = 0.45 * sparkle * strand_highlight(t_trt, h, lighting.specular.w);
    let tt = 0.6 * pow(max(dot(-to_light, to_eye), 0.0), 6.0);

    let shadow = light_transmittance(world);
    let light = lighting.light_colour.rgb * lighting.light_direction.w;
    let direct = (albedo * (diffuse * 0.8 + trt + tt) + vec3<f32>(r)) * light * shadow;
    let buried = mix(0.3, 1.0, smoothstep(0.0, 0.45, along));
    let ambient = albedo * lighting.ambient.rgb * lighting.ambient.w * buried * (0.4 + 0.6 * shadow);

    return tone_map(direct + ambient);
}

// How much of its pixel a fragment covers: the ribbon's true width, and
// thinning over the last fifth towards the tip.
fn hair_alpha(in: HairOut) -> f32 {
    return in.params.y * (1.0 - 0.6 * smoothstep(0.8, 1.0, in.params.x));
}

@fragment
fn fs_hair(in: HairOut) -> HairFragment {
    var out: HairFragment;
    out.colour = vec4<f32>(in.shade, 1.0);
    out.mask = coverage_mask(hair_alpha(in), in.params.z, in.clip.xy);
    return out;
}

// For backends that cannot write the sample mask (GL): alpha to coverage,
// whose fixed sample patterns make overlapping thin strands add up less.
@fragment
fn fs_hair_alpha(in: HairOut) -> @location(0) vec4<f32> {
    return vec4<f32>(in.shade, hair_alpha(in));
}
