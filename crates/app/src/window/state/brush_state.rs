//! The brush's state in the window: which tool is picked, its settings,
//! the stroke under way, and the strokes recorded to a file. What a stroke
//! does to the app is [`super::brushing`].

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use glam::DVec3;

use crate::brush::stroke_run::{StrokeOutcome, StrokeRun};
use crate::brush::strokes::{STROKES_VERSION, StrandRef, Stroke, StrokeFile, Tool};
use crate::window::live::live_sim::LiveSim;

/// Simulated time the hair settles, in the stroke, after a Part, Smooth or
/// Curl (before a parting or a smoothing is frozen, and over which a curl
/// is blended in), seconds: half a second, long enough for a turned root's
/// strand to swing clear and short enough not to stall the window.
pub const WINDOW_SETTLE_SECS: f64 = 0.5;

/// What the left mouse button does in the 3D view.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ToolKind {
    /// Orbit the camera (no brush).
    #[default]
    Orbit,
    /// Comb the hair along the drag.
    Comb,
    /// Take the hair under the brush and pull it.
    Grab,
    /// Shorten the strands under the brush.
    Cut,
    /// Lengthen the strands under the brush.
    Grow,
    /// Paint a curl on the strands under the brush.
    Curl,
    /// Paint a stiffness on the strands under the brush.
    Stiffness,
    /// Relax the strands under the brush toward their mean shape.
    Smooth,
    /// Draw a parting on the scalp.
    Part,
    /// Make the current shape of the strands under the brush their rest.
    Freeze,
    /// Paint the selection mask on the scalp: strands rooted under the
    /// brush are kept from every tool (Shift: unmask).
    Mask,
}

impl ToolKind {
    /// Every tool, in the tool bar's order.
    pub const ALL: [ToolKind; 11] = [
        ToolKind::Orbit,
        ToolKind::Comb,
        ToolKind::Grab,
        ToolKind::Cut,
        ToolKind::Grow,
        ToolKind::Curl,
        ToolKind::Stiffness,
        ToolKind::Smooth,
        ToolKind::Part,
        ToolKind::Freeze,
        ToolKind::Mask,
    ];

    /// The tool's name on its button.
    pub fn label(self) -> &'static str {
        match self {
            ToolKind::Orbit => "Orbit",
            ToolKind::Comb => "Comb",
            ToolKind::Grab => "Grab",
            ToolKind::Cut => "Cut",
            ToolKind::Grow => "Grow",
            ToolKind::Curl => "Curl",
            ToolKind::Stiffness => "Stiffness",
            ToolKind::Smooth => "Smooth",
            ToolKind::Part => "Part",
            ToolKind::Freeze => "Freeze",
            ToolKind::Mask => "Mask",
        }
    }

    /// The key that picks it (with no modifier, the pointer anywhere).
    pub fn key(self) -> egui::Key {
        use egui::Key;
        match self {
            ToolKind::Orbit => Key::O,
            ToolKind::Comb => Key::C,
            ToolKind::Grab => Key::G,
            ToolKind::Cut => Key::X,
            ToolKind::Grow => Key::W,
            ToolKind::Curl => Key::U,
            ToolKind::Stiffness => Key::K,
            ToolKind::Smooth => Key::M,
            ToolKind::Part => Key::P,
            ToolKind::Freeze => Key::R,
            ToolKind::Mask => Key::A,
        }
    }

    /// What it does, for its button's hover text.
    pub fn hint(self) -> &'static str {
        match self {
            ToolKind::Orbit => "left drag orbits the camera",
            ToolKind::Comb => {
                "drag through the hair: it follows the brush, then keeps its new shape"
            }
            ToolKind::Grab => "take the hair under the brush and pull it on soft springs",
            ToolKind::Cut => "shorten the strands the brush passes over to the cut length",
            ToolKind::Grow => "lengthen the strands the brush passes over to the grow length",
            ToolKind::Curl => "give the strands the brush passes over the curl below",
            ToolKind::Stiffness => "scale the stiffness of the strands the brush passes over",
            ToolKind::Smooth => "relax the strands the brush passes over toward their mean shape",
            ToolKind::Part => "draw a parting on the scalp: roots turn away from the line",
            ToolKind::Freeze => "make the current shape of the strands under the brush their rest",
            ToolKind::Mask => {
                "paint the scalp: strands rooted under the brush are kept from every tool (Shift: unmask)"
            }
        }
    }
}

