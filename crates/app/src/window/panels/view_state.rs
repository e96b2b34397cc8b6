//! What the window keeps between frames besides the app state: the
//! camera, the 3D pictures' textures, the open dialogs and the fields
//! being typed. The panels read and change it; nothing in it is saved.

use glam::DVec3;
use helixhair_render::OrbitCamera;

use super::files::file_menu::FileWindows;
use super::files::file_picker::FilePicker;
use crate::window::present::viewport::framed_camera;

/// What the window keeps between frames besides the app state.
#[derive(Debug)]
pub struct ViewState {
    /// The camera.
    pub camera: OrbitCamera,
    /// The 3D pictures to show (main, compare), as egui textures.
    pub textures: [Option<egui::TextureId>; 2],
    /// Size in pixels the 3D view had in the last frame.
    pub view_px: [u32; 2],
    /// The open file dialog.
    pub picker: Option<FilePicker>,
    /// Name field of "save as preset".
    pub preset_name: String,
    /// Guide strand count field.
    pub guides: usize,
    /// The style's strand count when the field last looked (`None`
    /// before the first frame).
    pub guides_seen: Option<usize>,
    /// Open (`Some(true)`) or close every group's section in the next
    /// frame ("expand all", "collapse all").
    pub open_groups: Option<bool>,
    /// The File menu's dialogs and jobs.
    pub files: FileWindows,
    /// The head pivot the camera was last framed on: a style with another
    /// head reframes it.
    pub framed_on_m: DVec3,
    /// A comb or grab stroke's depth: the point where it began, the brush
    /// then moving in the plane through it facing the camera.
    pub brush_plane_m: Option<DVec3>,
    /// Where the brush would touch under the pointer (world), to draw it.
    pub brush_at_m: Option<DVec3>,
}

impl ViewState {
    /// A view framing the head, for a style with `guides` strands.
    pub fn new(guides: usize) -> Self {
        Self {
            camera: framed_camera(DVec3::ZERO),
            textures: [None, None],
            view_px: [1, 1],
            picker: None,
            preset_name: "my style".into(),
            guides,
            guides_seen: None,
            open_groups: None,
            files: FileWindows::default(),
            framed_on_m: DVec3::ZERO,
            brush_plane_m: None,
            brush_at_m: None,
        }
    }
}
