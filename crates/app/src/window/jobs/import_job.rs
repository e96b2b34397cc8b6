//! File → "Import groom…" and a groom dropped on the window, once the
//! import dialog has its head ([`crate::window::panels::files::import_dialog`]):
//! the same import as `helixhair import GROOM --head MESH --out STYLE` ([`import_groom`]: read,
//! fit Super-Helices, sag-free rest shape, every strand simulated), run on
//! a worker thread with a progress bar over the strands fitted (Sintel's
//! 11,400 strands take minutes on two cores). The style is written beside
//! the groom (or, where that folder is read-only, in the working folder)
//! under a name not yet taken, and then opened like any style, through the
//! unsaved-changes question.

use std::path::{Path, PathBuf};

use helixhair_formats::Format;
use helixhair_physics::fit::FitOptions;

use crate::export::check_writable;
use crate::import::command::{ImportArgs, import_groom};
use crate::import::material::MaterialArgs;

use super::job::{Job, JobDone};

/// Whether `path` names a groom the import reads (by its extension).
pub fn import_extension(path: &Path) -> bool {
    Format::from_path(path).is_some()
        && !path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("ron"))
}

/// Where the style of `groom` goes: `NAME.ron` beside it, or `NAME-2.ron`,
/// … when taken; in the working folder when the groom's folder cannot be
/// written.
pub fn style_path_for(groom: &Path) -> anyhow::Result<PathBuf> {
    let stem = groom
        .file_stem()
        .map_or_else(|| "imported".into(), |s| s.to_string_lossy().into_owned());
    let beside = groom
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .map_or_else(|| PathBuf::from("."), Path::to_owned);
    let folder = if check_writable(&beside.join("probe")).is_ok() {
        beside
    } else {
        std::env::current_dir()?
    };
    let free = (1..10_000)
        .map(|k| match k {
            1 => folder.join(format!("{stem}.ron")),
            k => folder.join(format!("{stem}-{k}.ron")),
        })
        .find(|p| !p.exists());
    free.ok_or_else(|| anyhow::anyhow!("no free style name for {stem} in {}", folder.display()))
}

