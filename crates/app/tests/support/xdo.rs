//! Driving the window as a user does (`window_brush.rs`,
//! `window_sintel.rs`): the window process, xdotool, and finding the
//! window by its title.

use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// Kills the window when dropped (the tests end it; it has no `--frames`
/// end in sight).
pub struct Window(pub Child);

impl Drop for Window {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// Runs xdotool on `display` with `args`; its standard output.
pub fn xdotool(display: &str, args: &[&str]) -> Option<String> {
    let out = Command::new("xdotool")
        .args(args)
        .env("DISPLAY", display)
        .stderr(Stdio::null())
        .output()
        .ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).trim().to_owned())
}

/// The id of `window`'s X window, found by a part of its title within
/// `patience`; `Err` with why (to skip on) when the window could not open.
/// Panics if it exits otherwise or never shows.
pub fn find_window(
    display: &str,
    title: &str,
    window: &mut Window,
    patience: Duration,
) -> Result<String, String> {
    let started = Instant::now();
    loop {
        if let Some(id) = xdotool(display, &["search", "--name", title])
            .and_then(|ids| ids.lines().next().map(str::to_owned))
        {
            return Ok(id);
        }
        if let Ok(Some(status)) = window.0.try_wait() {
            return Err(format!("the window exited ({status}) before it showed"));
        }
        assert!(
            started.elapsed() < patience,
            "no window titled {title} in {patience:?}"
        );
        std::thread::sleep(Duration::from_millis(250));
    }
}

/// The window (`helixhair` with `args` then `last`) on `display`, its
/// runtime folder `dir/xdg` (made) and its stderr in `dir/stderr.txt`.
pub fn open_window(
    args: &[&str],
    last: &std::path::Path,
    display: &str,
    dir: &std::path::Path,
) -> Window {
    let runtime = dir.join("xdg");
    std::fs::create_dir_all(&runtime).expect("a runtime folder");
    let child = Command::new(env!("CARGO_BIN_EXE_helixhair"))
        .args(args)
        .arg(last)
        .env("DISPLAY", display)
        .env_remove("WAYLAND_DISPLAY")
        .env("XDG_RUNTIME_DIR", &runtime)
        .env(
            "WGPU_BACKEND",
            std::env::var("WGPU_BACKEND").unwrap_or_else(|_| "vulkan".into()),
        )
        .stdout(Stdio::null())
        .stderr(std::fs::File::create(dir.join("stderr.txt")).expect("a stderr file"))
        .spawn()
        .expect("helixhair starts");
    Window(child)
}
