//! `helixhair import`: a groom made elsewhere (TressFX, `.hair`, USD,
//! OBJ curves) becomes a style of fitted Super-Helices (docs/import.md).
//!
//! 1. **Read** the groom with `helixhair-formats` (format from the file's
//!    extension); a malformed file is an error naming the file and the
//!    byte offset or line, and the command exits 1. Degenerate strands are
//!    repaired or skipped one by one, each reason counted.
//! 2. **Attach** each root to the head mesh (`--head`), if given
//!    ([`crate::import::roots`]).
//! 3. **Fit** every strand and solve its sag-free rest shape
//!    ([`crate::import::fit`]) for the hair's material
//!    ([`crate::import::material`]).
//! 4. **Choose guides** (`--guides K`) and **write** the style (atomically)
//!    and the JSON report ([`crate::import::report`]).

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context as _, bail};
use clap::Args;
use glam::DVec3;
use helixhair_formats::{Format, ReadOptions};
use helixhair_physics::engine::EngineKind;
use helixhair_physics::engine::RestContact;
use helixhair_physics::fit::resolution::sag_load_per_m3;
use helixhair_physics::fit::{FitOptions, StiffenOptions};
use helixhair_physics::{RigidMotion, SimSettings};

use crate::head::groom::head_collider;
use crate::import::fit::{FitJob, FitOutcome, FitSettings, fit_all};
use crate::import::material::MaterialArgs;
use crate::import::report::ImportReport;
use crate::import::roots::{attach, farthest_point_guides};
use crate::json_report::{summary_stream, write_json_report};
use crate::style::imported::ImportedStrands;
use crate::style::{DEFAULT_REFERENCE, STYLE_VERSION, StrandGroup, Style};
use crate::work_progress::WorkProgress;

/// The engine an imported style runs on: every strand of a groom
/// simulated needs the batch engine's throughput. The sag-free rest shapes
/// are solved for its contact law ([`RestContact`]).
const IMPORTED_ENGINE: EngineKind = EngineKind::Batch;

/// Largest groom file `import` reads, bytes (1 GiB): far above any public
/// groom (Sintel's is 2.9 MB), below what would exhaust a desktop's memory
/// once fitted.
pub const MAX_GROOM_BYTES: u64 = 1 << 30;

/// Arguments of `helixhair import`.
#[derive(Clone, Debug, Args)]
pub struct ImportArgs {
    /// The groom: .tfx (TressFX 3/4), .hair (Cem Yuksel), USD BasisCurves
    /// (.usda text, .usdc or .usd binary, .usdz package), Alembic curves
    /// (.abc) or .obj
    /// (polylines).
    #[arg(value_name = "GROOM")]
    pub groom: PathBuf,
    /// The head mesh (OBJ) the roots are attached to, drawn and exported
    /// with the hair, and (without `--collider`) the one the hair rests on;
    /// without it the roots are fixed in space, frames referenced to +z.
    #[arg(long, value_name = "MESH")]
    pub head: Option<PathBuf>,
    /// The mesh (OBJ) the hair collides with and rests on, when it is not
    /// `--head`: a coarse stand-in for a detailed bust, whose ears and lips
    /// would catch the hair (an open head mesh collides too: its inside
    /// comes from its winding number). Needs `--head`.
    #[arg(long, value_name = "MESH", requires = "head")]
    pub collider: Option<PathBuf>,
    /// Largest distance of a groom point from its fitted strand, as a
    /// fraction of the strand's length.
    #[arg(long, value_name = "F", default_value_t = FitOptions::default().tolerance_over_length)]
    pub fit_tolerance: f64,
    /// Most Super-Helix elements per strand (1 to 200).
    #[arg(long, value_name = "N", default_value_t = FitOptions::default().max_elements)]
    pub max_elements: usize,
    /// Largest distance of a strand's natural shape (relaxed without
    /// gravity) from the hair's, as a fraction of its length: with
    /// sag-free, strands get the elements this needs (docs/import.md,
    /// "Choosing N"). Larger is cheaper to simulate, less true.
    #[arg(long, value_name = "F", default_value_t = FitOptions::default().natural_tolerance_over_length)]
    pub natural_tolerance: f64,
    /// Keep the fitted shape as the rest shape (it then sags under
    /// gravity) instead of solving sag-free natural strains.
    #[arg(long)]
    pub no_sag_free: bool,
    /// Leave strands whose sag-free equilibrium is unstable as they are
    /// (they fall when simulated) instead of stiffening each by the least
    /// factor that holds it (as far as the moduli's valid range allows:
    /// 256× for the default hair; docs/import.md).
    #[arg(long)]
    pub no_stiffen: bool,
    /// Simulate K guide strands spread over the scalp and draw the others
    /// following them, instead of simulating every strand.
    #[arg(long, value_name = "K")]
    pub guides: Option<usize>,
    /// The groom's length unit in metres, instead of what the file
    /// declares (or its format's default: USD's is centimetres).
    #[arg(long, value_name = "M")]
    pub metres_per_unit: Option<f64>,
    /// The hair's material: the sag-free rest shape balances its weight
    /// against its stiffness ([`crate::import::material`]).
    #[command(flatten)]
    pub material: MaterialArgs,
    /// The style to write (RON).
    #[arg(long, value_name = "STYLE")]
    pub out: PathBuf,
    /// Write a JSON report to REPORT (`-`: stdout, the summary then goes to
    /// stderr).
    #[arg(long, value_name = "REPORT")]
    pub json: Option<PathBuf>,
}

