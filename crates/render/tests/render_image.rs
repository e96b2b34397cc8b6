//! The renderer draws hair where it should: small pictures, checked with
//! stated thresholds rather than against one machine's pixels.
//!
//! The scene is the default head with straight strands hanging from a grid
//! of roots on its scalp, seen from the front, in a 128 × 128 picture.

use glam::Vec3;
use helixhair_gpu::context_or_skip;
use helixhair_render::head_generate::default_head;
use helixhair_render::{
    HairStrands, HeadMesh, Light, OffscreenRenderer, OrbitCamera, RenderSettings, RgbaImage, Scene,
    StrandBuffers,
};

const SIDE_PX: u32 = 128;

/// Straight strands from the centres of every scalp triangle, along the
/// surface normal for 2 cm and then down for 15 cm.
fn hanging_hair(head: &HeadMesh) -> HairStrands {
    let mut strands = StrandBuffers::default();
    for &t in &head.scalp_triangles {
        let corners = head.mesh.triangle(t as usize);
        let normal = head
            .mesh
            .triangle_normals(t as usize)
            .iter()
            .sum::<Vec3>()
            .normalize();
        let root = corners.iter().sum::<Vec3>() / 3.0;
        let bend = root + normal * 0.02;
        strands.push_strand((0..=12).map(|k| {
            let s = k as f32 / 12.0;
            if s < 0.2 {
                root.lerp(bend, s / 0.2)
            } else {
                bend - Vec3::Y * 0.15 * (s - 0.2) / 0.8
            }
        }));
    }
    one_colour(strands, Vec3::new(0.35, 0.2, 0.08), [4e-4, 1e-4])
}

/// `strands` all in `colour`, `[root, tip]` widths in metres.
fn one_colour(
    strands: StrandBuffers,
    colour: Vec3,
    [root_width_m, tip_width_m]: [f32; 2],
) -> HairStrands {
    let n = strands.strand_count();
    HairStrands {
        strands,
        colours: vec![colour; n],
        root_width_m,
        tip_width_m,
    }
}

fn front_camera() -> OrbitCamera {
    OrbitCamera {
        yaw_rad: 0.0,
        pitch_rad: 0.0,
        ..OrbitCamera::default()
    }
}

fn render(hair: &HairStrands, head: &HeadMesh, test: &str) -> Option<RgbaImage> {
    render_with(RenderSettings::new(SIDE_PX, SIDE_PX), hair, head, test)
}

fn render_with(
    settings: RenderSettings,
    hair: &HairStrands,
    head: &HeadMesh,
    test: &str,
) -> Option<RgbaImage> {
    let gpu = context_or_skip(test)?;
    let mut renderer = OffscreenRenderer::new(gpu, settings).expect("renderer");
    let scene = Scene {
        hair,
        head,
        camera: front_camera(),
        light: Light::default(),
    };
    let image = renderer.render(&scene).expect("renders");
    if let Ok(dir) = std::env::var("HELIXHAIR_TEST_IMAGES") {
        let path = std::path::Path::new(&dir).join(format!("{test}.png"));
        image::save_buffer(
            &path,
            &image.rgba,
            image.width_px,
            image.height_px,
            image::ExtendedColorType::Rgba8,
        )
        .expect("saved");
    }
    Some(image)
}

/// Where a world point lands in the picture, in pixels (x right, y down).
fn pixel_of(p: Vec3) -> (u32, u32) {
    let clip = front_camera().clip_from_world(1.0) * p.extend(1.0);
    let ndc = clip.truncate() / clip.w;
    let x = (ndc.x * 0.5 + 0.5) * SIDE_PX as f32;
    let y = (0.5 - ndc.y * 0.5) * SIDE_PX as f32;
    (x as u32, y as u32)
}

fn luma(px: [u8; 4]) -> f32 {
    0.2126 * px[0] as f32 + 0.7152 * px[1] as f32 + 0.0722 * px[2] as f32
}

#[test]
fn hair_covers_the_scalp_and_the_face_stays_visible() {
    let head = default_head();
    let hair = hanging_hair(&head);
    let Some(with_hair) = render(&hair, &head, "hair_covers_the_scalp") else {
        return;
    };
    let Some(bald) = render(&HairStrands::default(), &head, "bald") else {
        return;
    };

    // Projected scalp triangle centres: the hair must change most of them.
    let scalp_pixels: Vec<(u32, u32)> = head
        .scalp_triangles
        .iter()
        .map(|&t| pixel_of(head.mesh.triangle(t as usize).iter().sum::<Vec3>() / 3.0))
        .collect();
    let changed = scalp_pixels
        .iter()
        .filter(|&&(x, y)| {
            let (a, b) = (with_hair.pixel(x, y), bald.pixel(x, y));
            (0..3)
                .map(|c| (a[c] as i32 - b[c] as i32).abs())
                .sum::<i32>()
                > 12
        })
        .count();
    let coverage = changed as f32 / scalp_pixels.len() as f32;
    assert!(
        coverage > 0.6,
        "hair changes only {:.0}% of the scalp's pixels",
        100.0 * coverage
    );

    // The face (nose tip, below the hairline) is skin in both pictures:
    // lit, reddish, and not hidden by hair.
    let (x, y) = pixel_of(Vec3::new(0.0, -0.02, 0.11));
    for image in [&with_hair, &bald] {
        let px = image.pixel(x, y);
        assert!(px[0] > px[2] + 15 && luma(px) > 50.0, "face pixel {px:?}");
    }
    // The backdrop corner is neutral grey.
    let corner = bald.pixel(2, 2);
    assert!(
        (corner[0] as i32 - corner[2] as i32).abs() < 12,
        "backdrop {corner:?}"
    );
}

