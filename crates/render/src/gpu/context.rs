//! A wgpu device with no window: what headless renders and tests use.
//!
//! The adapter is chosen the way wgpu's environment variables say
//! (`WGPU_BACKEND=vulkan` picks Mesa's lavapipe on a machine without a GPU,
//! `WGPU_ADAPTER_NAME` picks by name), falling back to the default adapter.
//! No feature beyond core WebGPU is needed, so any adapter will do.

use thiserror::Error;

/// Why no GPU device could be made.
#[derive(Debug, Error)]
pub enum GpuError {
    /// No adapter at all (no GPU driver, no software rasteriser).
    #[error(
        "no graphics adapter found ({0}); install Mesa's lavapipe \
         (apt-get install mesa-vulkan-drivers libvulkan1) and set WGPU_BACKEND=vulkan"
    )]
    NoAdapter(wgpu::RequestAdapterError),
    /// The adapter refused to make a device.
    #[error("the graphics adapter `{adapter}` refused a device: {error}")]
    NoDevice {
        /// The adapter's name.
        adapter: String,
        /// What it said.
        error: wgpu::RequestDeviceError,
    },
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

/// A device and its queue, with the adapter's name for reports.
#[derive(Debug)]
pub struct GpuContext {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// Adapter name and backend, e.g. `llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan)`.
    pub adapter_label: String,
    /// The backend the adapter runs on.
    pub backend: wgpu::Backend,
}

impl GpuContext {
    /// Makes a device on the adapter the environment selects, or the
    /// default one.
    pub fn new_headless() -> Result<Self, GpuError> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle().with_env());
        let adapter = pollster::block_on(wgpu::util::initialize_adapter_from_env_or_default(
            &instance, None,
        ))
        .map_err(GpuError::NoAdapter)?;
        let info = adapter.get_info();
        let adapter_label = format!("{} ({:?})", info.name, info.backend);
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("helixhair"),
            required_limits: adapter.limits(),
            ..Default::default()
        }))
        .map_err(|error| GpuError::NoDevice {
            adapter: adapter_label.clone(),
            error,
        })?;
        Ok(Self {
            device,
            queue,
            adapter_label,
            backend: info.backend,
        })
    }
}
