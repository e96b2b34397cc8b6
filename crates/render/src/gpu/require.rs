//! The GPU test policy: a test that finds no adapter skips on a user's
//! machine but fails where `HELIXHAIR_REQUIRE_GPU=1` is set (CI sets it,
//! with Mesa's lavapipe installed), so CI can never pass by skipping.

use super::context::GpuContext;

/// The environment variable that turns a missing adapter into a failure.
pub const REQUIRE_GPU_VAR: &str = "HELIXHAIR_REQUIRE_GPU";

/// A headless device for test `test`, or `None` (after saying so on
/// stderr) when there is none and the environment does not require one.
///
/// # Panics
///
/// When no device can be made and `HELIXHAIR_REQUIRE_GPU=1`.
pub fn gpu_or_skip(test: &str) -> Option<GpuContext> {
    match GpuContext::new_headless() {
        Ok(gpu) => Some(gpu),
        Err(error) if std::env::var(REQUIRE_GPU_VAR).as_deref() == Ok("1") => {
            panic!("{test}: {REQUIRE_GPU_VAR}=1 but {error}")
        }
        Err(error) => {
            eprintln!("{test}: skipped, {error}");
            None
        }
    }
}
