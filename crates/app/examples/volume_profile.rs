//! One case of the `volume-cost` study (docs/volume.md) run long enough to
//! profile: the full head scaled to STRANDS strands on the batch engine,
//! model and guard on unless told, FRAMES timed frames after one warm-up.
//! Prints the median frame and the median of the model's own pass. Usage:
//! `volume_profile [STRANDS] [FRAMES] [off] [noguard]`, e.g. under
//! `perf record -F 999 -g`.

use helixhair_app::bench::volume::{build, scaled_groom};
use helixhair_physics::engine::EngineKind;

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let strands: usize = args.first().map_or(Ok(3000), |a| a.parse())?;
    let frames: usize = args.get(1).map_or(Ok(60), |a| a.parse())?;
    let on = !args.iter().any(|a| a == "off");
    let guard = !args.iter().any(|a| a == "noguard");
    let groom = scaled_groom(strands)?;
    let mut sim = build(&groom, EngineKind::Batch, on)?;
    if !guard {
        sim.engine_mut().set_guard(None);
    }
    sim.run(1)?;
    let (mut frame, mut pass) = (Vec::new(), Vec::new());
    for _ in 0..frames {
        frame.push(sim.step());
        pass.push(sim.engine().volume_secs());
    }
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let (f, p) = (median(&mut frame), median(&mut pass));
    println!(
        "batch {} strands, model {}, guard {}: frame {:.2} ms, model's pass {:.2} ms ({:.0}%)",
        sim.engine().strand_count(),
        if on { "on" } else { "off" },
        if guard { "on" } else { "off" },
        1e3 * f,
        1e3 * p,
        100.0 * p / f
    );
    Ok(())
}
