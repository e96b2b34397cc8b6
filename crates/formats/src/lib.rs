//! Reads and writes hair curve files, knowing nothing of physics, rendering
//! or windows.
//!
//! A groom is a [`CurveSet`]: polylines in `f32` metres, Y up, root first,
//! with optional widths and colours per strand or per point, and
//! [`Metadata`] saying where it came from. Moving hair adds an
//! [`Animation`] (frames of points over the same strands).
//!
//! | format | read | written |
//! | --- | --- | --- |
//! | AMD TressFX `.tfx` ([`tfx`]) | 4.x and 3.x: points, colours | 4.0, one frame |
//! | Cem Yuksel's `.hair` ([`hair`]) | points, thickness, colours | the same, one frame |
//! | USD `.usda` ([`usda`]) | `BasisCurves`: points, time samples, widths, colours, transforms, units | the same, plus a head `Mesh` |
//! | USD `.usdc`, `.usd` ([`usdc`]) | the same, from binary crate files (a text `.usd` as `.usda`) | the same, crate version 0.8.0 |
//! | USD `.usdz` ([`usdc::usdz`]) | the package's first layer (`.usdc` or `.usda`) | one `.usdc` layer |
//! | OBJ ([`obj`]) | `l` polylines (chained), `v` points | one frame |
//! | Alembic `.abc` ([`abc`]) | Ogawa `AbcGeom` curves: points, time samples, widths, transforms | the same, plus a head `PolyMesh` |
//!
//! # How it works
//!
//! 1. **Decode**: a reader turns the file's bytes into strands, checking
//!    every count against the file's length before allocating (so a hostile
//!    header cannot exhaust memory; see [`mod@read`] for the bound) and
//!    reporting problems with a byte offset or a line ([`ReadError`]).
//! 2. **Units and axes**: points become metres, Y up ([`ReadOptions`] for
//!    formats that do not say).
//! 3. **Repair**: degenerate strands are repaired or skipped one by one,
//!    never the whole groom ([`repair`], [`RepairSummary`]).
//!
//! Writers check everything first, then write to any [`std::io::Write`] in
//! one call, so a caller doing atomic replacement never renames half a file.
//! [`read()`] picks a reader by [`Format`], [`write()`] a writer; `docs/formats.md` at the
//! repository root has limits, error examples and fuzzing figures.

#![warn(missing_docs)]

pub mod abc;
pub mod animation;
mod bytes;
pub mod curve_set;
pub mod error;
pub mod format;
pub mod hair;
pub mod imported;
pub mod mesh;
pub mod obj;
pub mod options;
pub mod read;
pub mod repair;
pub mod tfx;
pub mod usda;
pub mod usdc;
mod warnings;
pub mod write;

pub use abc::read_abc;
pub use abc::write::write_abc;
pub use animation::{Animation, Frame};
pub use curve_set::{Curve, CurveSet, Metadata, StrandValue, UpAxis};
pub use error::{Location, ReadError, ReadErrorKind, WriteError};
pub use format::Format;
pub use hair::{read_hair, write_hair};
pub use mesh::{MeshPose, TriangleMesh};
pub use obj::{read_obj, write_obj};
pub use options::ReadOptions;
pub use read::{Imported, read};
pub use repair::{RepairReason, RepairSummary};
pub use tfx::{read_tfx, write_tfx};
pub use usda::read_usda;
pub use usda::write::{write_usda, write_usda_with_head_poses};
pub use usdc::read_usdc;
pub use usdc::usdz::{read_usdz, write_usdz};
pub use usdc::write::write_usdc;
pub use write::write;