/// The brush's settings (the tool bar and the Brush panel edit them).
#[derive(Clone, Debug, PartialEq)]
pub struct BrushSettings {
    /// The picked tool.
    pub kind: ToolKind,
    /// The brush sphere's radius, metres (default 3 cm: a comb's width of
    /// hair on a head).
    pub radius_m: f64,
    /// How strongly it acts, 0 to 1.
    pub strength: f64,
    /// Which part of the radius fades out, 0 (hard) to 1 (soft).
    pub falloff: f64,
    /// Whether combed, grabbed, smoothed and parted hair keeps its shape.
    pub freeze: bool,
    /// Cut: the longest a cut strand may be, metres.
    pub cut_length_m: f64,
    /// Grow: the shortest a grown strand may be, metres.
    pub grow_length_m: f64,
    /// Curl: radius and rise per turn, metres.
    pub curl_radius_m: f64,
    /// Curl: rise per turn, metres.
    pub curl_step_m: f64,
    /// Stiffness: factor on the group's moduli.
    pub stiffness_scale: f64,
    /// Part: the largest turn of a root at the line, degrees.
    pub part_angle_deg: f64,
    /// Groups the brush may not touch (the selection mask), by name.
    pub masked_groups: Vec<String>,
}

impl Default for BrushSettings {
    fn default() -> Self {
        Self {
            kind: ToolKind::Orbit,
            radius_m: 0.03,
            strength: 1.0,
            falloff: 0.5,
            freeze: true,
            cut_length_m: 0.15,
            grow_length_m: 0.30,
            curl_radius_m: 0.01,
            curl_step_m: 0.03,
            stiffness_scale: 2.0,
            part_angle_deg: 30.0,
            masked_groups: Vec::new(),
        }
    }
}

impl BrushSettings {
    /// The stroke these settings make (its path empty), for the groups
    /// of `all_groups` not masked, less the `masked` strands; `None` for
    /// Orbit and Mask, which make no stroke.
    pub fn stroke(&self, all_groups: &[String], masked: &BTreeSet<StrandRef>) -> Option<Stroke> {
        let tool = match self.kind {
            ToolKind::Orbit | ToolKind::Mask => return None,
            ToolKind::Comb => Tool::Comb,
            ToolKind::Grab => Tool::Grab,
            ToolKind::Cut => Tool::Cut {
                length_m: self.cut_length_m,
            },
            ToolKind::Grow => Tool::Grow {
                length_m: self.grow_length_m,
            },
            ToolKind::Curl => Tool::Curl {
                radius_m: self.curl_radius_m,
                step_m: self.curl_step_m,
            },
            ToolKind::Stiffness => Tool::Stiffness {
                scale: self.stiffness_scale,
            },
            ToolKind::Smooth => Tool::Smooth,
            ToolKind::Part => Tool::Part {
                angle_deg: self.part_angle_deg,
            },
            ToolKind::Freeze => Tool::Freeze,
        };
        let groups = if self.masked_groups.is_empty() {
            Vec::new()
        } else {
            all_groups
                .iter()
                .filter(|g| !self.masked_groups.contains(g))
                .cloned()
                .collect()
        };
        Some(Stroke {
            tool,
            path: Vec::new(),
            radius_m: self.radius_m,
            seconds: WINDOW_SETTLE_SECS,
            strength: self.strength,
            falloff: self.falloff,
            freeze: self.freeze,
            groups,
            masked: masked.iter().cloned().collect(),
        })
    }
}

/// A stroke under way in the window.
#[derive(Clone, Debug)]
pub struct ActiveStroke {
    /// The stroke.
    pub(super) run: StrokeRun,
    /// The run as it was when the stroke began (Esc restores it).
    pub(super) before: LiveSim,
    /// Where the pointer puts the brush now, world, metres.
    pub(super) centre_m: DVec3,
    /// Where the brush was at the last physics frame.
    pub(super) last_centre_m: DVec3,
}

impl ActiveStroke {
    /// Where the brush is, world, metres.
    pub fn centre_m(&self) -> DVec3 {
        self.centre_m
    }
}

/// Strokes being recorded to a file.
#[derive(Clone, Debug)]
pub struct StrokeRecording {
    /// Where they are written (after every stroke, atomically).
    pub path: PathBuf,
    /// The strokes so far.
    pub file: StrokeFile,
}

/// The brush's state between frames.
#[derive(Clone, Debug, Default)]
pub struct BrushState {
    /// The settings.
    pub settings: BrushSettings,
    /// The stroke under way.
    pub active: Option<ActiveStroke>,
    /// Strokes being recorded, if recording.
    pub recording: Option<StrokeRecording>,
    /// What the last stroke did.
    pub last: Option<StrokeOutcome>,
    /// Strands no tool may touch (painted with Mask on the scalp).
    pub masked: BTreeSet<StrandRef>,
}

impl BrushState {
    /// Starts recording strokes to `path` (written after every stroke).
    pub fn record_to(&mut self, path: &Path) {
        self.recording = Some(StrokeRecording {
            path: path.to_owned(),
            file: StrokeFile {
                version: STROKES_VERSION,
                strokes: Vec::new(),
            },
        });
    }
}
