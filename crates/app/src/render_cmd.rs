//! `helixhair render`: simulate a style for some frames, then draw it
//! offscreen into a PNG (or one PNG per frame with `--sequence`).
//!
//! The simulation is the headless one ([`HeadlessSim`]) on a still head,
//! colliding with it; the roots of scalp placements are grown on the head
//! first ([`crate::groom`]), and the drawn strands are interpolated from
//! the simulated guides. Any wgpu adapter works, Mesa's lavapipe included
//! (`WGPU_BACKEND=vulkan` on a machine without a GPU).

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

use anyhow::Context as _;
use clap::Args;
use helixhair_render::head_generate::default_head;
use helixhair_render::obj::load_head_obj;
use helixhair_render::{
    GpuContext, HeadMesh, Light, OffscreenRenderer, OrbitCamera, RenderSettings, RgbaImage, Scene,
};

use crate::atomic_write::write_atomically;
use crate::camera_arg::CameraArg;
use crate::drawn_hair::drawn_hair;
use crate::field_path::FieldPath;
use crate::groom::Groom;
use crate::guide_curves::guide_curves;
use crate::headless::{HeadlessSim, SimOverrides};
use crate::source_map::SourceMap;
use crate::style::Style;
use crate::style_error::{StyleError, StyleErrorKind};

/// Largest picture side, pixels.
pub const MAX_SIDE_PX: u32 = 8192;

/// Arguments of `helixhair render`.
#[derive(Clone, Debug, Args)]
pub struct RenderArgs {
    /// The style file (RON; see docs/style-format.md).
    #[arg(long, value_name = "FILE")]
    pub style: PathBuf,
    /// Frames to simulate before the picture (0: the style's natural shape).
    #[arg(long, value_name = "K", default_value_t = 60,
          value_parser = clap::value_parser!(u32).range(0..=100_000))]
    pub frames: u32,
    /// The view: front, side, back, three-quarter (the default), or
    /// YAW,PITCH,DISTANCE in degrees, degrees and metres.
    #[arg(long, value_name = "VIEW", default_value = "three-quarter")]
    pub camera: CameraArg,
    /// Picture width, pixels.
    #[arg(long, value_name = "PX", default_value_t = 1280,
          value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_SIDE_PX)))]
    pub width: u32,
    /// Picture height, pixels.
    #[arg(long, value_name = "PX", default_value_t = 720,
          value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_SIDE_PX)))]
    pub height: u32,
    /// A head mesh (OBJ, with the scalp faces in a group `scalp`) instead
    /// of the default head.
    #[arg(long, value_name = "OBJ")]
    pub head: Option<PathBuf>,
    /// The PNG to write; with --sequence, frame N goes to OUT with `_NNNN`
    /// before the extension.
    #[arg(long, value_name = "OUT")]
    pub out: PathBuf,
    /// Write a picture of the start and of every frame (0 to K), for a
    /// video, with a progress bar.
    #[arg(long)]
    pub sequence: bool,
}

/// The head to grow hair on: `path`'s OBJ, or the default head.
pub fn load_head(path: Option<&Path>) -> anyhow::Result<HeadMesh> {
    match path {
        // An OBJ error names the file and line: no context to add.
        Some(path) => Ok(load_head_obj(path)?),
        None => Ok(default_head()),
    }
}

/// `out` with `_NNNN` (frame number, four digits at least) before its
/// extension.
pub fn numbered_path(out: &Path, frame: u32) -> PathBuf {
    let stem = out
        .file_stem()
        .map_or_else(|| "frame".into(), |s| s.to_string_lossy());
    let ext = out
        .extension()
        .map_or_else(|| "png".into(), |e| e.to_string_lossy());
    out.with_file_name(format!("{stem}_{frame:04}.{ext}"))
}

/// Encodes `image` as PNG and writes it atomically, creating its folder.
pub fn write_png(path: &Path, image: &RgbaImage) -> anyhow::Result<()> {
    use image::ImageEncoder as _;
    let mut bytes = Vec::new();
    image::codecs::png::PngEncoder::new(&mut bytes)
        .write_image(
            &image.rgba,
            image.width_px,
            image.height_px,
            image::ExtendedColorType::Rgba8,
        )
        .context("cannot encode the PNG")?;
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    write_atomically(path, &bytes).with_context(|| format!("cannot write {}", path.display()))
}

/// Refuses a scalp placement that found no scalp to grow on (a `region`
/// that misses the head's scalp), naming the style's file, line and field
/// as a style error does.
fn check_placements(groom: &Groom, style_path: &Path, head: Option<&Path>) -> anyhow::Result<()> {
    let head = head.map_or_else(
        || "the default head".to_owned(),
        |p| p.display().to_string(),
    );
    for (i, (group, grown)) in groom.groups().enumerate() {
        let Some(scalp) = &group.scalp else { continue };
        if grown.roots.len() > group.roots.len() {
            continue;
        }
        let at = FieldPath::root().field("groups").index(i).field("scalp");
        let field = if scalp.region.is_some() {
            at.field("region")
        } else {
            at
        };
        // The file was just read; if it has gone since, report without a line.
        let src = std::fs::read_to_string(style_path).unwrap_or_default();
        let (position, field) = SourceMap::new(&src).locate(&field);
        return Err(StyleError::Located {
            path: style_path.to_owned(),
            position,
            field,
            kind: StyleErrorKind::InvalidValue,
            message: format!("places no roots: it covers none of the scalp of {head}"),
        }
        .into());
    }
    Ok(())
}

