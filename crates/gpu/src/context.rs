//! The device every GPU part of HelixHair runs on.
//!
//! # How the adapter is chosen
//!
//! `wgpu::util::initialize_adapter_from_env_or_default`: `WGPU_BACKEND`
//! (e.g. `vulkan`, which picks Mesa's lavapipe on a machine without a GPU)
//! and `WGPU_ADAPTER_NAME` when set, otherwise wgpu's default adapter
//! (compatible with the window's surface when there is one). The device
//! asks for the adapter's own limits, so large buffers and textures work
//! where the hardware allows them (lavapipe caps one storage binding at
//! 128 MiB); what each user needs beyond that it checks itself.

use thiserror::Error;

/// Why no device could be made. Both are normal on a machine without a
/// GPU driver: callers fall back (the physics' CPU path) or report the
/// message (the renderer, the window), never panic.
#[derive(Debug, Error)]
pub enum DeviceError {
    /// No adapter at all (no GPU driver, no software rasteriser, or the
    /// environment hides them).
    #[error(
        "no graphics adapter found ({0}); install a GPU driver, or Mesa's lavapipe \
         (apt-get install mesa-vulkan-drivers libvulkan1) and set WGPU_BACKEND=vulkan"
    )]
    NoAdapter(String),
    /// The adapter refused to make a device.
    #[error("the graphics adapter `{adapter}` refused a device: {reason}")]
    NoDevice {
        /// The adapter's name and backend.
        adapter: String,
        /// What wgpu said.
        reason: String,
    },
}

/// An adapter, its device and queue, and what reports say about it.
#[derive(Clone, Debug)]
pub struct GpuContext {
    /// The adapter the device was made on (the window asks it for the
    /// surface's formats).
    pub adapter: wgpu::Adapter,
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// The adapter's name, e.g. `llvmpipe (LLVM 15.0.6, 256 bits)`.
    pub adapter_name: String,
    /// The backend the adapter runs on.
    pub backend: wgpu::Backend,
    /// The device's limits (the adapter's own).
    pub limits: wgpu::Limits,
}

impl GpuContext {
    /// A device with no window, on the adapter the environment picks.
    pub fn new_headless() -> Result<Self, DeviceError> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle().with_env());
        Self::open(&instance, None)
    }

    /// A device that can draw to `surface` (made from `instance`).
    pub fn for_surface(
        instance: &wgpu::Instance,
        surface: &wgpu::Surface<'_>,
    ) -> Result<Self, DeviceError> {
        Self::open(instance, Some(surface))
    }

    fn open(
        instance: &wgpu::Instance,
        surface: Option<&wgpu::Surface<'_>>,
    ) -> Result<Self, DeviceError> {
        let adapter = pollster::block_on(wgpu::util::initialize_adapter_from_env_or_default(
            instance, surface,
        ))
        .map_err(|e| DeviceError::NoAdapter(e.to_string()))?;
        let info = adapter.get_info();
        let limits = adapter.limits();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("helixhair"),
            required_limits: limits.clone(),
            ..Default::default()
        }))
        .map_err(|e| DeviceError::NoDevice {
            adapter: format!("{} ({:?})", info.name, info.backend),
            reason: e.to_string(),
        })?;
        Ok(Self {
            adapter,
            device,
            queue,
            adapter_name: info.name,
            backend: info.backend,
            limits,
        })
    }

    /// Adapter name and backend for reports, e.g.
    /// `llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan)`.
    pub fn adapter_label(&self) -> String {
        format!("{} ({:?})", self.adapter_name, self.backend)
    }
}
