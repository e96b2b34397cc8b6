//! A headless wgpu device for compute, and the errors of the GPU path.
//!
//! The adapter comes from the environment (`WGPU_BACKEND`,
//! `WGPU_ADAPTER_NAME`) or wgpu's default choice; on a machine without a
//! GPU, Mesa's lavapipe (`WGPU_BACKEND=vulkan`) or llvmpipe (`gl`) serve.
//! The device asks for the adapter's own limits, so large buffers work where
//! the hardware allows them (lavapipe caps one storage binding at 128 MiB).

use thiserror::Error;

use crate::error::ParamError;

/// Why the GPU path could not run.
#[derive(Debug, Error)]
pub enum GpuError {
    /// No adapter at all: the caller should fall back to the CPU.
    #[error(
        "no GPU adapter found ({0}); install a driver or Mesa's lavapipe \
         (mesa-vulkan-drivers) and set WGPU_BACKEND=vulkan"
    )]
    NoAdapter(String),
    /// The adapter refused to create a device.
    #[error("the GPU adapter `{adapter}` could not create a device: {reason}")]
    Device {
        /// Adapter name.
        adapter: String,
        /// wgpu's message.
        reason: String,
    },
    /// A method the kernels do not implement.
    #[error("the GPU path runs `block`, `exact` and `dense`, not `{0}`")]
    UnsupportedMethod(String),
    /// A parameter out of range.
    #[error(transparent)]
    Param(#[from] ParamError),
    /// A buffer larger than one binding may be.
    #[error("{what} needs {bytes} bytes in one buffer; this adapter allows {limit_bytes}")]
    TooLarge {
        /// Which buffer.
        what: &'static str,
        /// Its size.
        bytes: u64,
        /// The adapter's limit.
        limit_bytes: u64,
    },
    /// A strand longer than the Dense kernel's workgroup arrays.
    #[error(
        "the GPU Dense kernel takes at most {max} elements per strand, not {elements}; \
         use `exact` (the same answer in O(N))"
    )]
    TooManyElements {
        /// Elements per strand asked for.
        elements: usize,
        /// The kernel's limit.
        max: usize,
    },
    /// Mapping a buffer for readback failed.
    #[error("reading GPU memory back failed: {0}")]
    Readback(String),
}

/// The device and queue the kernels run on.
#[derive(Debug)]
pub struct GpuContext {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// The adapter's name, e.g. `llvmpipe (LLVM 15.0.6, 256 bits)`.
    pub adapter_name: String,
    /// The device's limits.
    pub limits: wgpu::Limits,
}

impl GpuContext {
    /// A device on the adapter the environment picks, with no surface.
    pub fn new_headless() -> Result<Self, GpuError> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle().with_env());
        let adapter = pollster::block_on(wgpu::util::initialize_adapter_from_env_or_default(
            &instance, None,
        ))
        .map_err(|e| GpuError::NoAdapter(e.to_string()))?;
        let adapter_name = adapter.get_info().name;
        let limits = adapter.limits();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("helixhair physics"),
            required_limits: limits.clone(),
            ..Default::default()
        }))
        .map_err(|e| GpuError::Device {
            adapter: adapter_name.clone(),
            reason: e.to_string(),
        })?;
        Ok(Self {
            device,
            queue,
            adapter_name,
            limits,
        })
    }
}
