//! The errors of the GPU path.
//!
//! The device itself comes from `helixhair-gpu` ([`super::GpuContext`]),
//! the one device setup the renderer and the window share: the adapter the
//! environment picks (`WGPU_BACKEND`, `WGPU_ADAPTER_NAME`) or wgpu's
//! default, with the adapter's own limits (lavapipe caps one storage
//! binding at 128 MiB, which [`GpuError::TooLarge`] reports).

use helixhair_gpu::DeviceError;
use thiserror::Error;

use crate::error::ParamError;

/// Why the GPU path could not run.
#[derive(Debug, Error)]
pub enum GpuError {
    /// No adapter, or no device on it: the caller should fall back to the
    /// CPU ([`super::Stepper::prefer_gpu`] does).
    #[error(transparent)]
    Device(#[from] DeviceError),
    /// A method this GPU path does not run.
    #[error("this GPU path runs {runs}, not `{method}`")]
    UnsupportedMethod {
        /// The method asked for.
        method: String,
        /// What it runs.
        runs: &'static str,
    },
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
    /// A step longer than Mesa's llvmpipe (lavapipe) runs: it ends every
    /// loop of an invocation, silently, once the invocation has run
    /// 65,535 loop iterations in all (docs/gpu.md).
    #[error(
        "lavapipe runs at most {budget} loop iterations per strand and step; a {method} \
         step of {elements} elements with {points} quadrature points and {iterations} GMRES \
         iterations may take {count}"
    )]
    LoopBudget {
        /// The method.
        method: &'static str,
        /// The longest strand's elements.
        elements: usize,
        /// Quadrature points per element.
        points: usize,
        /// Most GMRES iterations.
        iterations: usize,
        /// The step's loop iterations at the worst case, by count.
        count: usize,
        /// Lavapipe's bound.
        budget: usize,
    },
    /// A curve to draw reads a strain the engine does not hold (a layout
    /// made for other strands).
    #[error("a drawn curve reads element {element} of an engine of {engine_elements} elements")]
    CurveSource {
        /// The element read.
        element: usize,
        /// The engine's element count.
        engine_elements: usize,
    },
    /// Mapping a buffer for readback failed.
    #[error("reading GPU memory back failed: {0}")]
    Readback(String),
}
