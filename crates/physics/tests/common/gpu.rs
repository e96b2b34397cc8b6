//! The GPU tests' adapter: skip where none exists, fail where CI asks.

use helixhair_physics::gpu::GpuContext;

/// A headless context, or `None` (after saying why) on a machine without an
/// adapter; with `HELIXHAIR_REQUIRE_GPU=1` (set by `.ci/run`) a missing
/// adapter fails the test instead.
pub fn context() -> Option<GpuContext> {
    match GpuContext::new_headless() {
        Ok(ctx) => Some(ctx),
        Err(e) if std::env::var("HELIXHAIR_REQUIRE_GPU").as_deref() == Ok("1") => {
            panic!("HELIXHAIR_REQUIRE_GPU=1 but {e}")
        }
        Err(e) => {
            eprintln!("skipping GPU test: {e}");
            None
        }
    }
}