#[test]
fn shading_varies_along_a_strand() {
    let head = default_head();
    // One thick strand in front of the face, hanging straight down: the
    // root is buried (ambient darkening) and the tip is not.
    let mut strands = StrandBuffers::default();
    strands.push_strand((0..=20).map(|k| Vec3::new(-0.05, 0.08 - 0.012 * k as f32, 0.16)));
    let hair = HairStrands {
        strands,
        colours: vec![Vec3::new(0.6, 0.45, 0.25)],
        root_width_m: 5e-3,
        tip_width_m: 5e-3,
    };
    let Some(image) = render(&hair, &head, "shading_along") else {
        return;
    };
    let samples: Vec<f32> = (1..=18)
        .map(|k| {
            let (x, y) = pixel_of(Vec3::new(-0.05, 0.08 - 0.012 * k as f32, 0.16));
            luma(image.pixel(x, y))
        })
        .collect();
    let (lo, hi) = samples
        .iter()
        .fold((f32::MAX, f32::MIN), |(lo, hi), &l| (lo.min(l), hi.max(l)));
    assert!(
        hi - lo > 20.0,
        "luma along the strand only spans {lo}..{hi}: {samples:?}"
    );
}

/// A sheet of vertical strands at depth `z_m`, from `x0_m` to `x1_m`,
/// shifted by `shift_m`.
fn sheet(strands: &mut StrandBuffers, x0_m: f32, x1_m: f32, z_m: f32, shift_m: Vec3) {
    for i in 0..=80 {
        let x = x0_m + (x1_m - x0_m) * i as f32 / 80.0;
        strands.push_strand((0..=10).map(|k| Vec3::new(x, 0.1 - 0.02 * k as f32, z_m) + shift_m));
    }
}

/// Sheet B hangs in front of the face; sheet A is the same sheet moved
/// 3 cm towards the light. Seen from the front, A does not cover B's
/// left edge ([`sheet_edge_px`]), but it lies between that edge and the
/// light.
fn sheets(with_a: bool) -> HairStrands {
    let towards_light = Light::default().direction;
    let mut strands = StrandBuffers::default();
    sheet(&mut strands, -0.06, 0.0, 0.15, Vec3::ZERO);
    if with_a {
        sheet(&mut strands, -0.06, 0.0, 0.15, towards_light * 0.03);
    }
    one_colour(strands, Vec3::new(0.6, 0.5, 0.4), [1e-3, 1e-3])
}

/// A pixel on sheet B's left edge.
fn sheet_edge_px() -> (u32, u32) {
    pixel_of(Vec3::new(-0.056, 0.02, 0.15))
}

#[test]
fn hair_between_the_light_and_a_strand_shadows_it() {
    let head = default_head();
    let hair = sheets;
    let Some(lit) = render(&hair(false), &head, "sheet_alone") else {
        return;
    };
    let Some(shadowed) = render(&hair(true), &head, "sheet_shadowed") else {
        return;
    };
    let (x, y) = sheet_edge_px();
    let (l, s) = (luma(lit.pixel(x, y)), luma(shadowed.pixel(x, y)));
    // Threshold: at least 15% darker in the shadow of a dense sheet.
    assert!(s < 0.85 * l, "luma {s} in shadow vs {l} lit");
}

/// The window's quick preview: without shadows sheet A no longer darkens
/// B, and at one sample per pixel the sheets are still drawn.
#[test]
fn without_shadows_nothing_is_shadowed_and_one_sample_still_draws_the_hair() {
    let head = default_head();
    let preview = RenderSettings {
        shadows: false,
        msaa_samples: 1,
        ..RenderSettings::new(SIDE_PX, SIDE_PX)
    };
    let Some(alone) = render_with(preview, &sheets(false), &head, "preview_sheet_alone") else {
        return;
    };
    let Some(both) = render_with(preview, &sheets(true), &head, "preview_sheets") else {
        return;
    };
    let Some(bare) = render_with(preview, &hair_free(), &head, "preview_no_hair") else {
        return;
    };
    let (x, y) = sheet_edge_px();
    let (l, s) = (luma(alone.pixel(x, y)), luma(both.pixel(x, y)));
    // The same pixel of the same strand, lit the same: equal but for
    // rounding.
    assert!((s - l).abs() <= 1.0, "luma {s} behind sheet A vs {l} alone");
    let hair_px = (0..SIDE_PX * SIDE_PX)
        .filter(|i| alone.pixel(i % SIDE_PX, i / SIDE_PX) != bare.pixel(i % SIDE_PX, i / SIDE_PX))
        .count();
    // The sheet is 6 cm by 15 cm in front of a 128-pixel view of a head
    // about 30 cm tall: several hundred pixels at least.
    assert!(hair_px > 500, "{hair_px} pixels of hair");
}

/// A picture in the window's byte order (BGRA) reads back as the same
/// RGBA bytes as the default picture: only the order in memory differs.
#[test]
fn a_bgra_picture_reads_back_as_the_same_picture() {
    let head = default_head();
    let hair = hanging_hair(&head);
    let bgra = RenderSettings {
        picture_format: wgpu::TextureFormat::Bgra8UnormSrgb,
        ..RenderSettings::new(SIDE_PX, SIDE_PX)
    };
    let Some(a) = render(&hair, &head, "rgba_picture") else {
        return;
    };
    let Some(b) = render_with(bgra, &hair, &head, "bgra_picture") else {
        return;
    };
    assert!(a.rgba == b.rgba, "the pictures differ");
}

fn hair_free() -> HairStrands {
    one_colour(StrandBuffers::default(), Vec3::ONE, [1e-3, 1e-3])
}
