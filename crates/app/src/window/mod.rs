//! The styling window: `helixhair` with no command.
//!
//! # Modules
//!
//! Window-free logic, tested without a display:
//! `app_state` (everything the window shows and edits, stepped once per
//! frame), `document` (the style, its file, unsaved marker, undo via
//! `undo`), `presets`, `live_sim` (the simulation following edits
//! without a reset, shapes kept by `resample`), `head_motion` (the
//! user's head pose and the built-in motions, with velocities and
//! accelerations for the physics), `collision` (the head collider
//! handed to the physics), `readouts`, `default_style` and
//! `viewport` (camera gestures, render strands from guides) and
//! `drawn` (styles with `render` sections, drawn as `helixhair render`
//! draws them).
//!
//! Files in and out: `export_job` (File → Export frame… and Record
//! animation…, through `sim --export`'s code), `import_job` (File →
//! Import groom… and dropped grooms, through `import`'s code),
//! `motion_recorder` (head drags recorded as a motion file), all run by
//! `job` on a worker thread with a progress bar and Cancel; `set_rest`
//! ("set current shape as rest": the sag-free solve of the import on the
//! hair as it is now).
//!
//! With a display: `event_loop` (winit), `window_gpu` (surface, 3D
//! pictures), `screenshot`, `egui_paint` and `panel_layer` (egui
//! painted, the panels cached where they do not change), `preview` (the
//! interactive preview's choices) and the egui panels (`ui`, `tool_bar`,
//! `file_menu`, `style_panel`, `readout_panel`, `file_picker`).
//!
//! # Without a display
//!
//! When no window can be opened (no `DISPLAY` or Wayland socket, or no
//! graphics adapter), [`run_window`] returns an error that says why and
//! points to the headless commands; the binary prints it and exits with
//! status 1, so scripts notice.

pub mod event_loop;
pub mod jobs;
pub mod live;
pub mod panels;
pub mod present;
pub mod state;

use std::path::PathBuf;

use clap::Args;
use clap::builder::TypedValueParser as _;

use self::live::head_motion::Clip;
use self::present::viewport::DEFAULT_RENDER_STRANDS;
use self::state::default_style::DEFAULT_GUIDES;

pub use event_loop::run_window;

/// What `helixhair` prints when it cannot open its window.
pub const HEADLESS_HINT: &str = "\
The headless commands need no display:
    helixhair sim --style assets/styles/curly.ron    simulate a style and report
    helixhair render --style assets/styles/groomed/curly.ron --out curly.png
                                                     draw it offscreen (no display needed)
    helixhair bench --help                           measure speed and accuracy
See `helixhair --help` for every command.";

/// Options of the window (`helixhair` without a command).
#[derive(Clone, Debug, Args)]
pub struct WindowArgs {
    /// Style to open (RON); default: curly hair on the default head.
    #[arg(long, value_name = "FILE")]
    pub style: Option<PathBuf>,
    /// Guide strands (simulated) of the default style.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_GUIDES,
          value_parser = clap::value_parser!(u32).range(1..=5000).map(|n| n as usize))]
    pub guides: usize,
    /// Render strands drawn, interpolated from the guides.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_RENDER_STRANDS,
          value_parser = clap::value_parser!(u32).range(1..=200_000).map(|n| n as usize))]
    pub render_strands: usize,
    /// Groom to import at start (.tfx, .hair, .usda, .usdc, .usd, .usdz,
    /// .abc, .obj): the window
    /// opens with the import dialog, which asks for its head.
    #[arg(long, value_name = "GROOM")]
    pub import: Option<PathBuf>,
    /// Play a head motion at start: nod, shake, turn or jerk.
    #[arg(long, value_name = "MOTION", value_parser = parse_clip)]
    pub play: Option<Clip>,
    /// Start in the compare view (Dense against Exact).
    #[arg(long)]
    pub compare: bool,
    /// Quit after K frames and print frame and physics times.
    #[arg(long, value_name = "K", value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub frames: Option<u32>,
    /// Always draw the interactive preview (at most 300 drawn strands, one
    /// sample per pixel, no shadows, at full resolution; panels repainted
    /// only where they change), as on a software adapter while the user
    /// drags; for measuring it with --frames.
    #[arg(long)]
    pub preview: bool,
    /// With --frames: time each stage of a frame (physics, strand
    /// geometry, the 3D picture, egui layout, tessellation, painting,
    /// presenting) and print their medians; the GPU's work is waited for
    /// at each stage, so it is counted where it is done.
    #[arg(long)]
    pub profile: bool,
    /// Save the window as a PNG after the last frame (--frames, default 120)
    /// and quit.
    #[arg(long, value_name = "PNG")]
    pub screenshot: Option<PathBuf>,
    /// Physics engine: reference, batch or gpu, set in the style as the
    /// engine menu sets it (an edit, undoable; saved only if you save).
    #[arg(long, value_name = "ENGINE", value_parser = crate::sim::engine_arg::parse_engine)]
    pub engine: Option<helixhair_physics::engine::EngineKind>,
}

fn parse_clip(name: &str) -> Result<Clip, String> {
    Clip::from_name(name).ok_or_else(|| {
        let names: Vec<&str> = Clip::ALL.iter().map(|c| c.name()).collect();
        format!("unknown motion `{name}`; one of {}", names.join(", "))
    })
}
