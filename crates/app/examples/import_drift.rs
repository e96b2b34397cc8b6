//! Drift of an imported groom on a still head, and the physics cost per
//! frame (docs/import.md, "Measured on Sintel"):
//!
//! `cargo run --release -p helixhair-app --example import_drift -- STYLE.ron HEAD.obj FRAMES`
//!
//! Builds the style's engine (the import writes `engine: Batch`), gives it
//! the head as a collider, records every simulated strand's element
//! boundary points, steps FRAMES frames of 1/60 s on a still head and
//! prints the distances points moved (median, p95, p99, max, and how many
//! moved more than 1 mm; the strands that moved most; the guard's
//! resets), and the median
//! and 90th-percentile wall time of a frame.

use std::path::Path;
use std::sync::Arc;

use anyhow::Context as _;
use helixhair_app::head::groom::head_collider;
use helixhair_app::style::Style;
use helixhair_app::{HeadlessSim, SimOverrides};

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let [_, style, head, frames] = &args[..] else {
        anyhow::bail!("usage: import_drift STYLE.ron HEAD.obj FRAMES");
    };
    let frames: usize = frames.parse().context("FRAMES must be a count")?;
    let style = Style::load(Path::new(style))?;
    let head = helixhair_render::obj::load_mesh_obj(Path::new(head))?;
    let mut sim = HeadlessSim::new(&style, SimOverrides::default())?;
    sim.engine_mut()
        .set_collider(Some(Arc::new(head_collider(&head)?)));
    let count = sim.engine().strand_count();
    let start: Vec<_> = (0..count)
        .map(|i| sim.engine().boundary_points_world(i))
        .collect();
    let mut secs = sim.run(frames)?;
    // The strands that moved most, to look at by hand.
    let mut worst: Vec<(f64, usize)> = (0..count)
        .map(|i| {
            let now = sim.engine().boundary_points_world(i);
            let far = start[i]
                .iter()
                .zip(now)
                .map(|(a, b)| (*a - b).length())
                .fold(0.0, f64::max);
            (far, i)
        })
        .collect();
    worst.sort_by(|a, b| b.0.total_cmp(&a.0));
    for (far, i) in worst.iter().take(5).filter(|(far, _)| *far > 1e-3) {
        println!(
            "strand {i}: moved up to {:.3} mm, {} elements",
            1e3 * far,
            sim.engine().q(*i).len()
        );
    }
    println!("guard: {} strands reset or pinned", sim.strands_lost());
    let mut moved: Vec<f64> = (0..count)
        .flat_map(|i| {
            let now = sim.engine().boundary_points_world(i);
            start[i]
                .iter()
                .zip(now)
                .map(|(a, b)| (*a - b).length())
                .collect::<Vec<_>>()
        })
        .collect();
    moved.sort_by(f64::total_cmp);
    secs.sort_by(f64::total_cmp);
    let pick = |v: &[f64], p: f64| v[((p * v.len() as f64) as usize).min(v.len() - 1)];
    let over_1_mm = moved.iter().filter(|&&m| m > 1e-3).count();
    println!(
        "{count} strands, {frames} frames: points moved median {:.3} mm, p95 {:.3} mm, p99 {:.3} mm, \
         max {:.3} mm ({over_1_mm} of {} points over 1 mm); frame median {:.1} ms, p90 {:.1} ms",
        1e3 * pick(&moved, 0.5),
        1e3 * pick(&moved, 0.95),
        1e3 * pick(&moved, 0.99),
        1e3 * moved[moved.len() - 1],
        moved.len(),
        1e3 * pick(&secs, 0.5),
        1e3 * pick(&secs, 0.9),
    );
    Ok(())
}
