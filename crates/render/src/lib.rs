//! Draws hair strands and a head mesh from plain buffers.
//!
//! The renderer knows nothing of the physics: it takes strand polylines
//! ([`StrandBuffers`], points per strand plus offsets) with a colour per
//! strand, and a triangle mesh ([`Mesh`], [`HeadMesh`]). The physics can
//! therefore feed it from CPU memory now and from GPU buffers later.
//!
//! # How it works
//!
//! - **Strands** are drawn as ribbons that face the camera: every point is
//!   uploaded twice ([`ribbons`]) and the vertex shader pushes the two
//!   copies apart across the strand's screen-space direction, tapering from
//!   root to tip. Strands thinner than a pixel are drawn a pixel wide with
//!   partial coverage, which 4× MSAA turns into antialiased, order-free
//!   transparency (a random subset of the samples per strand and pixel,
//!   so overlapping thin strands add up).
//! - **Fibre shading**: Kajiya–Kay diffuse plus Marschner-style R, TRT and
//!   TT lobes from shifted tangents, evaluated per strand point
//!   (`shaders/hair.wgsl`).
//! - **Self-shadowing**: a deep opacity map from the key light
//!   ([`gpu::shadow`]) makes a dense groom read as a volume.
//! - The **head** is lit with wrapped diffuse and receives the hair's
//!   shadow; a neutral **backdrop** fills the rest.
//! - The **orbit camera** ([`camera`]) is math only; windows own input.
//!
//! Besides drawing, this crate owns the head's geometry: the default head
//! ([`head_generate`]), OBJ heads ([`obj`]), even root placement on the
//! scalp ([`scalp_sampling`]) and render strands interpolated from guides
//! ([`interpolate`]). All of it is plain `f32` geometry.
//!
//! Shaders live in the workspace's `shaders/` folder ([`gpu::shaders`]) and
//! are validated by a test that needs no GPU.

#![warn(missing_docs)]

pub mod camera;
pub mod gpu;
pub mod head_generate;
pub mod head_shell;
pub mod interpolate;
pub mod mesh;
pub mod obj;
pub mod obj_locate;
pub mod ribbons;
pub mod rng;
pub mod scalp_sampling;
pub mod scene;
pub mod strand_buffers;
pub mod strand_shape;

pub use camera::OrbitCamera;
pub use gpu::context::{GpuContext, GpuError};
pub use gpu::offscreen::OffscreenRenderer;
pub use gpu::readback::RgbaImage;
pub use gpu::settings::RenderSettings;
pub use mesh::{HeadMesh, Mesh};
pub use scene::{HairStrands, Light, Scene};
pub use strand_buffers::StrandBuffers;
