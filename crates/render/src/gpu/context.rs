//! The renderer's device and its errors.
//!
//! The device is [`GpuContext`] from `helixhair-gpu`, the one device setup
//! the physics kernels and the window share: the adapter wgpu's environment
//! variables pick (`WGPU_BACKEND=vulkan` picks Mesa's lavapipe on a machine
//! without a GPU, `WGPU_ADAPTER_NAME` picks by name), or the default one.
//! The renderer needs no feature beyond core WebGPU, so any adapter will
//! do; [`GpuError`] adds what can go wrong after the device exists.

pub use helixhair_gpu::{DeviceError, GpuContext};
use thiserror::Error;

/// Why no GPU device could be made.
#[derive(Debug, Error)]
pub enum GpuError {
    /// No adapter (no GPU driver, no software rasteriser), or the adapter
    /// refused a device.
    #[error(transparent)]
    Device(#[from] DeviceError),
    /// The adapter cannot build the renderer's pipelines.
    #[error(
        "the graphics adapter `{adapter}` cannot run the renderer's shaders ({error}); \
         try another backend, e.g. WGPU_BACKEND=vulkan"
    )]
    Unsupported {
        /// The adapter's name.
        adapter: String,
        /// What wgpu reported.
        error: String,
    },
    /// Reading the rendered image back failed.
    #[error("reading the image back from the GPU failed: {0}")]
    Readback(String),
    /// A size the renderer cannot make a texture of.
    #[error("image size {width_px}x{height_px} is not supported (1 to {max_px} pixels a side)")]
    BadSize {
        /// Asked width.
        width_px: u32,
        /// Asked height.
        height_px: u32,
        /// Largest side the adapter takes.
        max_px: u32,
    },
}
