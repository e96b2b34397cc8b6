//! Everything that talks to wgpu: the device, the host side of the shader
//! structs, the shaders, the pipelines and the offscreen renderer.

pub mod context;
pub mod device_hair;
pub mod device_shape;
pub mod frame_data;
pub mod gpu_data;
pub mod offscreen;
pub mod passes;
pub mod readback;
pub mod settings;
pub mod shaders;
pub mod shadow;
pub mod targets;
