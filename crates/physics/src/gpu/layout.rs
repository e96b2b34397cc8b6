//! Host twins of the WGSL structs in `shaders/physics/common.wgsl`, `#[repr(C)]`
//! plain data (bytemuck), with every vec3 padded to a vec4 and every
//! mat3x3 stored as three vec4 columns, as WGSL lays them out in storage and
//! uniform buffers. `tests/gpu_layout.rs` checks sizes and member offsets
//! against the shader, reflected by naga; [`size_asserts`] pins the sizes at
//! compile time.

use bytemuck::{Pod, Zeroable};

use crate::batch::vec::{M3, V3};

/// A WGSL `mat3x3<f32>`: three columns padded to 16 bytes.
pub type Mat3Gpu = [[f32; 4]; 3];

/// Uniforms of one step (WGSL `Params`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct ParamsGpu {
    /// Number of strands.
    pub strand_count: u32,
    /// Elements per strand N.
    pub elements: u32,
    /// Quadrature points per element (≤ 8).
    pub points: u32,
    /// Padding.
    pub pad0: u32,
    /// Step h, seconds.
    pub h_secs: f32,
    /// ρS, kg/m.
    pub mass_per_length: f32,
    /// ν, N·s/m².
    pub air_drag: f32,
    /// s = 1 + hν/ρS.
    pub mass_scale: f32,
    /// Gravity, m/s² (w unused).
    pub gravity_m_per_s2: [f32; 4],
    /// Air velocity, m/s (w unused).
    pub air_velocity_m_per_s: [f32; 4],
    /// Quadrature nodes, 4 per vec4.
    pub nodes: [[f32; 4]; 2],
    /// Quadrature weights, 4 per vec4.
    pub weights: [[f32; 4]; 2],
    /// Head rotation, world from head.
    pub head_rotation: Mat3Gpu,
    /// Head angular velocity, rad/s.
    pub head_angular_velocity: [f32; 4],
    /// Head angular acceleration, rad/s².
    pub head_angular_acceleration: [f32; 4],
    /// Velocity of the head origin, m/s.
    pub head_velocity: [f32; 4],
    /// Acceleration of the head origin, m/s².
    pub head_acceleration: [f32; 4],
}

/// Per-element constants (WGSL `ElementConst`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct ElementConstGpu {
    /// (K_Q in N·m³, ℓ_Q in m).
    pub stiffness_length: [f32; 4],
    /// (qⁿ_Q in m⁻¹, γℓ_Q in N·m³·s).
    pub natural_friction: [f32; 4],
}

/// A root on the head (WGSL `RootPose`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct RootPoseGpu {
    /// Root point in head coordinates, m.
    pub position_m: [f32; 4],
    /// Root frame in head coordinates.
    pub head_from_root: Mat3Gpu,
}

/// Frame state at an element start (WGSL `Frame`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct FrameGpu {
    /// R_Q.
    pub frame: Mat3Gpu,
    /// ω, rad/s.
    pub angular_velocity: [f32; 4],
    /// α, rad/s².
    pub angular_acceleration: [f32; 4],
    /// p_Q relative to the root point, m: what a renderer draws.
    pub point_m: [f32; 4],
    /// ṗ_Q, m/s.
    pub point_velocity: [f32; 4],
    /// p̈_Q, m/s².
    pub point_acceleration: [f32; 4],
}

/// A_Q and B_Q (WGSL `Jacobians`), and the element's span.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct JacobiansGpu {
    /// A_Q, m²: about the element's end point for Block-diagonal and
    /// Exact (local moments), about the root for Dense.
    pub a: Mat3Gpu,
    /// B_Q, m.
    pub b: Mat3Gpu,
    /// End point minus start point, m (zero for Dense).
    pub span: [f32; 4],
}

/// An element's own sums (WGSL `Own`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct OwnGpu {
    /// D_Q.
    pub mass_block: Mat3Gpu,
    /// Own inertia about the root point.
    pub inertia: Mat3Gpu,
    /// Σ GᵀF.
    pub force: [f32; 4],
    /// (first moment, mass).
    pub moment: [f32; 4],
    /// Σ wF.
    pub force_sum: [f32; 4],
    /// Σ w r×F.
    pub torque_sum: [f32; 4],
}

