//! `helixhair groom`: a stroke file applied to a style, headless, with the
//! physics running, and the styled style written out.
//!
//! The same session code the window's tools drive
//! ([`crate::brush::session::GroomSession`]): a stroke file recorded in the
//! window replays here stroke for stroke, so strokes can be tested in CI
//! and scripted.

use std::io::Write;
use std::path::PathBuf;

use anyhow::Context as _;
use clap::Args;

use crate::brush::session::GroomSession;
use crate::brush::strokes::StrokeFile;
use crate::sim::build::SimOverrides;
use crate::sim::grown::grown_sim;
use crate::style::ron_file::RonFile as _;
use helixhair_physics::engine::EngineKind;

/// Arguments of `helixhair groom`.
#[derive(Clone, Debug, Args)]
pub struct GroomArgs {
    /// The style to groom (RON).
    #[arg(long, value_name = "STYLE")]
    pub style: PathBuf,
    /// The strokes to apply, in order (RON; docs/stroke-format.md).
    #[arg(long, value_name = "STROKES")]
    pub strokes: PathBuf,
    /// The head mesh (OBJ) to groom on, instead of the style's own head
    /// (an imported groom's) or the default head.
    #[arg(long, value_name = "MESH")]
    pub head: Option<PathBuf>,
    /// The styled style to write (RON, atomically; may be STYLE itself).
    #[arg(long, value_name = "STYLE")]
    pub out: PathBuf,
}

/// Runs `helixhair groom`, printing one line per stroke.
pub fn run_groom(args: &GroomArgs, stdout: &mut dyn Write) -> anyhow::Result<()> {
    let strokes = StrokeFile::load(&args.strokes)?;
    let overrides = SimOverrides {
        engine: Some(EngineKind::Reference),
        ..SimOverrides::default()
    };
    let (groom, sim) = grown_sim(&args.style, args.head.as_deref(), overrides)?;
    let mut session = GroomSession::new(groom, sim)?;
    for (i, stroke) in strokes.strokes.iter().enumerate() {
        let outcome = session
            .apply(stroke)
            .with_context(|| format!("stroke {} ({})", i + 1, stroke.tool.name()))?;
        writeln!(stdout, "stroke {}: {}", i + 1, outcome.describe())?;
    }
    session.style().save(&args.out)?;
    writeln!(
        stdout,
        "wrote {} ({} strokes applied)",
        args.out.display(),
        strokes.strokes.len()
    )?;
    Ok(())
}
