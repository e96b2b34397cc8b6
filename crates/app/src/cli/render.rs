//! `helixhair render`: simulate a style for some frames, then draw it
//! offscreen into a PNG (or one PNG per frame with `--sequence`).
//!
//! The simulation is the headless one ([`HeadlessSim`]) on a still head,
//! colliding with it; the roots of scalp placements are grown on the head
//! first ([`crate::head::groom`]), and the drawn strands are interpolated from
//! the simulated guides. Any wgpu adapter works, Mesa's lavapipe included
//! (`WGPU_BACKEND=vulkan` on a machine without a GPU).
//!
//! When the stability guard had to reset or pin strands, the picture is
//! still written, but the summary warns and the run exits 1, as
//! `helixhair sim` does, unless `--accept-resets` accepts the result.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::Context as _;
use clap::Args;
use helixhair_render::{
    GpuContext, Light, OffscreenRenderer, OrbitCamera, RenderSettings, RgbaImage, Scene,
};

use crate::atomic_write::write_atomically;
use crate::cli::camera_arg::CameraArg;
use crate::hair::drawn::drawn_hair;
use crate::hair::guide_curves::guide_curves;
use crate::hair::layout::DrawnLayout;
use crate::sim::build::SimOverrides;
use crate::sim::grown::grown_sim;
use crate::sim::headless::HeadlessSim;
use crate::sim::report::refuse_lost_strands;

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
    /// A head mesh (OBJ) instead of the default head; styles that grow
    /// hair on the scalp need its scalp faces in a group `scalp`.
    #[arg(long, value_name = "OBJ")]
    pub head: Option<PathBuf>,
    /// The picture to write (.png, or .jpg for JPEG); with --sequence, frame N goes to OUT with `_NNNN`
    /// before the extension.
    #[arg(long, value_name = "OUT")]
    pub out: PathBuf,
    /// Write a picture of the start and of every frame (0 to K), for a
    /// video, with a progress bar.
    #[arg(long)]
    pub sequence: bool,
    /// Exit 0 even when the guard had to reset or pin strands (by default
    /// the picture is written, a warning says what happened, and the run
    /// exits 1: the picture is not the simulation that was asked for).
    #[arg(long)]
    pub accept_resets: bool,
    /// Move the head: a clip (nod, shake, turn, jerk) or a motion file
    /// (docs/motion-format.md), from the first frame; the head is drawn
    /// where it is.
    #[arg(long, value_name = "CLIP|FILE", value_parser = crate::motion::playback::parse_play)]
    pub play: Option<crate::motion::playback::Playback>,
    /// Physics engine, instead of the style's `engine`: reference, batch
    /// or gpu.
    #[arg(long, value_name = "ENGINE", value_parser = crate::sim::engine_arg::parse_engine)]
    pub engine: Option<helixhair_physics::engine::EngineKind>,
    /// Hair–hair interaction (docs/volume.md) on or off, instead of the
    /// style's `sim.interaction.enabled`; either engine.
    #[arg(long, value_name = "on|off", value_parser = crate::sim::engine_arg::parse_interaction)]
    pub interaction: Option<bool>,
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

/// The picture formats `--out` may name, by extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PictureFormat {
    /// `.png` (lossless; the default when there is no extension).
    Png,
    /// `.jpg` or `.jpeg`, quality [`JPEG_QUALITY`].
    Jpeg,
}

/// JPEG quality (1 to 100): high enough that single hairs survive.
pub const JPEG_QUALITY: u8 = 92;

/// The format `path`'s extension names; an error for any other extension,
/// so `--out x.bmp` is refused rather than written as PNG bytes.
pub fn picture_format(path: &Path) -> anyhow::Result<PictureFormat> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    match ext.as_deref() {
        None | Some("png") => Ok(PictureFormat::Png),
        Some("jpg" | "jpeg") => Ok(PictureFormat::Jpeg),
        Some(other) => anyhow::bail!(
            "--out {}: cannot write `.{other}` pictures; name a .png or .jpg file",
            path.display()
        ),
    }
}

/// Encodes `image` in the format `path`'s extension names (PNG or JPEG)
/// and writes it atomically, creating its folder.
pub fn write_picture(path: &Path, image: &RgbaImage) -> anyhow::Result<()> {
    use image::ImageEncoder as _;
    let mut bytes = Vec::new();
    match picture_format(path)? {
        PictureFormat::Png => image::codecs::png::PngEncoder::new(&mut bytes)
            .write_image(
                &image.rgba,
                image.width_px,
                image.height_px,
                image::ExtendedColorType::Rgba8,
            )
            .context("cannot encode the PNG")?,
        PictureFormat::Jpeg => {
            // JPEG has no alpha: drop it (the pictures are opaque).
            let rgb: Vec<u8> = image
                .rgba
                .chunks_exact(4)
                .flat_map(|p| [p[0], p[1], p[2]])
                .collect();
            image::codecs::jpeg::JpegEncoder::new_with_quality(&mut bytes, JPEG_QUALITY)
                .write_image(
                    &rgb,
                    image.width_px,
                    image.height_px,
                    image::ExtendedColorType::Rgb8,
                )
                .context("cannot encode the JPEG")?
        }
    }
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    write_atomically(path, &bytes).with_context(|| format!("cannot write {}", path.display()))
}

