//! Hair out of HelixHair: simulated or drawn strands as curve files, one
//! frame or an animation, through `helixhair-formats`.
//!
//! # How it works
//!
//! 1. **Capture** ([`capture_curves`]): after a frame, each strand becomes
//!    a polyline of `points_per_strand` points. Simulated strands are
//!    sampled evenly along their helices ([`crate::hair::sampling`]),
//!    with their fibre diameter (2 × `radius_m`) as width. Drawn strands
//!    are what the renderer draws ([`crate::hair::drawn`]: interpolated
//!    from the simulated guides, coloured, draped over the head),
//!    resampled evenly by arc length, with the renderer's tapered ribbon
//!    width per point and their colour.
//! 2. **Collect** ([`ExportRecorder`]): USD (`.usda` text, `.usdc` or
//!    `.usd` binary, `.usdz` package) keeps every frame as a time sample
//!    (time code = frame number, `timeCodesPerSecond` = 1 / `dt`), the
//!    head as a `Mesh` that moves with the head's motion; Alembic (`.abc`)
//!    the same as samples of its curves' points and of the head's `Xform`;
//!    `.hair`, `.tfx` and `.obj` hold one frame, so an animation becomes a
//!    numbered sequence `name.0000.hair` (the start), `name.0001.hair`, …,
//!    each file written as soon as its frame is captured.
//! 3. **Write**: every file is encoded whole in memory by the format's
//!    writer (which checks everything before writing a byte), then
//!    replaced atomically ([`crate::atomic_write`]): a full disk, a kill or
//!    a bad folder leaves the old file or none under the final name, never
//!    a part. Missing parent folders are created; [`check_writable`] tries
//!    the folder before a long simulation, so a typo fails in a second.

pub mod command;

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use glam::Vec3;
use helixhair_formats::{
    Animation, Curve, CurveSet, Format, Frame, MeshPose, StrandValue, TriangleMesh, WriteError,
    write_abc, write_usda_with_head_poses, write_usdc, write_usdz,
};
use helixhair_physics::engine::Engine;
use helixhair_render::HeadMesh;
use helixhair_render::interpolate::resampled_shape;

use crate::atomic_write::write_atomically;
use crate::hair::drawn::drawn_hair_full;
use crate::hair::sampling::{MIN_POINTS_PER_STRAND, sample_strand};
use crate::head::groom::Groom;

/// Points per exported strand unless told otherwise: a power of two that
/// TressFX accepts, about ten points per turn of the example curls.
pub const DEFAULT_POINTS_PER_STRAND: usize = 32;

/// Most points per exported strand (`.hair` allows 65,536; more than this
/// only makes files larger than any renderer needs).
pub const MAX_POINTS_PER_STRAND: usize = 4096;

/// Which strands go into the file.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum StrandChoice {
    /// The simulated strands (guides), sampled along their helices.
    #[default]
    Simulated,
    /// Every drawn strand, as `helixhair render` draws it.
    Drawn,
}

/// Which frames go into the file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum FrameChoice {
    /// The start and every simulated frame: USD time samples, or a
    /// numbered sequence for the one-frame formats.
    All,
    /// Only the state after the last frame.
    Last,
}

/// What to export and where.
#[derive(Clone, Debug, PartialEq)]
pub struct ExportSpec {
    /// The file (for a sequence, the name the numbers go into).
    pub path: PathBuf,
    /// The format, from the file's extension.
    pub format: Format,
    /// Simulated or drawn strands.
    pub strands: StrandChoice,
    /// Points on every strand.
    pub points_per_strand: usize,
    /// Every frame or the last.
    pub frames: FrameChoice,
    /// Whether a USD file (`.usda`, `.usdc`, `.usd`, `.usdz`) or an
    /// Alembic `.abc` gets the head as a mesh.
    pub head: bool,
}