/// Suffix sums past an element (WGSL `Beyond`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct BeyondGpu {
    /// I past the element.
    pub inertia: Mat3Gpu,
    /// (c, m) past the element.
    pub moment: [f32; 4],
    /// Force past the element.
    pub force: [f32; 4],
    /// Torque past the element.
    pub torque: [f32; 4],
}

/// What Exact's elimination keeps per element (WGSL `Elimination` of
/// `engine.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct EliminationGpu {
    /// W̃ top.
    pub w_top: Mat3Gpu,
    /// W̃ bottom.
    pub w_bottom: Mat3Gpu,
    /// S̃⁻¹.
    pub s_inv: Mat3Gpu,
    /// r̃.
    pub rhs: [f32; 4],
}

/// An element's own sums with U_Q and V_Q (WGSL `DenseOwn`, Dense only).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct DenseOwnGpu {
    /// The sums Block-diagonal also needs.
    pub own: OwnGpu,
    /// U_Q = Σ_own wρS G, kg·m.
    pub u: Mat3Gpu,
    /// V_Q = Σ_own wρS \[r\]×G, kg·m².
    pub v: Mat3Gpu,
}

/// Uniforms of one step of the GPU engine (WGSL `Params` of
/// `shaders/physics/engine.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct EngineParamsGpu {
    /// Number of strands.
    pub strand_count: u32,
    /// Quadrature points per element (≤ 8).
    pub points: u32,
    /// Most GMRES iterations (0: the velocity-explicit answer).
    pub iterations: u32,
    /// 1 with a head collider, else 0.
    pub has_collider: u32,
    /// Step h, seconds.
    pub h_secs: f32,
    /// GMRES's stopping fraction of |rhs| ([`crate::gmres::GMRES_TOLERANCE`]).
    pub gmres_tolerance: f32,
    /// Contact skin, m.
    pub skin_m: f32,
    /// α of the implicit contact.
    pub implicit_stiffness_ratio: f32,
    /// Cap on the contact acceleration, m/s².
    pub max_acceleration_m_per_s2: f32,
    /// The field's grid spacing, m.
    pub field_cell_m: f32,
    /// The step's method: WGSL `METHOD_EXACT` (0) or `METHOD_BLOCK` (1).
    pub method: u32,
    /// Vectors per element in the `krylov` buffer (WGSL `KRYLOV_SLOTS`, or
    /// `BLOCK_SLOTS` for Block-diagonal).
    pub slots: u32,
    /// The field's grid points along x, y, z (w unused).
    pub field_dims: [u32; 4],
    /// The field's grid point (0, 0, 0), head coordinates, m.
    pub field_origin_m: [f32; 4],
    /// Gravity, m/s² (w unused).
    pub gravity_m_per_s2: [f32; 4],
    /// Air velocity, m/s (w unused).
    pub air_velocity_m_per_s: [f32; 4],
    /// Quadrature nodes, 4 per vec4.
    pub nodes: [[f32; 4]; 2],
    /// Quadrature weights, 4 per vec4.
    pub weights: [[f32; 4]; 2],
    /// Head rotation, world from head.
    pub head_rotation: Mat3Gpu,
    /// Head origin, world, m.
    pub head_position_m: [f32; 4],
    /// Head angular velocity, rad/s.
    pub head_angular_velocity: [f32; 4],
    /// Head angular acceleration, rad/s².
    pub head_angular_acceleration: [f32; 4],
    /// Velocity of the head origin, m/s.
    pub head_velocity: [f32; 4],
    /// Acceleration of the head origin, m/s².
    pub head_acceleration: [f32; 4],
    /// θ h, s: the step Block-diagonal's GMRES takes its velocity terms
    /// with ([`crate::batch::step::block_implicit::BLOCK_THETA`] times the step), rounded once.
    pub block_h_secs: f32,
    /// Padding.
    pub pad: [f32; 3],
}

