//! The one place HelixHair makes a wgpu device, and the one GPU test policy.
//!
//! Three parts of HelixHair run on the GPU: the physics kernels
//! (`helixhair-physics`, feature `gpu`), the offscreen renderer
//! (`helixhair-render`) and the styling window (`helixhair-app`). The
//! physics and the renderer must not know each other (ARCHITECTURE.md,
//! "Layers are strict"), so what they share sits below both, here:
//!
//! - [`GpuContext`] ([`context`]): an adapter chosen the same way
//!   everywhere (wgpu's environment variables first, then the default
//!   adapter), and a device asking for that adapter's own limits; headless
//!   ([`GpuContext::new_headless`]) or able to draw to a window's surface
//!   ([`GpuContext::for_surface`]). Failing to find an adapter or a device
//!   is a [`DeviceError`] whose message says what to install, never a
//!   panic.
//! - [`require`]: a GPU test skips on a machine without an adapter, but
//!   fails where `HELIXHAIR_REQUIRE_GPU=1` (CI), so CI cannot pass by
//!   skipping.
//!
//! - [`readback`]: a buffer read back to the CPU, a bind group of whole
//!   buffers, and a dispatch's workgroup counts.
//!
//! The crate depends on wgpu, pollster and thiserror only.

#![warn(missing_docs)]

pub mod context;
pub mod readback;
pub mod require;
pub mod upload;

pub use context::{DeviceError, DeviceHealth, GpuContext};
pub use readback::{bind_buffers, dispatch_dims, map_and_wait, read_bytes};
pub use require::{
    HIDDEN_ADAPTER_ENV, REQUIRE_GPU_VAR, context_or_skip, gpu_required, skip_or_fail,
};
pub use upload::upload_buffer;