impl ExportSpec {
    /// A spec for `path`, its format from the extension; refuses unknown
    /// extensions and point counts the format cannot hold before anything
    /// is simulated.
    pub fn new(
        path: &Path,
        strands: StrandChoice,
        points_per_strand: usize,
        frames: FrameChoice,
        head: bool,
    ) -> anyhow::Result<ExportSpec> {
        let names: Vec<String> = Format::EXTENSIONS.iter().map(|e| format!(".{e}")).collect();
        let format = Format::from_path(path).with_context(|| {
            format!(
                "{}: unknown export format; the extension picks one of {}",
                path.display(),
                names.join(", ")
            )
        })?;
        if !(MIN_POINTS_PER_STRAND..=MAX_POINTS_PER_STRAND).contains(&points_per_strand) {
            anyhow::bail!(
                "--points-per-strand {points_per_strand}: must be {MIN_POINTS_PER_STRAND} to \
                 {MAX_POINTS_PER_STRAND}"
            );
        }
        if format == Format::Tfx
            && !(points_per_strand.is_power_of_two() && (4..=64).contains(&points_per_strand))
        {
            anyhow::bail!(
                "--points-per-strand {points_per_strand}: TressFX (.tfx) needs a power of two \
                 from 4 to 64 points per strand (e.g. 16, 32 or 64)"
            );
        }
        Ok(ExportSpec {
            path: path.to_owned(),
            format,
            strands,
            points_per_strand,
            frames,
            head,
        })
    }

    /// Whether the export is several frames in one file (USD, Alembic) or a
    /// numbered sequence.
    pub fn animated(&self, steps: usize) -> bool {
        self.frames == FrameChoice::All && steps > 0
    }

    /// Whether a head mesh is written (USD only).
    pub fn writes_head(&self) -> bool {
        self.head && self.format.holds_animation()
    }
}

/// `path` with a four-digit frame number before its extension:
/// `out/curly.hair`, 7 → `out/curly.0007.hair`.
pub fn sequence_path(path: &Path, frame: usize) -> PathBuf {
    let stem = path
        .file_stem()
        .map_or_else(|| "hair".into(), |s| s.to_string_lossy());
    let ext = path
        .extension()
        .map_or_else(String::new, |e| format!(".{}", e.to_string_lossy()));
    path.with_file_name(format!("{stem}.{frame:04}{ext}"))
}

/// Creates `path`'s folder if missing and checks a file can be created in
/// it (then removes that file), so a bad or unwritable folder is reported
/// before a long simulation.
pub fn check_writable(path: &Path) -> anyhow::Result<()> {
    if path.file_name().is_none() || path.as_os_str().to_string_lossy().ends_with('/') {
        anyhow::bail!("{}: the export path names no file", path.display());
    }
    let dir = match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir,
        _ => Path::new("."),
    };
    std::fs::create_dir_all(dir)
        .with_context(|| format!("cannot create the folder {} for the export", dir.display()))?;
    if path.is_dir() {
        anyhow::bail!("{}: is a folder, not a file to export to", path.display());
    }
    let probe = dir.join(format!(".helixhair-export-probe-{}", std::process::id()));
    std::fs::File::create(&probe)
        .with_context(|| format!("cannot write in {} (the export's folder)", dir.display()))?;
    // The probe file was just created; failing to remove it changes nothing.
    let _ = std::fs::remove_file(&probe);
    Ok(())
}

/// The head as the formats crate's plain mesh.
pub fn head_triangle_mesh(head: &HeadMesh) -> TriangleMesh {
    TriangleMesh {
        vertices_m: head.mesh.positions.clone(),
        triangles: head
            .mesh
            .indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]])
            .collect(),
    }
}

