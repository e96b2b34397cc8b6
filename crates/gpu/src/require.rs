//! The GPU test policy: a test that finds no adapter skips on a user's
//! machine but fails where `HELIXHAIR_REQUIRE_GPU=1` is set (CI sets it,
//! with Mesa's lavapipe installed), so CI can never pass by skipping.
//!
//! Every GPU test in the workspace goes through [`context_or_skip`] (tests
//! that need a device) or [`skip_or_fail`] (tests that run a binary and
//! learn from its output that it found no adapter).

use crate::context::GpuContext;

/// The environment variable that turns a missing adapter into a failure.
pub const REQUIRE_GPU_VAR: &str = "HELIXHAIR_REQUIRE_GPU";

/// Environment that hides every adapter from a child process (the "no
/// adapter" tests): wgpu on Vulkan only, with the Vulkan loader pointed at a
/// driver manifest that does not exist (both its old and new variable).
pub const HIDDEN_ADAPTER_ENV: [(&str, &str); 3] = [
    ("WGPU_BACKEND", "vulkan"),
    ("VK_ICD_FILENAMES", "/nonexistent/helixhair-no-driver.json"),
    ("VK_DRIVER_FILES", "/nonexistent/helixhair-no-driver.json"),
];

/// Whether the environment requires a GPU (`HELIXHAIR_REQUIRE_GPU=1`).
pub fn gpu_required() -> bool {
    std::env::var(REQUIRE_GPU_VAR).as_deref() == Ok("1")
}

/// Says on stderr that `test` is skipped because of `why`, or, when the
/// environment requires a GPU, fails it.
///
/// # Panics
///
/// When `HELIXHAIR_REQUIRE_GPU=1`.
pub fn skip_or_fail(test: &str, why: impl std::fmt::Display) {
    if gpu_required() {
        panic!("{test}: {REQUIRE_GPU_VAR}=1 but {why}");
    }
    eprintln!("{test}: skipped, {why}");
}

/// A headless device for test `test`, or `None` (after saying so on
/// stderr) when there is none and the environment does not require one.
///
/// # Panics
///
/// When no device can be made and `HELIXHAIR_REQUIRE_GPU=1`.
pub fn context_or_skip(test: &str) -> Option<GpuContext> {
    match GpuContext::new_headless() {
        Ok(gpu) => Some(gpu),
        Err(error) => {
            skip_or_fail(test, error);
            None
        }
    }
}
