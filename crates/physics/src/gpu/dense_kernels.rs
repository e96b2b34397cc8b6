//! The Dense kernel's plan: its WGSL, stages, per-element buffers and
//! limits, which [`super::GpuSystem`] builds.
//!
//! How it works (`shaders/physics/dense.wgsl`, arithmetic of
//! [`crate::batch::step::dense`]). Three dispatches per step:
//!
//! | stage | invocations | what it does |
//! | --- | --- | --- |
//! | `stage_frames` | one per strand | root-to-tip chain, A_Q (about the root), B_Q |
//! | `stage_elements` | one per element | own sums with U_Q and V_Q |
//! | `stage_dense` | a workgroup of [`DENSE_WORKGROUP`] per strand | suffix (one invocation), assembly of S = s·M + diag(D) (blocks in parallel), right-looking square-root-free Cholesky S = L D Lᵀ with the forward substitution folded in (rows in parallel, one barrier per column), back substitution (one barrier per row), integrate |
//!
//! Memory. The step matrix is 9N² f32 per strand in a storage buffer
//! (binding 8), so Dense's memory per strand grows as N²: 3.6 KB at
//! N = 10, 14.4 KB at N = 20. The per-element X_Q, Y_Q and the 3N-entry
//! right-hand side and Δv live in workgroup memory: 7.5 KiB for
//! [`MAX_DENSE_ELEMENTS`] = 64, inside the 16 KiB every wgpu device
//! offers (`max_compute_workgroup_storage_size`'s default). Keeping the
//! whole matrix in workgroup memory as well would be faster on a real GPU
//! but stops at N = 21 (36N² bytes ≤ 16 KiB); a strand with more than 64
//! elements is refused with [`GpuError::TooManyElements`].

use super::GpuError;
use super::layout::Span;
use super::layout::{DenseOwnGpu, FrameGpu, JacobiansGpu};

/// `shaders/physics/dense.wgsl`: the three Dense stages.
pub const DENSE_WGSL: &str = include_str!("../../../../shaders/physics/dense.wgsl");

/// Invocations of one `stage_dense` workgroup (WGSL `DENSE_WORKGROUP`):
/// one warp on NVIDIA hardware, so a barrier is cheap there, and the 3N
/// rows of N ≤ 10 update in one pass (N = 20 takes two). Measured against
/// 64 on lavapipe in `docs/gpu.md` (Dense kernel).
pub const DENSE_WORKGROUP: u32 = 32;

/// Most elements per strand the Dense kernel takes (WGSL
/// `MAX_DENSE_ELEMENTS`): the size of its workgroup arrays.
pub const MAX_DENSE_ELEMENTS: usize = 64;

/// Bytes of workgroup memory `stage_dense` declares: X and Y (two
/// mat3x3, 48 bytes each) per element, and 3 floats each of the
/// right-hand side and of Δv per element.
pub const DENSE_WORKGROUP_BYTES: usize = MAX_DENSE_ELEMENTS * (2 * 48 + 2 * 3 * 4);

/// Bytes of the step matrix of one strand of `n` elements.
pub fn matrix_bytes_per_strand(n: usize) -> usize {
    9 * n * n * size_of::<f32>()
}

/// Bindings 5–8 of the Dense kernel, as (label, bytes per element) for a
/// strand of `n` elements: the matrix's 36N² bytes per strand are 36N per
/// element.
pub fn scratch_sizes(n: usize) -> [(&'static str, usize); 4] {
    [
        ("frames", size_of::<FrameGpu>()),
        ("jacobians", size_of::<JacobiansGpu>()),
        ("dense_own", size_of::<DenseOwnGpu>()),
        ("matrix", matrix_bytes_per_strand(n) / n.max(1)),
    ]
}

/// The entry points in dispatch order.
pub(crate) const STAGES: [(&str, Span); 3] = [
    ("stage_frames", Span::PerStrand),
    ("stage_elements", Span::PerElement),
    ("stage_dense", Span::WorkgroupPerStrand),
];

/// Refuses strands the kernel's workgroup arrays cannot hold, or a device
/// with less workgroup memory than they need.
pub fn check(n: usize, limits: &wgpu::Limits) -> Result<(), GpuError> {
    if n > MAX_DENSE_ELEMENTS {
        return Err(GpuError::TooManyElements {
            elements: n,
            max: MAX_DENSE_ELEMENTS,
        });
    }
    let available = limits.max_compute_workgroup_storage_size as u64;
    if (DENSE_WORKGROUP_BYTES as u64) > available {
        return Err(GpuError::TooLarge {
            what: "stage_dense workgroup memory",
            bytes: DENSE_WORKGROUP_BYTES as u64,
            limit_bytes: available,
        });
    }
    Ok(())
}