/// One strand of the GPU engine (WGSL `Strand`): where its elements lie in
/// the per-element buffers, its own ρS and ν, and its root.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct StrandGpu {
    /// Its first element's index in every per-element buffer.
    pub first: u32,
    /// Its element count N.
    pub elements: u32,
    /// Its index among the engine's strands (the table is in the order
    /// the invocations take them, [`crate::gpu::GpuEngine`]).
    pub index: u32,
    /// Padding.
    pub pad0: u32,
    /// ρS, kg/m.
    pub mass_per_length: f32,
    /// ν, N·s/m².
    pub air_drag: f32,
    /// Padding.
    pub pad1: [f32; 2],
    /// Root point in head coordinates, m.
    pub position_m: [f32; 4],
    /// Root frame in head coordinates.
    pub head_from_root: Mat3Gpu,
}

/// What the engine's sweep 1 leaves per element (WGSL `ElementData`, the
/// twin of [`crate::batch::layout::ElementData`]).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct ElementDataGpu {
    /// A_Q, about the element's end point.
    pub a: Mat3Gpu,
    /// B_Q.
    pub b: Mat3Gpu,
    /// D_Q.
    pub own_mass_block: Mat3Gpu,
    /// Own inertia about the element's start point.
    pub inertia: Mat3Gpu,
    /// U_Q.
    pub u: Mat3Gpu,
    /// V_Q.
    pub v: Mat3Gpu,
    /// The contact's point inertias, four 3×3 blocks.
    pub contact: [Mat3Gpu; 4],
    /// Σ GᵀF.
    pub own_force: [f32; 4],
    /// (first moment, mass).
    pub moment: [f32; 4],
    /// Σ wF.
    pub force_sum: [f32; 4],
    /// Σ w r×F.
    pub torque_sum: [f32; 4],
    /// End point minus start point; w is 1 where a sample touched.
    pub span: [f32; 4],
}

/// Compile-time sizes, equal to the WGSL sizes the layout test reflects.
pub mod size_asserts {
    use super::*;
    const _: () = assert!(std::mem::size_of::<ParamsGpu>() == 240);
    const _: () = assert!(std::mem::size_of::<ElementConstGpu>() == 32);
    const _: () = assert!(std::mem::size_of::<RootPoseGpu>() == 64);
    const _: () = assert!(std::mem::size_of::<FrameGpu>() == 128);
    const _: () = assert!(std::mem::size_of::<JacobiansGpu>() == 112);
    const _: () = assert!(std::mem::size_of::<OwnGpu>() == 160);
    const _: () = assert!(std::mem::size_of::<BeyondGpu>() == 96);
    const _: () = assert!(std::mem::size_of::<EliminationGpu>() == 160);
    const _: () = assert!(std::mem::size_of::<DenseOwnGpu>() == 256);
    const _: () = assert!(std::mem::size_of::<EngineParamsGpu>() == 320);
    const _: () = assert!(std::mem::size_of::<StrandGpu>() == 96);
    const _: () = assert!(std::mem::size_of::<ElementDataGpu>() == 560);
}

/// A vec3 padded to a WGSL vec4.
pub fn v4(v: V3<f32>) -> [f32; 4] {
    [v.x, v.y, v.z, 0.0]
}

/// The xyz of a padded vec4.
pub fn v3(v: [f32; 4]) -> V3<f32> {
    V3::new(v[0], v[1], v[2])
}

/// A matrix as padded columns.
pub fn m4(m: &M3<f32>) -> Mat3Gpu {
    [v4(m.c0), v4(m.c1), v4(m.c2)]
}

/// Padded columns as a matrix.
pub fn m3(m: &Mat3Gpu) -> M3<f32> {
    M3::from_cols(v3(m[0]), v3(m[1]), v3(m[2]))
}

/// How many invocations a stage runs.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Span {
    /// One invocation per strand (workgroups of 64).
    PerStrand,
    /// One invocation per element (workgroups of 64).
    PerElement,
    /// One workgroup per strand.
    WorkgroupPerStrand,
}
