//! Styling by hand in the real window, driven as a user drives it: the
//! window opens on a copy of `assets/styles/straight.ron` on an X server
//! (Xvfb when no display is set), xdotool picks the Comb (key C), drags it
//! across the hair and saves (Ctrl+S). The saved style must hold the
//! stroke (frozen shapes for the strands it combed, and only for them),
//! read back to the same style, and simulate still with no guard event.
//!
//! Without an X server, xdotool or a graphics adapter the test skips on a
//! user's machine, but fails where `HELIXHAIR_REQUIRE_GPU=1` (CI sets it
//! and installs Xvfb, xdotool and lavapipe).

use crate::support;

use std::path::Path;
use std::process::Command;
use std::thread::sleep;
use std::time::{Duration, Instant};

use helixhair_app::Style;
use support::display::display;
use support::xdo::{find_window, open_window, xdotool};

/// The workspace's GPU test policy (`helixhair_gpu::require`).
fn skip_or_fail(why: &str) {
    helixhair_gpu::skip_or_fail("window_brush", why);
}

/// Seconds to wait for the window to appear and for the save to land (a
/// debug build on lavapipe opens in about 10 s).
const PATIENCE: Duration = Duration::from_secs(90);

/// Where the drag starts and how it moves, window pixels: from the hair
/// right of the face (the default 1280×800 layout puts the 3D view between
/// x = 500 and 950), 20 steps of 6 px left and 3 px up.
const DRAG_FROM: (i32, i32) = (820, 420);
const DRAG_STEPS: i32 = 20;
const DRAG_STEP: (i32, i32) = (-6, -3);

#[test]
fn comb_in_the_window_then_save_keeps_the_stroke_and_reloads_unchanged() {
    let Some((display, _xvfb)) = display() else {
        skip_or_fail("no X display and no Xvfb to start");
        return;
    };
    if xdotool(&display, &["version"]).is_none() {
        skip_or_fail("xdotool is not installed");
        return;
    }
    let dir = std::env::temp_dir().join(format!("helixhair-window-brush-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let style_path = dir.join("brushed.ron");
    let assets = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/styles/straight.ron");
    std::fs::copy(&assets, &style_path).unwrap();
    let original = std::fs::read_to_string(&style_path).unwrap();
    let mut window = open_window(
        &["--preview", "--frames", "1000000", "--style"],
        &style_path,
        &display,
        &dir,
    );
    let id = match find_window(&display, "brushed.ron", &mut window, PATIENCE) {
        Ok(id) => id,
        Err(why) => {
            let stderr = std::fs::read_to_string(dir.join("stderr.txt")).unwrap_or_default();
            skip_or_fail(&format!("{why}: {stderr}"));
            return;
        }
    };
    // Let the hair hang, then pick the Comb and drag it through the hair.
    sleep(Duration::from_secs(3));
    let run = |args: &[&str]| {
        xdotool(&display, args).unwrap_or_else(|| panic!("xdotool {args:?} failed"));
    };
    let at = |x: i32, y: i32| [x.to_string(), y.to_string()];
    let [x0, y0] = at(DRAG_FROM.0, DRAG_FROM.1);
    run(&["windowfocus", "--sync", &id]);
    run(&["mousemove", "--window", &id, &x0, &y0]);
    run(&["key", "c"]);
    sleep(Duration::from_millis(500));
    run(&["mousedown", "1"]);
    for k in 1..=DRAG_STEPS {
        let [x, y] = at(DRAG_FROM.0 + k * DRAG_STEP.0, DRAG_FROM.1 + k * DRAG_STEP.1);
        run(&["mousemove", "--window", &id, &x, &y]);
        sleep(Duration::from_millis(150));
    }
    run(&["mouseup", "1"]);
    sleep(Duration::from_secs(1));
    run(&["key", "ctrl+s"]);
    let started = Instant::now();
    let saved = loop {
        let now = std::fs::read_to_string(&style_path).unwrap_or_default();
        if now != original && !now.is_empty() {
            break now;
        }
        assert!(
            started.elapsed() < 2 * PATIENCE,
            "the style was never saved"
        );
        sleep(Duration::from_millis(250));
    };
    drop(window);

    // The stroke is in the file: the combed strands' frozen shapes, and
    // nothing else changed.
    let style = Style::from_ron(&saved, &style_path).expect("the saved style reads");
    let before = Style::from_ron(&original, &style_path).unwrap();
    let edits: Vec<_> = style.groups.iter().flat_map(|g| &g.edits).collect();
    let strands: usize = style.groups.iter().map(|g| g.simulated_count()).sum();
    assert!(
        !edits.is_empty() && edits.len() < strands / 2,
        "{} of {strands} strands edited",
        edits.len()
    );
    assert!(edits.iter().all(|e| e.rest.is_some()), "{saved}");
    let mut without = style.clone();
    without.groups.iter_mut().for_each(|g| g.edits.clear());
    assert_eq!(without, before, "the stroke changed more than its strands");
    // It reads back as it was written.
    let again = Style::from_ron(&style.to_ron().unwrap(), &style_path).unwrap();
    assert_eq!(again, style);
    // And the combed hair rests: the saved style simulates 2 s with no
    // guard event (`sim` exits 1 on one).
    let sim = Command::new(env!("CARGO_BIN_EXE_helixhair"))
        .args(["sim", "--steps", "120", "--style"])
        .arg(&style_path)
        .output()
        .expect("sim runs");
    assert!(
        sim.status.success(),
        "{}\n{}",
        String::from_utf8_lossy(&sim.stdout),
        String::from_utf8_lossy(&sim.stderr)
    );
    let _ = std::fs::remove_dir_all(&dir);
}