/// The strands of `engine`'s current state as curves: simulated strands
/// sampled along their helices, or (with `groom`, which [`StrandChoice::Drawn`]
/// needs) the drawn strands.
pub fn capture_curves(
    engine: &Engine,
    groom: Option<&Groom>,
    strands: StrandChoice,
    points_per_strand: usize,
) -> anyhow::Result<CurveSet> {
    let n = points_per_strand.max(MIN_POINTS_PER_STRAND);
    let curves = match strands {
        StrandChoice::Simulated => (0..engine.strand_count())
            .map(|i| Curve {
                points_m: sample_strand(engine, i, n),
                width_m: Some(StrandValue::PerStrand(
                    (2.0 * engine.strand_model(i).params.radius_m) as f32,
                )),
                colour: None,
            })
            .collect(),
        StrandChoice::Drawn => {
            let groom = groom.context("drawn strands need the style grown on a head")?;
            let hair = drawn_hair_full(groom, engine);
            let taper = |k: usize| {
                let t = k as f32 / (n - 1) as f32;
                hair.root_width_m + (hair.tip_width_m - hair.root_width_m) * t
            };
            hair.strands
                .iter()
                .zip(&hair.colours)
                .map(|(strand, colour)| {
                    let root = strand.first().copied().unwrap_or(Vec3::ZERO);
                    Curve {
                        points_m: resampled_shape(strand, n)
                            .into_iter()
                            .map(|offset| root + offset)
                            .collect(),
                        width_m: Some(StrandValue::PerPoint((0..n).map(taper).collect())),
                        colour: Some(StrandValue::PerStrand(colour.to_array())),
                    }
                })
                .collect()
        }
    };
    Ok(CurveSet::new(curves))
}

/// The head's pose in `engine` now, as a mesh pose at `time_code`.
fn head_pose(engine: &Engine, time_code: f64) -> MeshPose {
    let head = engine.head();
    MeshPose {
        time_code,
        rotation: head.world_from_body,
        translation_m: head.position_m,
    }
}

/// Whether a head pose is the rest pose (a still head needs no
/// transform in the file).
fn is_rest(pose: &MeshPose) -> bool {
    pose.rotation == glam::DMat3::IDENTITY && pose.translation_m == glam::DVec3::ZERO
}

/// Frames captured for one export, written as they come (sequences) or at
/// the end (`.usda`, the last frame).
#[derive(Debug)]
pub struct ExportRecorder {
    spec: ExportSpec,
    dt_secs: f64,
    first: Option<CurveSet>,
    frames: Vec<Frame>,
    head_poses: Vec<MeshPose>,
    written: Vec<PathBuf>,
    bytes: u64,
}

impl ExportRecorder {
    /// A recorder for `spec`, whose frames are `dt_secs` apart.
    pub fn new(spec: ExportSpec, dt_secs: f64) -> ExportRecorder {
        ExportRecorder {
            spec,
            dt_secs,
            first: None,
            frames: Vec::new(),
            head_poses: Vec::new(),
            written: Vec::new(),
            bytes: 0,
        }
    }

    /// The spec.
    pub fn spec(&self) -> &ExportSpec {
        &self.spec
    }

    /// The strands of `engine` now, as the spec asks.
    fn curves_now(&self, engine: &Engine, groom: Option<&Groom>) -> anyhow::Result<CurveSet> {
        capture_curves(
            engine,
            groom,
            self.spec.strands,
            self.spec.points_per_strand,
        )
    }

    /// Captures frame `frame` (0: the start) of an animation: a time sample
    /// for USD and Alembic, or the next file of a numbered sequence, written now.
    pub fn capture(
        &mut self,
        engine: &Engine,
        groom: Option<&Groom>,
        frame: usize,
    ) -> anyhow::Result<()> {
        let curves = self.curves_now(engine, groom)?;
        let time_code = frame as f64;
        self.head_poses.push(head_pose(engine, time_code));
        if self.spec.format.holds_animation() {
            self.frames.push(Frame::from_curves(time_code, &curves));
            if self.first.is_none() {
                self.first = Some(curves);
            }
            return Ok(());
        }
        let path = sequence_path(&self.spec.path, frame);
        self.write_one(&path, &curves)
    }

    /// Writes the state of `engine` as the one frame of the export (no
    /// time samples, no sequence number).
    pub fn write_single(
        &mut self,
        engine: &Engine,
        groom: Option<&Groom>,
        head: Option<&TriangleMesh>,
    ) -> anyhow::Result<()> {
        let curves = self.curves_now(engine, groom)?;
        let path = self.spec.path.clone();
        if !self.spec.format.holds_animation() {
            return self.write_one(&path, &curves);
        }
        let pose = head_pose(engine, 0.0);
        let poses = if !is_rest(&pose) && head.is_some() {
            vec![pose]
        } else {
            Vec::new()
        };
        // No frames, but the rate: readers then agree with the animations
        // this program writes (60 time codes per second at 60 Hz), not
        // USD's fallback of 24.
        let rate = Animation {
            time_codes_per_second: 1.0 / self.dt_secs,
            frames: Vec::new(),
        };
        self.write_usd(&path, &curves, Some(&rate), head, &poses)
    }

