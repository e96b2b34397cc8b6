//! The import dialog of File → "Import groom…" (and a groom dropped on the
//! window): which head the groom was made on. A groom's strands are placed
//! on the head they were groomed on, often far from the origin (Sintel's
//! hair stands 1.5 m up); imported on the bald default head, it would hang
//! in the air. The dialog asks for two meshes, each among those beside
//! the groom (OBJ files with faces), a typed path, or none:
//!
//! - the head drawn, on which the roots are placed and which exports carry
//!   (preselected: the first mesh whose name does not say "collider");
//! - the mesh the hair collides with and rests on (preselected: the first
//!   "collider"; none: the drawn head). A detailed bust has eye holes,
//!   lips and ears that catch hair; a coarse closed collider rests it.
//!
//! And, when a style is open, whether the hair is made of its material
//! (its first group's radius, density and moduli): the sag-free rest shape
//! balances the hair's weight against its stiffness
//! ([`crate::import::material`]). Off, the default fibre.

use std::path::{Path, PathBuf};

use helixhair_physics::StrandParams;

use crate::import::material::MaterialArgs;
use crate::style::Style;

/// The import dialog's fields.
#[derive(Clone, Debug)]
pub struct ImportDialog {
    /// The groom to import.
    pub groom: PathBuf,
    /// The meshes found beside it.
    pub beside: Vec<PathBuf>,
    /// The head mesh drawn, as typed or picked (empty: the default head).
    pub head: String,
    /// The mesh the hair collides with, as typed or picked (empty: the
    /// drawn head).
    pub collider: String,
    /// The open style's name and first group's parameters, whose material
    /// the hair may take.
    pub open_material: Option<(String, StrandParams)>,
    /// Whether the hair takes [`ImportDialog::open_material`].
    pub use_open_material: bool,
}

impl ImportDialog {
    /// A dialog for `groom`, its meshes preselected from those beside it:
    /// the first that is not a collider drawn, the first collider (a name
    /// with "collider") collided with.
    pub fn new(groom: &Path, open_material: Option<(String, StrandParams)>) -> Self {
        let beside = head_meshes_beside(groom);
        let text = |p: Option<&PathBuf>| p.map(|p| p.display().to_string()).unwrap_or_default();
        let collider = beside.iter().find(|p| is_collider(p));
        let drawn = beside.iter().find(|p| !is_collider(p)).or(collider);
        Self {
            groom: groom.to_owned(),
            head: text(drawn),
            collider: text(collider.filter(|&c| Some(c) != drawn)),
            beside,
            open_material,
            use_open_material: false,
        }
    }

    /// The material chosen: the open style's, or the default fibre.
    pub fn material(&self) -> MaterialArgs {
        MaterialArgs {
            from_params: self
                .open_material
                .as_ref()
                .filter(|_| self.use_open_material)
                .map(|(_, params)| Box::new(params.clone())),
            ..MaterialArgs::default()
        }
    }

    /// The head chosen: `None` for the default head.
    pub fn head_path(&self) -> Option<PathBuf> {
        let typed = self.head.trim();
        (!typed.is_empty()).then(|| PathBuf::from(typed))
    }

    /// The collider chosen: `None` for the drawn head (and always with the
    /// default head, which is its own collider).
    pub fn collider_path(&self) -> Option<PathBuf> {
        let typed = self.collider.trim();
        let head = self.head_path()?;
        (!typed.is_empty() && Path::new(typed) != head).then(|| PathBuf::from(typed))
    }
}

/// The material an import may take from the open `style`: its name and
/// its first group's parameters (`None` without groups).
pub fn open_material(style: &Style) -> Option<(String, StrandParams)> {
    let group = style.groups.first()?;
    Some((style.name.clone(), group.params.clone()))
}

/// Whether `mesh`'s file name says it is a collider.
fn is_collider(mesh: &Path) -> bool {
    mesh.file_name()
        .is_some_and(|n| n.to_string_lossy().to_lowercase().contains("collider"))
}

/// The OBJ meshes with faces in `groom`'s folder (not the groom itself),
/// colliders first (a name with "collider"), then by name.
pub fn head_meshes_beside(groom: &Path) -> Vec<PathBuf> {
    let folder = groom
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let Ok(entries) = std::fs::read_dir(folder) else {
        return Vec::new();
    };
    let mut meshes: Vec<PathBuf> = entries
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            p.extension().is_some_and(|e| e.eq_ignore_ascii_case("obj"))
                && p.file_name() != groom.file_name()
                && has_faces(p)
        })
        .collect();
    meshes.sort_by_key(|p| (!is_collider(p), p.clone()));
    meshes
}

