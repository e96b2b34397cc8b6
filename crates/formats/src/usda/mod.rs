//! USD text layers (`.usda`): `BasisCurves` read and written, by hand.
//!
//! # Why by hand
//!
//! The one maintained pure-Rust USD crate, `openusd`, reads and writes
//! usda/usdc/usdz, but its current releases need Rust 1.96 (the workspace
//! is on 1.95) and it brings about 55 crates where this one has two; the
//! `usd` crates are bindings to Pixar's C++ build. So this module reads a
//! careful subset of the text format ([`parse`]) and writes plain `usda`
//! ([`mod@write`]); binary crate files have their own reader and writer
//! ([`crate::usdc`]), which build the same layer model ([`parse::Layer`])
//! and share the step from it to curves. `docs/formats.md` has the
//! evaluation. Pixar's own library (`usd-core` on PyPI) reads back what
//! this module writes, in a test.
//!
//! # What is read
//!
//! Every `BasisCurves` prim (not under a `class`, not `active = false`):
//! `curveVertexCounts`, `points` (the default value, or time samples, which
//! become an [`crate::Animation`]), `widths` (or `primvars:widths`) and
//! `primvars:displayColor` with `constant`, `uniform` or `vertex`
//! interpolation (inferred from the count when not authored). Type `linear`
//! is read exactly; `cubic` curves are read as their control polylines,
//! with a warning. Points go through the prim's and its ancestors'
//! transforms ([`transform`]), then the layer's `metersPerUnit` (USD's
//! fallback 0.01 when absent) and `upAxis` (fallback Y) make them metres,
//! Y up. Widths are scaled by `metersPerUnit` only (not by transforms).
//! Several prims concatenate, in file order; animated prims must share their
//! sample times. Composition arcs (references, payloads, variants) are not
//! followed and a warning says so.
//!
//! # What is written
//!
//! See [`write::write_usda`]: one `BasisCurves` prim of linear curves in
//! metres, Y up, with widths, colours, time samples for an animation and an
//! optional head `Mesh`.

pub(crate) mod curves;
mod lexer;
pub mod parse;
pub mod transform;
pub mod write;

pub use curves::{USD_FALLBACK_METERS_PER_UNIT, USD_FALLBACK_TIME_CODES_PER_SECOND};

use crate::error::{Location, ReadError, ReadErrorKind};
use crate::format::Format;
use crate::imported::Imported;
use crate::options::ReadOptions;

/// Reads a `.usda` layer's `BasisCurves` prims.
pub fn read_usda(bytes: &[u8], options: &ReadOptions) -> Result<Imported, ReadError> {
    let error = |line, kind, message: &str| {
        ReadError::new(
            Format::Usda,
            Location::Line(line),
            kind,
            message.to_string(),
        )
    };
    let first_line_end = bytes
        .iter()
        .position(|&b| b == b'\n')
        .unwrap_or(bytes.len());
    let first_line = bytes[..first_line_end].trim_ascii();
    if !first_line.starts_with(b"#usda") {
        let message = if bytes.starts_with(b"PXR-USDC") {
            "this is a binary crate file: name it .usdc (or .usd) to read it as one"
        } else {
            "a usda layer starts with \"#usda 1.0\""
        };
        return Err(error(1, ReadErrorKind::BadMagic, message));
    }
    if !first_line.starts_with(b"#usda 1.") {
        return Err(error(
            1,
            ReadErrorKind::UnsupportedVersion,
            "only usda 1.x layers are read",
        ));
    }
    let rest = &bytes[first_line_end.min(bytes.len())..];
    let text = std::str::from_utf8(rest).map_err(|utf8| {
        let line = 1 + rest[..utf8.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        error(line, ReadErrorKind::Syntax, "the text is not UTF-8")
    })?;
    let layer = parse::parse_layer(text, 1)?;
    curves::curves_from_layer(Format::Usda, layer, options, bytes.len())
}