/// Runs `helixhair import`.
pub fn run_import(
    args: &ImportArgs,
    stdout: &mut dyn Write,
    stderr: &mut dyn Write,
) -> anyhow::Result<()> {
    let report = import_groom(args, &WorkProgress::default())?;
    let summary_out = summary_stream(args.json.as_deref(), stdout, stderr);
    summary_out.write_all(report.summary().as_bytes())?;
    if let Some(path) = &args.json {
        write_json_report(&report, path, stdout)?;
    }
    Ok(())
}

/// Imports `args.groom` into the style `args.out` (steps 1 to 4 of the
/// module docs) and returns the report; `progress` counts the strands
/// fitted, and cancelling it stops the import before anything is written.
/// The window's File → Import groom… runs this on a worker thread.
pub fn import_groom(args: &ImportArgs, progress: &WorkProgress) -> anyhow::Result<ImportReport> {
    let started = Instant::now();
    let options = FitOptions {
        tolerance_over_length: args.fit_tolerance,
        max_elements: args.max_elements,
        natural_tolerance_over_length: args.natural_tolerance,
        ..FitOptions::default()
    };
    if !(options.tolerance_over_length > 0.0 && options.tolerance_over_length < 1.0) {
        bail!("--fit-tolerance {}: must lie in (0, 1)", args.fit_tolerance);
    }
    if !(options.natural_tolerance_over_length > 0.0 && options.natural_tolerance_over_length < 1.0)
    {
        bail!(
            "--natural-tolerance {}: must lie in (0, 1)",
            args.natural_tolerance
        );
    }
    if !(1..=helixhair_physics::params::MAX_ELEMENTS).contains(&options.max_elements) {
        bail!("--max-elements {}: must lie in 1..=200", args.max_elements);
    }
    if args.guides == Some(0) {
        bail!("--guides 0: at least one guide must be simulated");
    }
    let groom_name = args.groom.display().to_string();
    let format = Format::from_path(&args.groom).with_context(|| {
        format!(
            "{groom_name}: unknown groom format; expected .tfx, .hair, .usda, .usdc, .usd, .usdz, .abc or .obj"
        )
    })?;
    let size = std::fs::metadata(&args.groom)
        .with_context(|| format!("{groom_name}: cannot read the groom"))?
        .len();
    if size > MAX_GROOM_BYTES {
        bail!("{groom_name}: {size} bytes is more than the {MAX_GROOM_BYTES} bytes `import` reads");
    }
    let bytes = std::fs::read(&args.groom)
        .with_context(|| format!("{groom_name}: cannot read the groom"))?;
    let read_options = ReadOptions {
        metres_per_unit: args.metres_per_unit,
        ..ReadOptions::default()
    };
    let imported = helixhair_formats::read(&bytes, format, &read_options)
        .with_context(|| format!("{groom_name}: not a valid groom"))?;
    let read_secs = started.elapsed().as_secs_f64();

    let head = match &args.head {
        Some(path) => Some(helixhair_render::obj::load_mesh_obj(path)?),
        None => None,
    };
    let collider_mesh = match &args.collider {
        Some(path) => Some(helixhair_render::obj::load_mesh_obj(path)?),
        None => None,
    };
    let collider_file = args.collider.as_ref().or(args.head.as_ref());
    let collider = match (collider_mesh.as_ref().or(head.as_ref()), collider_file) {
        (Some(mesh), Some(path)) => Some(
            head_collider(mesh)
                .with_context(|| format!("{}: cannot build the collision field", path.display()))?,
        ),
        _ => None,
    };
    let attach_start = Instant::now();
    let mut jobs = Vec::with_capacity(imported.curves.curves.len());
    let mut root_distances = Vec::new();
    for curve in &imported.curves.curves {
        let points_m: Vec<DVec3> = curve.points_m.iter().map(|p| p.as_dvec3()).collect();
        let reference = match (&head, points_m.first()) {
            (Some(head), Some(root)) => match attach(head, *root) {
                Some(a) => {
                    root_distances.push(a.distance_m);
                    -a.normal
                }
                None => DEFAULT_REFERENCE,
            },
            _ => DEFAULT_REFERENCE,
        };
        jobs.push(FitJob {
            points_m,
            reference,
        });
    }
    let attach_secs = attach_start.elapsed().as_secs_f64();

    let material = args.material.params()?;
    let fit_start = Instant::now();
    let gravity_m_per_s2 = (!args.no_sag_free).then_some(SimSettings::default().gravity_m_per_s2);
    let settings = FitSettings {
        // With sag-free, enough elements for the natural shape too.
        options: FitOptions {
            sag_load_per_m3: gravity_m_per_s2
                .map_or(DVec3::ZERO, |gravity| sag_load_per_m3(&material, gravity)),
            ..options
        },
        material: &material,
        gravity_m_per_s2,
        support: collider.as_ref().map(|collider| {
            RestContact::for_engine(&SimSettings::default(), collider, RigidMotion::default())
        }),
        stiffen: if args.no_stiffen {
            StiffenOptions::none()
        } else {
            StiffenOptions::for_material(&material)
        },
    };
    let outcomes = fit_all(&jobs, &settings, progress);
    if progress.cancelled() {
        bail!("{groom_name}: import cancelled; no style was written");
    }
    let fit_secs = fit_start.elapsed().as_secs_f64();

    let mut report = ImportReport::new(&groom_name, format, &imported.summary, &outcomes);
    report.root_distance_to_head_m = crate::import::report::Spread::of(&root_distances);
    report.warnings = imported.warnings.clone();
    let mut strands: Vec<_> = outcomes
        .into_iter()
        .filter_map(|o| match o {
            FitOutcome::Fitted { strand, .. } => Some(strand),
            FitOutcome::Skipped(_) => None,
        })
        .collect();
    if strands.is_empty() {
        // The reader's warnings often say why (a unit read as centimetres
        // makes every strand a kink too tight to fit).
        let warnings: String = report
            .warnings
            .iter()
            .map(|w| format!("\n  warning: {w}"))
            .collect();
        bail!(
            "{groom_name}: no strand could be imported (see the skipped counts: {:?}){warnings}",
            report.skipped
        );
    }
    if let Some(k) = args.guides {
        let roots: Vec<DVec3> = strands.iter().map(|s| s.root.position_m).collect();
        let chosen = farthest_point_guides(&roots, k);
        for s in &mut strands {
            s.guide = false;
        }
        for i in chosen {
            strands[i].guide = true;
        }
    }
    report.guides = strands.iter().filter(|s| s.guide).count();

    let style = Style {
        version: STYLE_VERSION,
        name: args.groom.file_stem().map_or_else(
            || "imported".to_owned(),
            |s| s.to_string_lossy().into_owned(),
        ),
        sim: SimSettings::default(),
        engine: IMPORTED_ENGINE,
        accuracy_target: None,
        groups: vec![StrandGroup {
            name: "imported".to_owned(),
            params: material,
            roots: Vec::new(),
            scalp: None,
            render: None,
            imported: Some(ImportedStrands {
                source: relative_to_style(&args.groom, &args.out),
                head: args
                    .head
                    .as_deref()
                    .map(|h| relative_to_style(h, &args.out)),
                collider: args
                    .collider
                    .as_deref()
                    .map(|c| relative_to_style(c, &args.out)),
                strands,
            }),
            edits: Vec::new(),
        }],
    };
    let write_start = Instant::now();
    if let Some(dir) = args.out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    style.save(&args.out)?;
    report.timings.read_secs = read_secs;
    report.timings.attach_secs = attach_secs;
    report.timings.fit_secs = fit_secs;
    report.timings.write_secs = write_start.elapsed().as_secs_f64();
    report.timings.total_secs = started.elapsed().as_secs_f64();
    report.style = args.out.display().to_string();
    Ok(report)
}

/// `target` as a path relative to `style`'s folder (absolute when the two
/// share nothing, e.g. different drives).
pub fn relative_to_style(target: &Path, style: &Path) -> String {
    let absolute = |p: &Path| std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf());
    let target = absolute(target);
    let folder = absolute(style);
    let folder = folder.parent().unwrap_or(Path::new("/"));
    let t: Vec<_> = target.components().collect();
    let f: Vec<_> = folder.components().collect();
    let common = t.iter().zip(&f).take_while(|(a, b)| a == b).count();
    if common == 0 {
        return target.display().to_string();
    }
    let mut out = PathBuf::new();
    for _ in common..f.len() {
        out.push("..");
    }
    for c in &t[common..] {
        out.push(c);
    }
    out.display().to_string()
}