/// Runs `helixhair render`.
pub fn run_render(args: &RenderArgs, stdout: &mut dyn Write) -> anyhow::Result<()> {
    picture_format(&args.out)?;
    let style_path = args.style.display().to_string();
    let (groom, mut sim) = grown_sim(
        &args.style,
        args.head.as_deref(),
        SimOverrides {
            engine: args.engine,
            interaction: args.interaction,
            ..SimOverrides::default()
        },
    )?;
    if let Some(play) = &args.play {
        sim.play_motion(play.load()?);
    }
    let gpu = GpuContext::new_headless()?;
    let settings = RenderSettings::new(args.width, args.height);
    let mut renderer = OffscreenRenderer::new(gpu, settings)?;
    let mut camera: OrbitCamera = args.camera.camera();
    if sim.head_pivot_m() != glam::DVec3::ZERO {
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
    let layout = DrawnLayout::new(&groom, sim.engine(), usize::MAX);
    let mut frame = |sim: &HeadlessSim| -> anyhow::Result<(RgbaImage, FrameCounts, f64)> {
        let hair = drawn_hair(&groom, &layout, sim.engine());
        let pose = sim.engine().head();
        let head = groom
            .head
            .posed(pose.world_from_body.as_mat3(), pose.position_m.as_vec3());
        let scene = Scene {
            hair: &hair,
            head: &head,
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
            write_picture(&numbered_path(&args.out, k), &image)?;
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
            // Not `sum`: an empty f64 sum is -0.0, printed "-0.00 s".
            .fold(0.0, |total, secs| total + secs);
        let (image, c, secs) = frame(&sim)?;
        write_picture(&args.out, &image)?;
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
        "style `{}` ({style_path}): {} simulated strands, {}\n  \
         drew {} strands, {} points at {}x{} on {}: {timing}\n  wrote {}",
        groom.style.name,
        sim.engine().strand_count(),
        crate::sim::report::frames_simulated(args.frames as usize, sim_secs),
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
    if let Some(note) = sim.engine().gpu_note() {
        writeln!(stdout, "  {note}")?;
    }
    let handed = sim.handed_to_exact();
    if handed > 0 {
        writeln!(
            stdout,
            "  Block-diagonal could not hold this style at its time step: the guard stepped \
             {handed} strand-frame(s) with Exact instead, and that is what the picture shows \
             there (more substeps may let Block-diagonal hold it)"
        )?;
    }
    let lost = sim.strands_lost();
    if lost > 0 {
        writeln!(
            stdout,
            "  warning: the stability guard reset or pinned strands {lost} times; the picture \
             is not the simulation the style asks for"
        )?;
    }
    refuse_lost_strands(lost, args.accept_resets)
}

/// What one frame drew.
#[derive(Clone, Copy, Debug, Default)]
struct FrameCounts {
    strands: usize,
    points: usize,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grey(width_px: u32, height_px: u32) -> RgbaImage {
        RgbaImage {
            width_px,
            height_px,
            rgba: vec![128; (4 * width_px * height_px) as usize],
        }
    }

    #[test]
    fn the_out_extension_picks_the_format_and_jpg_writes_jpeg_bytes() {
        let dir = std::env::temp_dir().join(format!("helixhair-pictures-{}", std::process::id()));
        let (jpg, png) = (dir.join("x.jpg"), dir.join("x.png"));
        write_picture(&jpg, &grey(8, 4)).unwrap();
        write_picture(&png, &grey(8, 4)).unwrap();
        // JPEG starts with its SOI marker, PNG with its signature.
        assert_eq!(std::fs::read(&jpg).unwrap()[..3], [0xFF, 0xD8, 0xFF]);
        assert_eq!(std::fs::read(&png).unwrap()[..4], [0x89, b'P', b'N', b'G']);
        let decoded = image::open(&jpg).unwrap();
        assert_eq!((decoded.width(), decoded.height()), (8, 4));
        assert_eq!(
            picture_format(Path::new("a.JPEG")).unwrap(),
            PictureFormat::Jpeg
        );
        let refused = picture_format(Path::new("a.bmp")).unwrap_err().to_string();
        assert!(
            refused.contains("a.bmp") && refused.contains(".png or .jpg"),
            "{refused}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