/// Starts importing `groom` on `head` (a mesh file; `None`: the default
/// head), its hair colliding with `collider` (`None`: the head itself), on
/// a worker thread; the job's result is the style file written, which
/// names both meshes, so it opens on them.
pub fn start_import(
    groom: &Path,
    head: Option<PathBuf>,
    collider: Option<PathBuf>,
    material: MaterialArgs,
) -> anyhow::Result<Job<JobDone>> {
    let out = style_path_for(groom)?;
    let defaults = FitOptions::default();
    let args = ImportArgs {
        groom: groom.to_owned(),
        collider: collider.filter(|_| head.is_some()),
        head,
        fit_tolerance: defaults.tolerance_over_length,
        max_elements: defaults.max_elements,
        natural_tolerance: defaults.natural_tolerance_over_length,
        no_sag_free: false,
        no_stiffen: false,
        guides: None,
        metres_per_unit: None,
        material,
        out: out.clone(),
        json: None,
    };
    let label = format!(
        "Importing {} (fitting strands) into {}",
        groom.display(),
        out.display()
    );
    Job::spawn(label, move |progress| {
        let report = import_groom(&args, progress)?;
        Ok(JobDone::Imported(out, report.warnings))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::style::Style;
    use helixhair_formats::{Curve, CurveSet};
    use helixhair_physics::StrandParams;

    #[test]
    fn a_groom_imported_in_the_window_becomes_a_style_beside_it() {
        let dir = std::env::temp_dir().join(format!("helixhair-import-job-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let groom = dir.join("two.obj");
        let curves = CurveSet::new(
            (0..2)
                .map(|k| Curve {
                    points_m: (0..6)
                        .map(|i| glam::Vec3::new(0.02 * k as f32, -0.02 * i as f32, 0.0))
                        .collect(),
                    width_m: None,
                    colour: None,
                })
                .collect(),
        );
        let mut bytes = Vec::new();
        helixhair_formats::write(&mut bytes, Format::Obj, &curves).unwrap();
        std::fs::write(&groom, bytes).unwrap();
        std::fs::write(dir.join("two.ron"), "taken").unwrap();
        assert!(import_extension(&groom) && !import_extension(&dir.join("two.ron")));
        let job = start_import(&groom, None, None, MaterialArgs::default()).unwrap();
        let JobDone::Imported(style, _) = job.wait().unwrap() else {
            panic!("an import")
        };
        assert_eq!(style, dir.join("two-2.ron"), "the taken name is left alone");
        let loaded = Style::load(&style).unwrap();
        let imported = loaded.groups[0].imported.as_ref().unwrap();
        assert_eq!(imported.strands.len(), 2);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn the_readers_warnings_reach_the_window() {
        // Issue 32, item 11: a `.usda` without `metersPerUnit` was read in
        // centimetres and, imported in the window, nothing said so.
        let dir =
            std::env::temp_dir().join(format!("helixhair-import-warn-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let groom = dir.join("no_unit.usda");
        let layer = "#usda 1.0\n(\n    upAxis = \"Y\"\n)\n\ndef BasisCurves \"hair\"\n{\n    \
                     uniform token type = \"linear\"\n    int[] curveVertexCounts = [3]\n    \
                     point3f[] points = [(0, 0, 0), (0, -7, 0), (0, -14, 0.1)]\n}\n";
        std::fs::write(&groom, layer).unwrap();
        let JobDone::Imported(_, warnings) =
            start_import(&groom, None, None, MaterialArgs::default())
                .unwrap()
                .wait()
                .unwrap()
        else {
            panic!("an import")
        };
        assert!(
            warnings.iter().any(|w| w.contains("metersPerUnit")),
            "{warnings:?}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_groom_imported_on_the_head_beside_it_opens_on_that_head() {
        // Issue 32, item 1: imported in the window, the groom opened on the
        // bald default head with its hair 1.5 m above it.
        use crate::window::panels::files::import_dialog::ImportDialog;
        use crate::window::state::app_state::AppState;
        let dir =
            std::env::temp_dir().join(format!("helixhair-import-head-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let lift = glam::Vec3::new(0.0, 1.5, 0.0);
        let mut head = helixhair_render::head_generate::default_head();
        head.mesh.positions.iter_mut().for_each(|p| *p += lift);
        let head_obj = helixhair_render::obj::write_head_obj(&head, "bust");
        std::fs::write(dir.join("bust.obj"), head_obj).unwrap();
        let crown =
            head.mesh
                .positions
                .iter()
                .copied()
                .fold(
                    glam::Vec3::splat(f32::MIN),
                    |a, b| if b.y > a.y { b } else { a },
                );
        let curves = CurveSet::new(
            (0..3)
                .map(|k| Curve {
                    points_m: (0..6)
                        .map(|i| crown + glam::Vec3::new(0.01 * k as f32, 0.001, 0.012 * i as f32))
                        .collect(),
                    width_m: None,
                    colour: None,
                })
                .collect(),
        );
        let groom = dir.join("crown.obj");
        let mut bytes = Vec::new();
        helixhair_formats::write(&mut bytes, Format::Obj, &curves).unwrap();
        std::fs::write(&groom, bytes).unwrap();
        // The dialog offers the bust; the import uses it, and the open
        // style's material when asked.
        let mut open = StrandParams {
            density_kg_per_m3: 1100.0,
            radius_m: 40e-6,
            ..StrandParams::default()
        };
        open.youngs_modulus_pa = 3.0e9;
        let mut dialog = ImportDialog::new(&groom, Some(("open".into(), open.clone())));
        dialog.use_open_material = true;
        assert_eq!(dialog.head_path(), Some(dir.join("bust.obj")));
        let JobDone::Imported(style, _) = start_import(
            &groom,
            dialog.head_path(),
            dialog.collider_path(),
            dialog.material(),
        )
        .unwrap()
        .wait()
        .unwrap() else {
            panic!("an import")
        };
        let written = Style::load(&style).unwrap();
        let material = &written.groups[0].params;
        assert_eq!(
            (
                material.density_kg_per_m3,
                material.radius_m,
                material.youngs_modulus_pa
            ),
            (1100.0, 40e-6, 3.0e9)
        );
        let app = AppState::new(written, Some(&style)).unwrap();
        assert_eq!(
            app.head_files().map(|f| f.drawn.as_path()),
            Some(dir.join("bust.obj").as_path())
        );
        // The head pivot (which the view frames) is on the lifted head, and
        // every root sits on it, not a metre and a half above the default.
        assert!(app.head().pivot_m.y > 1.2, "pivot {}", app.head().pivot_m);
        let top = f64::from(crown.y);
        for i in 0..app.sim().engine().strand_count() {
            let root = app.sim().engine().boundary_points_world(i)[0];
            assert!((root.y - top).abs() < 0.01, "root {root} vs crown y {top}");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
