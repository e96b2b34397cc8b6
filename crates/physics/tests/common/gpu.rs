//! The GPU tests' adapter, by the workspace's one test policy
//! (`helixhair_gpu::context_or_skip`): skip where none exists, fail where
//! CI asks (`HELIXHAIR_REQUIRE_GPU=1`, set by `.ci/run`).

use helixhair_physics::gpu::GpuContext;

/// A headless context, or `None` (after saying why) on a machine without an
/// adapter; a missing adapter fails the test where CI requires a GPU.
pub fn context() -> Option<GpuContext> {
    helixhair_gpu::context_or_skip("physics GPU test")
}
