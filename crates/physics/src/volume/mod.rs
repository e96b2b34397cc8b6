//! Hair with volume: hair–hair interaction through a grid.
//!
//! Strands of the same head would otherwise pass through each other, and
//! a full head sags into a thin shell on the skull. Pairwise collisions
//! between thousands of strands are too slow to be interactive, so, like
//! Petrovic et al. 2005 ("Volumetric methods for simulation and rendering
//! of hair", Pixar), McAdams et al. 2009 and the tools artists use
//! (Blender's hair volume: internal friction, a voxel cell size, a density
//! target and strength; Unreal's Niagara groom solver and its pressure
//! grid), the model treats the hair as a continuum on a grid:
//!
//! 1. [`grid`]: a box of cubic cells fitted to the head's hair at rest,
//!    fixed in head coordinates; a trilinear stencil ties a point to the
//!    eight nodes around it. [`cell`] finds a point's cell and weights,
//!    once per point and frame: the splat finds it and the read-back
//!    reuses it.
//! 2. [`pair_points`]: the hair is sampled by one point per pair of an
//!    element's quadrature nodes, the pair's centre of mass, with its mass
//!    and mean velocity. [`splat`]: every point spreads its mass and
//!    momentum onto the nodes: density and mean velocity of the hair
//!    around each node.
//! 3. [`rest`]: the density of the groom's rest pose, node by node, sets
//!    the threshold above which hair is compressed; at rest nothing is.
//! 4. [`friction`]: each quadrature sample's velocity is pulled toward
//!    the grid's at its point, a drag toward a velocity field, implicit in
//!    the step exactly as air drag is.
//! 5. [`pressure`]: samples whose point is in nodes denser than their
//!    threshold are pushed down the excess's gradient (an equation of
//!    state, no solve).
//!
//! [`field`] runs 2–5 on any set of points, and each engine only gathers its
//! points and hands out the answers: [`reference`](mod@reference) is the f64
//! `HairSystem`'s use of it (once per frame, before the strands step, it
//! gathers every strand's points, splats them and hands each strand its pull,
//! [`friction::VolumePull`], which the step adds to its forces and to its drag
//! rate), and `crate::batch::volume` the f32 batch engine's (an f32 gather per
//! SIMD batch, the same f64 splat and read, and a per-sample pull in the batch
//! step, `crate::batch::volume::pull`). [`state`] is what both keep between frames;
//! [`balance`] counts the model's work in the guard's energy balance, and
//! exchanges the old pull's work for the new one's in the reused start-of-frame
//! measure.
//! [`settings`] holds the knobs.
//!
//! What is left out: the GPU kernels do not run the model
//! (`docs/gpu.md`); the grid is splatted once per frame, so with several
//! substeps the grid velocity and push are those of the frame's start.

pub mod balance;
pub mod cell;
pub mod field;
pub mod friction;
pub mod grid;
pub mod pair_points;
pub mod pressure;
pub mod reference;
pub mod rest;
pub mod settings;
pub mod splat;
pub mod splat_lanes;
pub mod state;

pub use field::{SampleReading, VolumeField};
pub use friction::VolumePull;
pub use grid::Grid;
pub use reference::ReferenceVolume;
pub use rest::RestDensity;
pub use settings::InteractionSettings;
pub use splat::SamplePoint;
pub use state::ModelState;
