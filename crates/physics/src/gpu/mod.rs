//! The GPU path (cargo feature `gpu`): the GPU engine's step (Exact and
//! Block-diagonal) and the Dense kernel as wgpu compute shaders, with a
//! CPU twin for every kernel stage.
//!
//! - [`GpuContext`]: the headless device, from `helixhair-gpu` (the one
//!   device setup of the workspace); [`error`]: [`GpuError`] (no adapter
//!   is an error the caller turns into a CPU fallback:
//!   [`Stepper::prefer_gpu`] does it with a message).
//! - [`layout`]: host structs of the WGSL structs, checked against the
//!   shaders by `tests/gpu_layout.rs`.
//! - [`engine`]: [`GpuEngine`], the CPU engines' one step, Exact and
//!   Block-diagonal (velocity-implicit with GMRES, the head's implicit
//!   contact, each strand's own constants) on the GPU; [`engine_twin`] its
//!   CPU twin, the batch engine's step at f32 one strand wide.
//! - [`curves`]: the strands' centrelines written on the engine's device
//!   for a renderer (the points buffer's layout is documented there), and
//!   the CPU twin of that stage.
//! - [`measure`]: the guard's measure of every strand on the engine's
//!   device, so that a frame reads back one measure per strand instead of
//!   the state, and its CPU twin, the batch engine's measure at f32.
//! - [`kernels`]: [`GpuSystem`], the velocity-explicit Dense kernel (one
//!   strand's constants shared by all), and the buffer and dispatch
//!   helpers both paths use.
//! - [`dense_kernels`]: the Dense kernel's stages, buffers and limits (a
//!   workgroup per strand factoring its 3N×3N step matrix).
//! - [`twin`]: the CPU twin of the Dense kernel's frame chain and its
//!   buffer conversions; [`dense_twin`] those of its other stages.
//!
//! The WGSL lives in the top-level `shaders/physics/` folder (`common.wgsl`,
//! `engine.wgsl`, `group.wgsl` (the uniform group of [`GpuSystem`]),
//! `chain.wgsl` (its frame chain), `dense.wgsl`; the renderer's shaders are the
//! files directly in `shaders/`), included with `include_str!`.
//! `docs/gpu.md` explains the stage split and how a renderer reads the
//! state without a readback.

pub mod curves;
pub mod dense_kernels;
pub mod dense_twin;
pub mod engine;
pub mod engine_twin;
pub mod error;
pub mod kernels;
pub mod layout;
pub mod measure;
pub mod twin;

pub use engine::GpuEngine;
pub use error::GpuError;
pub use helixhair_gpu::GpuContext;
pub use kernels::GpuSystem;

use crate::batch::BatchSystem;
use crate::error::ParamError;
use crate::motion::{HeadTrajectory, RootPose};
use crate::params::StrandParams;
use crate::settings::{Method, SimSettings};

/// A group of strands on the Dense kernel of [`GpuSystem`], or on the CPU
/// batch path when it cannot run (no adapter, Dense past its element
/// limit; Exact and Block-diagonal, which run on the GPU engine,
/// `engine: Gpu`, [`crate::engine::GpuSide`]).
#[derive(Debug)]
pub enum Stepper {
    /// Stepped by the kernels.
    Gpu(Box<GpuSystem>),
    /// Stepped by [`BatchSystem`].
    Cpu(Box<BatchSystem>),
}

impl Stepper {
    /// The GPU path if an adapter exists, else the CPU batch path; the
    /// message says which and why (print it: it is the user's clear sign
    /// that the GPU was not used).
    pub fn prefer_gpu(
        settings: &SimSettings,
        params: &StrandParams,
        roots: &[RootPose],
    ) -> Result<(Self, String), ParamError> {
        let gpu = GpuContext::new_headless()
            .map_err(GpuError::from)
            .and_then(|ctx| GpuSystem::new(ctx, settings, params, roots));
        match gpu {
            Ok(system) => {
                let message = format!("physics on the GPU ({})", system.adapter_name());
                Ok((Stepper::Gpu(Box::new(system)), message))
            }
            Err(GpuError::Param(e)) => Err(e),
            Err(e) => {
                // The batch path has no Dense; Exact solves the same step
                // matrix to round-off in O(N).
                let (cpu_settings, note) = if settings.method == Method::Dense {
                    let exact = SimSettings {
                        method: Method::Exact,
                        ..settings.clone()
                    };
                    (exact, " with Exact (Dense's answer in O(N))")
                } else {
                    (settings.clone(), "")
                };
                let mut cpu = BatchSystem::new(cpu_settings)?;
                cpu.add_group(params, roots)?;
                let message = format!("{e}; falling back to the CPU batch path{note}");
                Ok((Stepper::Cpu(Box::new(cpu)), message))
            }
        }
    }

    /// Advances one frame on whichever path holds the strands.
    pub fn step_frame(&mut self, head: &dyn HeadTrajectory) {
        match self {
            Stepper::Gpu(g) => g.step_frame(head),
            Stepper::Cpu(c) => c.step_frame(head),
        }
    }
}
