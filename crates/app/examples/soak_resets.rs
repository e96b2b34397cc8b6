//! Which strands the batch engine's guard resets under the soak's head
//! motion with the collider, and how often each: a probe for the soak's
//! finding (docs/reliability.md). Usage: `soak_resets [FRAMES]`.

use std::collections::BTreeMap;
use std::sync::Arc;

use helixhair_app::bench::soak::SEED;
use helixhair_app::bench::soak::motion::SoakMotion;
use helixhair_app::head::groom::Groom;
use helixhair_app::style::Style;
use helixhair_app::{HeadlessSim, SimOverrides};
use helixhair_physics::engine::EngineKind;
use helixhair_render::head_generate::default_head;

fn main() -> anyhow::Result<()> {
    let frames: usize = std::env::args().nth(1).map_or(Ok(2500), |a| a.parse())?;
    let style = Style::load("assets/styles/groomed/full_head.ron".as_ref())?;
    let groom = Groom::new(style, default_head());
    let collider = Arc::new(groom.collider()?);
    let overrides = SimOverrides {
        engine: Some(EngineKind::Batch),
        ..SimOverrides::default()
    };
    let mut sim = HeadlessSim::new(&groom.grown, overrides)?;
    let engine = sim.engine_mut();
    engine.set_collider(Some(collider));
    let dt = engine.settings().dt_secs;
    let motion = SoakMotion::new(SEED, frames as f64 * dt);
    let mut per_strand: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for frame in 1..=frames {
        engine.step_frame(&motion);
        if let Some(batch) = engine.batch() {
            let resets = batch.last_guard_resets();
            if !resets.is_empty() {
                let t = frame as f64 * dt;
                let clip = motion
                    .segments()
                    .iter()
                    .rev()
                    .find(|s| s.start_secs <= t)
                    .map(|s| (s.clip.name(), t - s.start_secs));
                let (lo, hi) = (resets.iter().min(), resets.iter().max());
                println!(
                    "frame {frame} t {t:.2} s: {} resets (strands {lo:?} to {hi:?}), clip {clip:?}",
                    resets.len()
                );
                // What failed, and by how much: the first few events.
                for event in batch.last_guard_events().iter().take(3) {
                    println!("  {event}");
                }
            }
            for &s in resets {
                per_strand.entry(s).or_default().push(frame);
            }
        }
    }
    let mut counts: BTreeMap<usize, usize> = BTreeMap::new();
    for frames in per_strand.values() {
        *counts.entry(frames.len()).or_default() += 1;
    }
    println!(
        "strands reset: {}; resets per strand -> strands: {counts:?}",
        per_strand.len()
    );
    if let Some((s, f)) = per_strand.iter().max_by_key(|(_, f)| f.len()) {
        println!("most: strand {s} at frames {f:?}");
    }
    Ok(())
}
