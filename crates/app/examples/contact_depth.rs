//! How deep hair rests in the head's collider, by the physics' own distance
//! field, with the contact stiffness of your choice: the
//! probe behind the contact measurements of issues 32 and 33.
//!
//! `cargo run --release -p helixhair-app --example contact_depth -- STYLE.ron FRAMES SKIN_M ALPHA [CLIP]`
//!
//! Grows and settles STYLE as `render` and `sim --export` do, sets the
//! engine's contact skin (metres) and implicit stiffness ratio α
//! (`ContactSettings`), settles it again with them (so no stored spring
//! energy is left over from the change), then steps FRAMES frames on a
//! still head or under CLIP (`nod`, `shake`, `turn`, `jerk`). It prints
//! the first guard events, and the share of quadrature samples at a signed
//! distance below 0, −1 mm and −3 mm, the deepest one, and per element
//! index how many samples are inside. Either engine (the style's `engine`).
//!
//! Measured with it (groomed examples under the shake, 300 frames, α = 4;
//! the coils grown with their lead-in bend, `head::coil`): with a 2 mm
//! skin, 1.04% of the curly example's samples lie below the mesh (the
//! deepest at −2.2 mm, its draped loops) and 0.47% of the coily one's
//! (−1.2 mm); with a 3 mm skin, as both examples set, 0.40% (−1.25 mm)
//! and none. Stiffer contact blows up as the 30 cm straight and wavy
//! examples land on the head: at α = 16 two guard events on straight hair
//! on a still head (a point at 73 m/s), at α = 32 3 to 12 per clip on
//! both.

use std::path::Path;

use anyhow::Context as _;
use helixhair_app::SimOverrides;
use helixhair_app::motion::clip::Clip;
use helixhair_app::sim::grown::grown_sim;
use helixhair_app::sim::settle::settle_on_head;

/// Guard events printed in full.
const SHOWN_EVENTS: usize = 3;

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let (style, frames, skin_m, alpha) = match &args[..] {
        [_, style, frames, skin, alpha, ..] => (
            Path::new(style),
            frames.parse::<usize>().context("FRAMES must be a count")?,
            skin.parse::<f64>().context("SKIN_M must be metres")?,
            alpha.parse::<f64>().context("ALPHA must be a number")?,
        ),
        _ => anyhow::bail!("usage: contact_depth STYLE.ron FRAMES SKIN_M ALPHA [CLIP]"),
    };
    let clip = match args.get(5) {
        Some(name) => Some(Clip::from_name(name).context("CLIP: nod, shake, turn or jerk")?),
        None => None,
    };
    let (_groom, mut sim) = grown_sim(style, None, SimOverrides::default())?;
    let engine = sim.engine_mut();
    let mut contact = engine.contact_settings();
    contact.skin_m = skin_m;
    contact.implicit_stiffness_ratio = alpha;
    engine.set_contact_settings(contact);
    settle_on_head(engine);
    if let Some(clip) = clip {
        sim.play(clip);
    }
    let mut shown = 0;
    for _ in 0..frames {
        sim.run(1)?;
        for event in sim.engine().last_guard_events() {
            if shown < SHOWN_EVENTS {
                println!("{event}");
                shown += 1;
            }
        }
    }
    let engine = sim.engine();
    let field = engine.collider().context("the style has no collider")?;
    let head = *engine.head();
    let mut distances_m: Vec<f64> = Vec::new();
    let mut inside_by_element = std::collections::BTreeMap::new();
    for index in 0..engine.strand_count() {
        let (root, kin) = engine.kinematics(index);
        let per_element = kin.samples.len() / (kin.points_m.len() - 1).max(1);
        for (k, sample) in kin.samples.iter().enumerate() {
            let world = root.position_m + sample.position_m;
            let local = head.world_from_body.transpose() * (world - head.position_m);
            if let Some((distance_m, _)) = field.sample(local) {
                distances_m.push(distance_m);
                if distance_m < 0.0 {
                    *inside_by_element.entry(k / per_element).or_insert(0usize) += 1;
                }
            }
        }
    }
    distances_m.sort_by(f64::total_cmp);
    let share_below = |x: f64| {
        100.0 * distances_m.iter().filter(|d| **d < x).count() as f64
            / distances_m.len().max(1) as f64
    };
    println!("inside, by element index: {inside_by_element:?}");
    println!(
        "skin {skin_m} m, alpha {alpha}: {} samples; below 0: {:.2}%, -1 mm: {:.2}%, \
         -3 mm: {:.2}%; deepest {:.2} mm; {} guard events",
        distances_m.len(),
        share_below(0.0),
        share_below(-1e-3),
        share_below(-3e-3),
        1e3 * distances_m.first().copied().unwrap_or(f64::NAN),
        engine.guard_event_count()
    );
    Ok(())
}
