//! The host side of the shader structs: `#[repr(C)]` plain data with the
//! layouts WGSL gives the structs of the same names in
//! `shaders/common.wgsl` (uniforms) and the vertex inputs of the passes.
//!
//! Sizes are asserted here at compile time, and a test parses the shaders
//! with naga and compares each uniform struct's size with these, so a field
//! added on one side only fails the build or the tests, not the picture.

use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec3, Vec4};

/// One point of view (WGSL `View`): the camera, or the light.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct View {
    /// Clip coordinates from world coordinates, column-major.
    pub clip_from_world: [[f32; 4]; 4],
    /// Eye position (w = 1) or unit direction towards the eye (w = 0).
    pub eye: [f32; 4],
    /// Width and height in pixels, focal length in pixels, narrowest ribbon
    /// in pixels.
    pub viewport: [f32; 4],
    /// Ribbon width at root and tip in metres; two unused.
    pub ribbon: [f32; 4],
}

/// Lights, materials and deep opacity map parameters (WGSL `Lighting`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct Lighting {
    /// The light's clip coordinates from world coordinates.
    pub light_clip_from_world: [[f32; 4]; 4],
    /// Unit direction towards the light; intensity.
    pub light_direction: [f32; 4],
    /// Light colour (linear RGB); unused.
    pub light_colour: [f32; 4],
    /// Ambient colour (linear RGB); ambient strength.
    pub ambient: [f32; 4],
    /// First layer thickness (m), opacity per fragment, light depth range
    /// (m); unused.
    pub shadow: [f32; 4],
    /// Scalp tint (linear RGB); unused.
    pub scalp: [f32; 4],
    /// Primary and secondary highlight shifts and exponents.
    pub specular: [f32; 4],
}

/// One side of one strand point (WGSL `StrandVertex`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct StrandVertex {
    /// Position, metres, world coordinates.
    pub position_m: [f32; 3],
    /// Unit tangent towards the tip.
    pub tangent: [f32; 3],
    /// Linear RGB colour of the strand.
    pub colour: [f32; 3],
    /// Position along the strand (0 root, 1 tip), side (−1 or 1), and a
    /// per-strand random number in [0, 1).
    pub params: [f32; 3],
}

/// One head vertex (WGSL `MeshVertex` in `head.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct MeshVertex {
    /// Position, metres.
    pub position_m: [f32; 3],
    /// Unit normal.
    pub normal: [f32; 3],
    /// 1 on the scalp, 0 elsewhere.
    pub scalp: f32,
}

const _: () = assert!(size_of::<View>() == 112);
const _: () = assert!(size_of::<Lighting>() == 160);
const _: () = assert!(size_of::<StrandVertex>() == 48);
const _: () = assert!(size_of::<MeshVertex>() == 28);

impl StrandVertex {
    /// The attributes of `@location(0..4)`.
    pub const ATTRIBUTES: [wgpu::VertexAttribute; 4] =
        wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x3, 3 => Float32x3];
}

impl MeshVertex {
    /// The attributes of `@location(0..3)`.
    pub const ATTRIBUTES: [wgpu::VertexAttribute; 3] =
        wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32];
}

/// The layout of a buffer of `V`s, one per vertex, with `attributes`.
pub fn vertex_layout<V>(
    attributes: &'static [wgpu::VertexAttribute],
) -> wgpu::VertexBufferLayout<'static> {
    wgpu::VertexBufferLayout {
        array_stride: size_of::<V>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes,
    }
}

/// A column-major matrix as WGSL's `mat4x4<f32>`.
pub fn mat(m: Mat4) -> [[f32; 4]; 4] {
    m.to_cols_array_2d()
}

/// `xyz` and `w` as one `vec4<f32>`.
pub fn vec4(xyz: Vec3, w: f32) -> [f32; 4] {
    Vec4::from((xyz, w)).to_array()
}
