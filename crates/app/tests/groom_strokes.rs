//! The styling tools end to end: the stroke file of issue #28
//! (`assets/strokes/comb_cut_curl.ron`: comb the right side forward, cut
//! the back to 15 cm, curl the left side, freeze everything) applied to
//! `assets/styles/straight.ron` by `helixhair groom`'s code, then the
//! styled style simulated 5 s on a still head beside the unstyled one.
//!
//! Known answers, none of them the code's own output:
//!
//! - a comb moves hair the way it is drawn: the combed side's tips end
//!   forward (+z) of where they hang unstyled, by centimetres, and stay
//!   there (the style holds still: the shape is a frozen equilibrium);
//! - strands no tool but the freeze reached end where they hung unstyled
//!   (the unstyled hair brought to rest, as a session starts);
//! - a cut strand is at most the cut length, the others keep theirs;
//! - a helix of radius R and step P has chord over arc length
//!   c/√(R² + c²), c = P/2π: 0.43 for the curl painted here, where a
//!   straight hanging strand's is near 1;
//! - no guard event: a stroke never leaves a strand the guard must reset.

use std::path::{Path, PathBuf};

use glam::DVec3;
use helixhair_app::brush::command::{GroomArgs, run_groom};
use helixhair_app::brush::session::GroomSession;
use helixhair_app::sim::grown::grown_sim;
use helixhair_app::{HeadlessSim, SimOverrides, Style};

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Every strand's element-end points (world) after `frames` frames and
/// after half as many, and the run's guard events and lost strands.
struct Run {
    half: Vec<Vec<DVec3>>,
    end: Vec<Vec<DVec3>>,
    guard: usize,
}

fn settle(style: &Path, frames: usize) -> (Style, HeadlessSim, Run) {
    let (groom, mut sim) = grown_sim(style, None, SimOverrides::default()).expect("grows");
    let points = |sim: &HeadlessSim| -> Vec<Vec<DVec3>> {
        let e = sim.engine();
        (0..e.strand_count())
            .map(|i| e.boundary_points_world(i))
            .collect()
    };
    sim.run(frames / 2).expect("runs");
    let half = points(&sim);
    sim.run(frames - frames / 2).expect("runs");
    let end = points(&sim);
    let guard = sim.guard_events().len() + sim.strands_lost();
    (groom.grown, sim, Run { half, end, guard })
}

fn tip(points: &[DVec3]) -> DVec3 {
    *points.last().expect("a strand has points")
}

fn length(points: &[DVec3]) -> f64 {
    points.windows(2).map(|p| p[0].distance(p[1])).sum()
}

#[test]
fn the_issue_strokes_comb_cut_and_curl_straight_hair_and_it_stays() {
    let out_dir = std::env::temp_dir().join(format!("helixhair-groom-{}", std::process::id()));
    std::fs::create_dir_all(&out_dir).expect("a temporary folder");
    let styled = out_dir.join("styled.ron");
    let args = GroomArgs {
        style: repo().join("assets/styles/straight.ron"),
        strokes: repo().join("assets/strokes/comb_cut_curl.ron"),
        head: None,
        out: styled.clone(),
    };
    let mut report = Vec::new();
    run_groom(&args, &mut report).expect("the strokes apply");
    let report = String::from_utf8(report).expect("text");
    println!("{report}");
    assert!(
        !report.contains("guard stepped in"),
        "no stroke may need the guard: {report}"
    );

    // Where the hair hung before: the unstyled style brought to rest, as
    // a session starts.
    let (groom, sim) = grown_sim(&args.style, None, SimOverrides::default()).expect("grows");
    let grown = groom.grown.clone();
    let mut session = GroomSession::new(groom, sim).expect("a session");
    // Longer than the strokes' session takes (3 s, then 1 s a stroke), so
    // this is the rest the hair tends to.
    session.settle_for(10.0).expect("settles");
    let engine = session.sim().engine();
    let hung: Vec<Vec<DVec3>> = (0..engine.strand_count())
        .map(|i| engine.boundary_points_world(i))
        .collect();
    // The styled style, five seconds on a still head.
    let (styled_grown, styled_sim, after) = settle(&styled, 300);
    assert_eq!(after.guard, 0, "the styled hair needs no guard");
    assert_eq!(hung.len(), after.end.len(), "same strands");

    let mut index = 0;
    let mut combed_forward = Vec::new();
    for (group, styled_group) in grown.groups.iter().zip(&styled_grown.groups) {
        for n in 0..group.roots.len() {
            let i = index;
            index += 1;
            let edit = styled_group.edits.iter().find(|e| e.strand == n);
            let (b, a) = (&hung[i], &after.end[i]);
            // Still: the styled shape is an equilibrium.
            let drift = tip(&after.half[i]).distance(tip(a));
            assert!(
                drift < 2e-3,
                "{} strand {n}: tip moved {:.1} mm between 2.5 s and 5 s",
                group.name,
                drift * 1e3
            );
            let cut = edit.and_then(|e| e.length_m);
            let curled = edit.and_then(|e| e.natural_shape.as_ref()).is_some();
            let model_length = styled_sim.engine().strand_model(i).params.length_m;
            match cut {
                Some(l) => {
                    // The element ends' polyline is no longer than the arc.
                    assert!(l <= 0.15 + 1e-12, "cut to {l}");
                    assert!(model_length <= 0.15 + 1e-12);
                    assert!(length(a) <= model_length + 1e-9);
                }
                None => assert!(
                    (model_length - group.params.length_m).abs() < 1e-12,
                    "{} strand {n} kept its length",
                    group.name
                ),
            }
            let chord = tip(a).distance(a[0]) / model_length;
            if curled {
                assert!(
                    chord < 0.6,
                    "{} strand {n} curls: chord {chord:.2}",
                    group.name
                );
            } else {
                assert!(
                    chord > 0.85,
                    "{} strand {n} stays straight: chord {chord:.2}",
                    group.name
                );
            }
            if group.name == "right" {
                combed_forward.push(tip(a).z - tip(b).z);
            } else if cut.is_none() && !curled {
                let moved = tip(a).distance(tip(b));
                assert!(
                    moved < 1e-4,
                    "{} strand {n}, reached by no tool but the freeze, moved {:.1} mm",
                    group.name,
                    moved * 1e3
                );
            }
        }
    }
    let mean_forward = combed_forward.iter().sum::<f64>() / combed_forward.len() as f64;
    assert!(
        mean_forward > 0.02,
        "the combed side's tips end forward by centimetres: {:.1} mm ({combed_forward:?})",
        mean_forward * 1e3
    );
    let curled = styled_grown
        .groups
        .iter()
        .flat_map(|g| &g.edits)
        .filter(|e| e.natural_shape.is_some())
        .count();
    let cut = styled_grown
        .groups
        .iter()
        .flat_map(|g| &g.edits)
        .filter(|e| e.length_m.is_some())
        .count();
    assert!(
        curled > 0 && cut > 0,
        "the strokes curled {curled} and cut {cut} strands"
    );
    // The saved style reloads to the same style.
    let reloaded = Style::load(&styled).expect("the styled style loads");
    let written = std::fs::read_to_string(&styled).expect("the styled style is written");
    assert_eq!(reloaded.to_ron().expect("writes"), written);
    std::fs::remove_dir_all(&out_dir).ok();
}
