//! Draws an exported animation as it reads back: the first and the last
//! time sample of a `.usda` (or any file the formats crate reads), read
//! with `helixhair-formats` and drawn by the renderer on the default head,
//! side by side in one PNG. Proof that what HelixHair exports is the hair
//! it simulated (docs/export.md shows the picture).
//!
//! ```sh
//! helixhair sim --style assets/styles/groomed/full_head.ron --play shake --steps 120 \
//!     --strands drawn --export out/full_head.usda
//! cargo run --release -p helixhair-app --example reimport_picture -- \
//!     out/full_head.usda docs/images/export_reimported.png
//! ```
//!
//! Needs a graphics adapter (lavapipe works: `WGPU_BACKEND=vulkan`).

use std::path::PathBuf;

use anyhow::Context as _;
use glam::Vec3;
use helixhair_app::cli::camera_arg::CameraArg;
use helixhair_app::cli::render::write_picture;
use helixhair_formats::{CurveSet, Format, ReadOptions, StrandValue, read};
use helixhair_render::head_generate::default_head;
use helixhair_render::{
    GpuContext, HairStrands, Light, OffscreenRenderer, RenderSettings, RgbaImage, Scene,
    StrandBuffers,
};

/// Each half of the picture, pixels.
const HALF_W: u32 = 640;
const HEIGHT: u32 = 640;

/// Colour of strands the file gives none (dark brown, linear).
const DEFAULT_COLOUR: Vec3 = Vec3::new(0.04, 0.017, 0.007);

fn hair(curves: &CurveSet, points: &[Vec3]) -> HairStrands {
    let mut strands = StrandBuffers::default();
    let mut colours = Vec::new();
    let mut start = 0;
    let mut root_width_m: f32 = 0.0;
    for curve in &curves.curves {
        let n = curve.points_m.len();
        strands.push_strand(points[start..start + n].iter().copied());
        start += n;
        colours.push(
            curve
                .colour
                .as_ref()
                .and_then(|c| c.at(0))
                .map_or(DEFAULT_COLOUR, Vec3::from_array),
        );
        if let Some(w) = curve
            .width_m
            .as_ref()
            .and_then(|w: &StrandValue<f32>| w.at(0))
        {
            root_width_m = root_width_m.max(w);
        }
    }
    // Fibre-thin simulated strands alone would vanish at this size.
    let root_width_m = root_width_m.max(3e-4);
    HairStrands {
        strands,
        colours,
        root_width_m,
        tip_width_m: 0.35 * root_width_m,
    }
}

fn main() -> anyhow::Result<()> {
    let mut args = std::env::args_os().skip(1).map(PathBuf::from);
    let (Some(input), Some(output)) = (args.next(), args.next()) else {
        anyhow::bail!("usage: reimport_picture EXPORTED.usda OUT.png");
    };
    let bytes =
        std::fs::read(&input).with_context(|| format!("cannot read {}", input.display()))?;
    let format = Format::from_path(&input).context("unknown extension")?;
    let imported = read(&bytes, format, &ReadOptions::default())
        .map_err(|e| anyhow::anyhow!("{}: {e}", input.display()))?;
    let curves = &imported.curves;
    let flat: Vec<Vec3> = curves
        .curves
        .iter()
        .flat_map(|c| c.points_m.iter().copied())
        .collect();
    let (first, last) = match &imported.animation {
        Some(a) if !a.frames.is_empty() => (
            a.frames[0].points_m.clone(),
            a.frames[a.frames.len() - 1].points_m.clone(),
        ),
        _ => (flat.clone(), flat),
    };
    let head = default_head();
    let camera = "front"
        .parse::<CameraArg>()
        .map_err(anyhow::Error::msg)?
        .camera();
    let mut renderer = OffscreenRenderer::new(
        GpuContext::new_headless()?,
        RenderSettings::new(HALF_W, HEIGHT),
    )?;
    let mut halves = Vec::new();
    for points in [&first, &last] {
        let hair = hair(curves, points);
        let scene = Scene {
            hair: &hair,
            head: &head,
            camera,
            light: Light::default(),
        };
        halves.push(renderer.render(&scene)?);
    }
    let mut rgba = vec![0u8; (2 * HALF_W * HEIGHT * 4) as usize];
    for (h, half) in halves.iter().enumerate() {
        for y in 0..HEIGHT as usize {
            let row = &half.rgba[y * HALF_W as usize * 4..(y + 1) * HALF_W as usize * 4];
            let at = (y * 2 * HALF_W as usize + h * HALF_W as usize) * 4;
            rgba[at..at + row.len()].copy_from_slice(row);
        }
    }
    let picture = RgbaImage {
        width_px: 2 * HALF_W,
        height_px: HEIGHT,
        rgba,
    };
    write_picture(&output, &picture)?;
    println!(
        "{}: {} strands, {} time samples; wrote {}",
        input.display(),
        curves.curves.len(),
        imported.animation.as_ref().map_or(1, |a| a.frames.len()),
        output.display()
    );
    Ok(())
}
