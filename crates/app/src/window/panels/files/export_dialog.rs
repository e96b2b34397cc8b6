//! The export dialog of File → "Export frame…" and "Record animation…":
//! the file (its extension picks the format), simulated or drawn strands,
//! points per strand and, for a recording, the frame count and the head
//! clip it plays (or the head's motion as it is).

use crate::export::{MAX_POINTS_PER_STRAND, StrandChoice};
use crate::hair::sampling::MIN_POINTS_PER_STRAND;
use crate::motion::clip::Clip;

/// Frames "Record animation…" offers first: two seconds at 60 Hz.
pub const DEFAULT_RECORD_FRAMES: usize = 120;

/// Most frames one recording takes (ten minutes at 60 Hz).
pub const MAX_RECORD_FRAMES: usize = 36_000;

/// The export dialog's fields.
#[derive(Clone, Debug)]
pub struct ExportDialog {
    /// Record an animation (true) or export the frame on screen.
    pub animation: bool,
    /// The file to write, as typed.
    pub path: String,
    /// Simulated or drawn strands.
    pub strands: StrandChoice,
    /// Points per strand.
    pub points_per_strand: usize,
    /// Frames to record.
    pub frames: usize,
    /// The clip a recording plays from its first frame (`None`: the head
    /// moves on as it moves now).
    pub clip: Option<Clip>,
    /// Simulated seconds per recorded frame (the style's time step).
    pub frame_secs: f64,
}

/// What the user did in the dialog this frame.
pub enum DialogAnswer {
    /// Nothing yet.
    Stay,
    /// Closed it.
    Cancel,
    /// Asked to export.
    Go,
}

/// Frames of `frame_secs` a recording of `clip` takes by default: the
/// clip and one second after it for the hair to settle.
pub fn frames_for(clip: Clip, frame_secs: f64) -> usize {
    ((clip.duration_secs() + 1.0) / frame_secs).ceil() as usize
}

/// Draws the dialog.
pub fn export_dialog(ctx: &egui::Context, dialog: &mut ExportDialog) -> DialogAnswer {
    let mut answer = DialogAnswer::Stay;
    let title = if dialog.animation {
        "Record animation"
    } else {
        "Export frame"
    };
    egui::Window::new(title)
        .collapsible(false)
        .default_width(460.0)
        .show(ctx, |ui| {
            ui.horizontal(|ui| {
                ui.label("file");
                ui.add(egui::TextEdit::singleline(&mut dialog.path).desired_width(360.0));
            });
            ui.small(
                ".usda, .usdc, .usd, .usdz or .abc (curves with the head), .hair, .tfx or .obj; \
                 a folder is made if missing",
            );
            ui.horizontal(|ui| {
                ui.label("strands");
                ui.radio_value(&mut dialog.strands, StrandChoice::Simulated, "simulated");
                ui.radio_value(&mut dialog.strands, StrandChoice::Drawn, "drawn");
            });
            ui.horizontal(|ui| {
                ui.label("points per strand");
                ui.add(
                    egui::DragValue::new(&mut dialog.points_per_strand)
                        .range(MIN_POINTS_PER_STRAND..=MAX_POINTS_PER_STRAND),
                );
            });
            if dialog.animation {
                ui.horizontal(|ui| {
                    ui.label("frames");
                    ui.add(egui::DragValue::new(&mut dialog.frames).range(1..=MAX_RECORD_FRAMES));
                    ui.small("hands off");
                });
                ui.horizontal(|ui| {
                    ui.label("head");
                    ui.radio_value(&mut dialog.clip, None, "as it moves now");
                    for clip in Clip::ALL {
                        let picked = ui.radio_value(&mut dialog.clip, Some(clip), clip.name());
                        if picked.clicked() {
                            // The whole clip and a second to settle.
                            dialog.frames = frames_for(clip, dialog.frame_secs);
                        }
                    }
                });
            }
            ui.horizontal(|ui| {
                let verb = if dialog.animation { "Record" } else { "Export" };
                let enter = ui.input(|i| i.key_pressed(egui::Key::Enter));
                if ui.button(verb).clicked() || enter {
                    answer = DialogAnswer::Go;
                }
                if ui.button("Cancel").clicked() {
                    answer = DialogAnswer::Cancel;
                }
            });
        });
    answer
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_picked_clip_records_the_clip_and_a_second_at_the_styles_rate() {
        // A shake lasts 4/3 s: with a second after it, 7/3 s of frames.
        assert_eq!(frames_for(Clip::Shake, 1.0 / 60.0), 140);
        assert_eq!(frames_for(Clip::Shake, 1.0 / 120.0), 280);
    }
}