/// Whether the OBJ file at `path` has a face (`f` line): a mesh, not a
/// curve groom.
fn has_faces(path: &Path) -> bool {
    std::fs::read_to_string(path)
        .map(|text| text.lines().any(|l| l.trim_start().starts_with("f ")))
        .unwrap_or(false)
}

/// What the user did in the dialog this frame.
pub enum ImportAnswer {
    /// Nothing yet.
    Stay,
    /// Closed it.
    Cancel,
    /// Asked to import.
    Go,
}

/// Draws the dialog (modal: the rest of the window waits behind it).
pub fn import_dialog(ctx: &egui::Context, dialog: &mut ImportDialog) -> ImportAnswer {
    let mut answer = ImportAnswer::Stay;
    let modal = egui::Modal::new(egui::Id::unique("import groom")).show(ctx, |ui| {
        ui.heading("Import groom");
        ui.label(format!("groom: {}", dialog.groom.display()));
        ui.label("head it was groomed on (the roots are placed on it; it is drawn and exported):");
        mesh_choice(
            ui,
            "head",
            &dialog.beside,
            &mut dialog.head,
            "the default head",
        );
        ui.separator();
        ui.label("mesh the hair collides with and rests on (a coarse closed one rests it best):");
        ui.add_enabled_ui(dialog.head_path().is_some(), |ui| {
            let beside = &dialog.beside;
            mesh_choice(
                ui,
                "collider",
                beside,
                &mut dialog.collider,
                "the head above",
            );
        });
        if let Some((name, params)) = &dialog.open_material {
            ui.separator();
            let label = format!(
                "hair made of the material of `{name}` ({:.0} µm, {:.0} kg/m³, E {:.2e} Pa); \
                 off: the default fibre",
                params.radius_m * 1e6,
                params.density_kg_per_m3,
                params.youngs_modulus_pa
            );
            ui.checkbox(&mut dialog.use_open_material, label);
        }
        ui.horizontal(|ui| {
            let enter = ui.input(|i| i.key_pressed(egui::Key::Enter));
            if ui.button("Import").clicked() || enter {
                answer = ImportAnswer::Go;
            }
            if ui.button("Cancel").clicked() {
                answer = ImportAnswer::Cancel;
            }
        });
    });
    if modal.should_close() && matches!(answer, ImportAnswer::Stay) {
        answer = ImportAnswer::Cancel;
    }
    answer
}

/// Radio buttons choosing `choice` among `meshes`, `none` (the empty
/// choice), or a typed path.
fn mesh_choice(ui: &mut egui::Ui, id: &str, meshes: &[PathBuf], choice: &mut String, none: &str) {
    ui.push_id(id, |ui| {
        for mesh in meshes {
            let text = mesh.display().to_string();
            let name = mesh
                .file_name()
                .map_or_else(|| text.clone(), |n| n.to_string_lossy().into_owned());
            ui.radio_value(choice, text, name);
        }
        ui.radio_value(choice, String::new(), none);
        ui.horizontal(|ui| {
            ui.label("or a mesh (OBJ)");
            ui.add(egui::TextEdit::singleline(choice).desired_width(320.0));
        });
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_meshes_beside_a_groom_are_offered_the_bust_drawn_and_the_collider_collided() {
        let dir =
            std::env::temp_dir().join(format!("helixhair-import-dialog-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let face = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        std::fs::write(dir.join("bust.obj"), face).unwrap();
        std::fs::write(dir.join("bust-collider.obj"), face).unwrap();
        std::fs::write(dir.join("groom.obj"), "v 0 0 0\nv 0 1 0\nl 1 2\n").unwrap();
        std::fs::write(dir.join("other_groom.obj"), "v 0 0 0\nv 0 1 0\nl 1 2\n").unwrap();
        std::fs::write(dir.join("notes.txt"), face).unwrap();
        let dialog = ImportDialog::new(&dir.join("groom.obj"), None);
        assert_eq!(
            dialog.beside,
            vec![dir.join("bust-collider.obj"), dir.join("bust.obj")]
        );
        assert_eq!(dialog.head_path(), Some(dir.join("bust.obj")));
        assert_eq!(dialog.collider_path(), Some(dir.join("bust-collider.obj")));
        let alone = ImportDialog::new(&dir.join("missing").join("g.tfx"), None);
        assert!(alone.beside.is_empty() && alone.head_path().is_none());
        assert!(alone.collider_path().is_none());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