    /// Writes the collected USD or Alembic animation (nothing to do for a
    /// sequence, whose files are written as captured); returns the files
    /// written and their total size in bytes.
    pub fn finish(mut self, head: Option<&TriangleMesh>) -> anyhow::Result<(Vec<PathBuf>, u64)> {
        if let Some(curves) = self.first.take() {
            let animation = Animation {
                time_codes_per_second: 1.0 / self.dt_secs,
                frames: std::mem::take(&mut self.frames),
            };
            let still = self.head_poses.iter().all(is_rest);
            let poses = if still || head.is_none() {
                Vec::new()
            } else {
                std::mem::take(&mut self.head_poses)
            };
            let path = self.spec.path.clone();
            self.write_usd(&path, &curves, Some(&animation), head, &poses)?;
        }
        Ok((self.written, self.bytes))
    }

    /// Removes the files written so far (a cancelled or failed sequence);
    /// a file that cannot be removed is left, as it is whole.
    pub fn discard(self) {
        for path in &self.written {
            let _ = std::fs::remove_file(path);
        }
    }

    /// Writes one USD layer (text, crate file or package) or Alembic
    /// archive, as the spec's format says, with its frames, head and head
    /// poses.
    fn write_usd(
        &mut self,
        path: &Path,
        curves: &CurveSet,
        animation: Option<&Animation>,
        head: Option<&TriangleMesh>,
        poses: &[MeshPose],
    ) -> anyhow::Result<()> {
        let format = self.spec.format;
        self.encode_and_save(path, |bytes| match format {
            Format::Usdc => write_usdc(bytes, curves, animation, head, poses),
            Format::Usdz => write_usdz(bytes, curves, animation, head, poses),
            Format::Abc => write_abc(bytes, curves, animation, head, poses),
            _ => write_usda_with_head_poses(bytes, curves, animation, head, poses),
        })
    }

    fn write_one(&mut self, path: &Path, curves: &CurveSet) -> anyhow::Result<()> {
        let format = self.spec.format;
        self.encode_and_save(path, |bytes| {
            helixhair_formats::write(bytes, format, curves)
        })
    }

    /// Encodes the whole file in memory (the writer checks everything
    /// first), then saves it.
    fn encode_and_save(
        &mut self,
        path: &Path,
        encode: impl FnOnce(&mut Vec<u8>) -> Result<(), WriteError>,
    ) -> anyhow::Result<()> {
        let mut bytes = Vec::new();
        encode(&mut bytes).with_context(|| format!("cannot export {}", path.display()))?;
        self.save(path, &bytes)
    }

    fn save(&mut self, path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir)
                .with_context(|| format!("cannot create the folder {}", dir.display()))?;
        }
        write_atomically(path, bytes).with_context(|| {
            format!(
                "cannot write {} ({} bytes; a file already there is left as it was)",
                path.display(),
                bytes.len()
            )
        })?;
        self.written.push(path.to_owned());
        self.bytes += bytes.len() as u64;
        Ok(())
    }
}

/// The extent (lowest and highest corner, metres) a `.usda` this module
/// wrote gives its head mesh (`def Mesh "head"`), at rest; `None` without
/// a head. Tests use it to check which head an export carries.
pub fn usda_head_extent(text: &str) -> Option<(glam::DVec3, glam::DVec3)> {
    let head = &text[text.find("def Mesh \"head\"")?..];
    let list = head[head.find("extent = [")? + "extent = [".len()..]
        .split(']')
        .next()?;
    let numbers: Vec<f64> = list
        .split(|c: char| "(), ".contains(c))
        .filter(|s| !s.is_empty())
        .map(str::parse)
        .collect::<Result<_, _>>()
        .ok()?;
    match numbers[..] {
        [a, b, c, d, e, f] => Some((glam::DVec3::new(a, b, c), glam::DVec3::new(d, e, f))),
        _ => None,
    }
}
