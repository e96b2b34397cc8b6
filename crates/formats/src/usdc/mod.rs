//! Binary USD: crate files (`.usdc`, and `.usd` files that are binary),
//! read and written by hand.
//!
//! # Why by hand
//!
//! The maintained pure-Rust USD crate, `openusd`, reads and writes crate
//! files, but its current releases (0.7, 0.8) need Rust 1.96 (the
//! workspace is on 1.95), the last that builds here (0.6.0) is two
//! releases behind, and it brings about 55 crates (86,000 lines) for what
//! is here about 2,000 lines, writer included; and its crate reader, not
//! yet fuzzed here, would have to be audited against the rule every reader
//! here keeps (any input: an error, never a panic or an unbounded
//! allocation). The format is small and documented by Pixar's source
//! (`pxr/usd/usd/crateFile.cpp`), and Pixar's own library (`usd-core`)
//! checks this module in the tests, both ways. `docs/formats.md` has the
//! evaluation.
//!
//! # How reading works
//!
//! 1. **Sections** ([`sections`]): the header, the table of contents and
//!    the structural sections (tokens, strings, fields, field sets, paths,
//!    specs), LZ4-compressed ([`lz4`]) and integer-coded ([`integers`]).
//! 2. **Values** ([`values`]): a field's 64-bit value rep says its type and
//!    where it is: inline, or at an offset (arrays, compressed or not; time
//!    samples).
//! 3. **Layer** ([`layer`]): specs become the same layer model the `.usda`
//!    reader builds, so prims, transforms, units, axes, primvars and time
//!    samples become curves by the same code ([`crate::usda`]).
//!
//! Every offset, count and compressed size is checked before use, and all
//! decoded data is charged to a budget proportional to the file's size
//! ([`cursor::Budget`]), so a hostile file gives an error at a byte
//! offset, never a panic or an allocation its size does not justify.
//! A `.usd` file that is text (`#usda`) is handed to the `.usda` reader;
//! a `.usdz` package's first layer is read by either ([`usdz`]).
//!
//! # What is written
//!
//! See [`write::write_usdc`]: the same prims as [`crate::write_usda`]
//! (linear `BasisCurves` in metres, Y up, widths, colours, time samples,
//! an optional head `Mesh` with its poses), as crate version 0.8.0.

pub(crate) mod builder;
pub mod cursor;
pub(crate) mod integers;
pub(crate) mod layer;
pub(crate) mod lz4;
pub(crate) mod sections;
pub mod usdz;
pub(crate) mod values;
pub mod write;

use crate::error::ReadError;
use crate::format::Format;
use crate::imported::Imported;
use crate::options::ReadOptions;
use crate::usda;
use crate::usdc::cursor::Budget;
use crate::usdc::values::Values;

/// Reads a crate file's `BasisCurves` prims (or a text layer, when the
/// bytes start with `#usda`, as a `.usd` file may).
pub fn read_usdc(bytes: &[u8], options: &ReadOptions) -> Result<Imported, ReadError> {
    if bytes.starts_with(b"#usda") {
        return usda::read_usda(bytes, options);
    }
    let budget = Budget::for_file(bytes.len(), Format::Usdc);
    let file = sections::read_sections(bytes, &budget)?;
    let values = Values {
        file: &file,
        bytes,
        budget: &budget,
    };
    let layer = layer::layer_from_crate(&values)?;
    usda::curves::curves_from_layer(Format::Usdc, layer, options, bytes.len())
}
