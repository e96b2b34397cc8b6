//! Alembic (`.abc`, Ogawa): curves read and written, by hand.
//!
//! # Why by hand
//!
//! No maintained Rust crate writes Alembic, and the one reader
//! (`ogawa-rs`) calls itself a work in progress that partially reads
//! curves; the official library is C++ (with HDF5 and Imath). The format
//! under Unreal's and Maya's groom pipelines is small: Ogawa, a tree of
//! groups and data blocks ([`ogawa`]); Alembic's objects, properties,
//! samples and time samplings over it ([`archive`]); the curves schema
//! ([`curves`]). PyAlembic (`alembic3d` on PyPI) checks this module in
//! the tests, both ways.
//!
//! # How reading works
//!
//! The archive's root gives its time samplings and top object; objects
//! are walked depth first (at most [`archive::MAX_DEPTH`] deep), their
//! `Xform`s composed, and every `AbcGeom_Curve` object's points, counts
//! and widths read at every sample ([`curves`]). Every offset and count
//! is checked and every decoded value charged to a budget proportional to
//! the file's size, so a hostile file gives an error at a byte offset,
//! never a panic or an allocation its size does not justify. HDF5
//! Alembic files (before Alembic 1.5) are refused with a message.
//!
//! # What is written
//!
//! See [`write::write_abc`]: the curves with their frames as samples of
//! `P`, widths, and the head (`PolyMesh`, under a sampled `Xform` when it
//! moves), in metres, Y up.

pub(crate) mod archive;
pub(crate) mod curves;
pub(crate) mod ogawa;
pub mod write;

use crate::error::ReadError;
use crate::format::Format;
use crate::imported::Imported;
use crate::options::ReadOptions;
use crate::usdc::cursor::Budget;

/// Reads an Alembic archive's curves.
pub fn read_abc(bytes: &[u8], options: &ReadOptions) -> Result<Imported, ReadError> {
    let budget = Budget::for_file(bytes.len(), Format::Abc);
    let archive = archive::Archive::open(bytes, &budget)?;
    curves::read_curves(&archive, options, bytes.len())
}
