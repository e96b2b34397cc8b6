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

use std::sync::{Arc, Mutex};

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
    /// The device stopped working after it was made: lost (driver reset,
    /// GPU removed, destroyed) or an operation on it failed. Nothing drawn
    /// or stepped on it since can be trusted; the caller reports it.
    #[error("the graphics device stopped working: {0}")]
    Lost(String),
}

/// What went wrong with a device after it was made, as wgpu reports it:
/// through the device-lost callback and the uncaptured-error handler,
/// which [`GpuContext`] installs so that neither panics (wgpu's default
/// handler panics on the first error). Users ask [`GpuContext::check`]
/// after waiting for the GPU.
#[derive(Debug, Default)]
pub struct DeviceHealth {
    first_problem: Mutex<Option<String>>,
}

impl DeviceHealth {
    /// Keeps `problem` unless an earlier one is kept (the first is the
    /// cause; later ones follow from it).
    fn record(&self, problem: String) {
        // A poisoned lock still holds the first problem.
        let mut first = self
            .first_problem
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        first.get_or_insert(problem);
    }

    /// The first problem seen, if any.
    pub fn problem(&self) -> Option<String> {
        self.first_problem
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .clone()
    }
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
    /// Whether the device still works ([`Self::check`]).
    pub health: Arc<DeviceHealth>,
}

impl GpuContext {
    /// Whether `other` is this very device (a clone of this context), not
    /// merely an equal-looking one: wgpu's ids repeat across instances, so
    /// two devices of two instances can compare equal.
    pub fn same_device(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.health, &other.health)
    }

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
        let health = Arc::new(DeviceHealth::default());
        let on_lost = health.clone();
        device.set_device_lost_callback(move |reason, message| {
            on_lost.record(format!("device lost ({reason:?}): {message}"));
        });
        let on_error = health.clone();
        device.on_uncaptured_error(Arc::new(move |error: wgpu::Error| {
            on_error.record(error.to_string());
        }));
        Ok(Self {
            adapter,
            device,
            queue,
            adapter_name: info.name,
            backend: info.backend,
            limits,
            health,
        })
    }

    /// `Ok` while the device works; the first problem wgpu reported
    /// otherwise (lost, or an operation that failed). Call it after waiting
    /// for the GPU, before trusting what was read back.
    pub fn check(&self) -> Result<(), DeviceError> {
        match self.health.problem() {
            None => Ok(()),
            Some(problem) => Err(DeviceError::Lost(problem)),
        }
    }

    /// Adapter name and backend for reports, e.g.
    /// `llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan)`.
    pub fn adapter_label(&self) -> String {
        format!("{} ({:?})", self.adapter_name, self.backend)
    }
}
