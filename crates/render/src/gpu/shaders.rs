//! The WGSL sources, from the top-level `shaders/` folder.
//!
//! WGSL has no `#include`: each pass's file is compiled with
//! `shaders/common.wgsl` (structs, bindings, ribbon expansion, the deep
//! opacity lookup) put in front of it. [`composed`] does that, for the
//! renderer and for the test that validates every shader without a GPU.

/// `shaders/common.wgsl`: what every pass shares.
pub const COMMON: &str = include_str!("../../../../shaders/common.wgsl");

/// One pass's shader file.
#[derive(Clone, Copy, Debug)]
pub struct ShaderFile {
    /// File name in `shaders/`.
    pub name: &'static str,
    /// Its text (without the common part).
    pub source: &'static str,
}

/// Hair ribbons, shaded (`vs_hair`, `fs_hair`).
pub const HAIR: ShaderFile = ShaderFile {
    name: "hair.wgsl",
    source: include_str!("../../../../shaders/hair.wgsl"),
};

/// The deep opacity map passes (`vs_shadow`, `fs_opacity`).
pub const HAIR_SHADOW: ShaderFile = ShaderFile {
    name: "hair_shadow.wgsl",
    source: include_str!("../../../../shaders/hair_shadow.wgsl"),
};

/// The head (`vs_head`, `fs_head`).
pub const HEAD: ShaderFile = ShaderFile {
    name: "head.wgsl",
    source: include_str!("../../../../shaders/head.wgsl"),
};

/// The backdrop (`vs_backdrop`, `fs_backdrop`).
pub const BACKDROP: ShaderFile = ShaderFile {
    name: "backdrop.wgsl",
    source: include_str!("../../../../shaders/backdrop.wgsl"),
};

/// Every pass's file.
pub const ALL: [ShaderFile; 4] = [HAIR, HAIR_SHADOW, HEAD, BACKDROP];

/// Ribbons built from strand points on the device (`stage_ribbons`,
/// [`super::device_hair`]): a compute pass, compiled alone (it declares
/// its own bindings and none of `common.wgsl`'s).
pub const RIBBONS: ShaderFile = ShaderFile {
    name: "ribbons.wgsl",
    source: include_str!("../../../../shaders/ribbons.wgsl"),
};

/// Drawn strands shaped by their guides on the device
/// (`stage_guide_shapes`, `stage_shape`, [`super::device_shape`]): compute
/// passes, compiled alone.
pub const STRAND_SHAPE: ShaderFile = ShaderFile {
    name: "strand_shape.wgsl",
    source: include_str!("../../../../shaders/strand_shape.wgsl"),
};

/// The files compiled without `common.wgsl`.
pub const ALONE: [ShaderFile; 2] = [RIBBONS, STRAND_SHAPE];

/// The source a pass is compiled from: the common part, then the file.
pub fn composed(file: &ShaderFile) -> String {
    format!("{COMMON}\n// ---- {} ----\n{}", file.name, file.source)
}

/// Compiles `file` into a shader module.
pub fn module(device: &wgpu::Device, file: &ShaderFile) -> wgpu::ShaderModule {
    device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(file.name),
        source: wgpu::ShaderSource::Wgsl(composed(file).into()),
    })
}