/// Runs `helixhair render`.
pub fn run_render(args: &RenderArgs, stdout: &mut dyn Write) -> anyhow::Result<()> {
    let style = Style::load(&args.style)?;
    let style_path = args.style.display().to_string();
    // A style that grows no hair on the scalp (an imported groom brings its
    // own roots) accepts any mesh as its head, `scalp` group or not.
    let head = match args.head.as_deref() {
        Some(path) if !crate::groom::needs_head(&style) => {
            helixhair_render::obj::load_mesh_obj(path)?
        }
        path => load_head(path)?,
    };
    let groom = Groom::new(style, head);
    check_placements(&groom, &args.style, args.head.as_deref())?;
    let mut sim = HeadlessSim::new(&groom.grown, SimOverrides::default())
        .with_context(|| format!("cannot simulate {style_path}"))?;
    let collider = groom
        .collider()
        .context("cannot build the head's collision field")?;
    sim.engine_mut().set_collider(Some(Arc::new(collider)));
    let gpu = GpuContext::new_headless()?;
    let settings = RenderSettings::new(args.width, args.height);
    let mut renderer = OffscreenRenderer::new(gpu, settings)?;
    let mut camera: OrbitCamera = args.camera.camera();
    if args.head.is_some() && !crate::groom::needs_head(&groom.style) {
        // An imported groom's head need not sit at the origin (Sintel's
        // bust stands 1.4 m up): aim at the middle of its hair instead.
        let hair = guide_curves(sim.engine());
        let (lo, hi) = hair.points.iter().fold(
            (glam::Vec3::splat(f32::MAX), glam::Vec3::splat(f32::MIN)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        if lo.x <= hi.x {
            camera.target_m = 0.5 * (lo + hi);
        }
    }
    let mut frame = |sim: &HeadlessSim| -> anyhow::Result<(RgbaImage, FrameCounts, f64)> {
        let hair = drawn_hair(&groom, &guide_curves(sim.engine()));
        let scene = Scene {
            hair: &hair,
            head: &groom.head,
            camera,
            light: Light::default(),
        };
        let start = Instant::now();
        let image = renderer.render(&scene)?;
        let counts = FrameCounts {
            strands: hair.strands.strand_count(),
            points: hair.point_count(),
        };
        Ok((image, counts, start.elapsed().as_secs_f64()))
    };

    let mut sim_secs = 0.0;
    let mut render_secs = Vec::new();
    let mut counts = FrameCounts::default();
    if args.sequence {
        let bar = indicatif::ProgressBar::new(u64::from(args.frames) + 1);
        for k in 0..=args.frames {
            if k > 0 {
                sim_secs += sim
                    .run(1)
                    .with_context(|| format!("simulating {style_path}"))?[0];
            }
            let (image, c, secs) = frame(&sim)?;
            write_png(&numbered_path(&args.out, k), &image)?;
            counts = c;
            render_secs.push(secs);
            bar.inc(1);
        }
        bar.finish_and_clear();
    } else {
        let steps = usize::try_from(args.frames).context("--frames does not fit this machine")?;
        sim_secs = sim
            .run(steps)
            .with_context(|| format!("simulating {style_path}"))?
            .iter()
            .sum();
        let (image, c, secs) = frame(&sim)?;
        write_png(&args.out, &image)?;
        (counts, render_secs) = (c, vec![secs]);
    }
    // The first frame also compiles the shaders; later ones show the
    // steady cost.
    let timing = match render_secs[..] {
        [first, ref later @ ..] if !later.is_empty() => format!(
            "{:.0} ms per frame (first frame {:.0} ms)",
            1e3 * later.iter().sum::<f64>() / later.len() as f64,
            1e3 * first
        ),
        _ => format!("{:.0} ms", 1e3 * render_secs.iter().sum::<f64>()),
    };
    writeln!(
        stdout,
        "style `{}` ({style_path}): {} simulated strands, {} frames in {sim_secs:.2} s\n  \
         drew {} strands, {} points at {}x{} on {}: {timing}\n  wrote {}",
        groom.style.name,
        sim.engine().strand_count(),
        args.frames,
        counts.strands,
        counts.points,
        args.width,
        args.height,
        renderer.adapter_label(),
        if args.sequence {
            format!(
                "{} pictures as {} (the start, then every frame)",
                render_secs.len(),
                numbered_path(&args.out, 0).display()
            )
        } else {
            args.out.display().to_string()
        },
    )?;
    Ok(())
}

/// What one frame drew.
#[derive(Clone, Copy, Debug, Default)]
struct FrameCounts {
    strands: usize,
    points: usize,
}
