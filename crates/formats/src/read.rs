//! One entry point over the readers, and what every reader returns.
//!
//! [`read`] takes a file's bytes and its [`Format`] (see
//! [`Format::from_path`]) and returns an [`Imported`] groom: the repaired
//! curves, the frames when the file is animated, the repair summary and
//! warnings about what was read approximately or not at all.
//!
//! # Memory bound
//!
//! Readers allocate in proportion to the file, never to a count written in
//! it: binary readers check every count against the file's length before
//! allocating, text readers grow their buffers only as values are parsed.
//! Reading a file of `n` bytes allocates at most about `64 n` bytes plus a
//! constant (the worst case is many empty curves, each a `Curve` of about
//! 100 bytes from a few bytes of text); a real groom takes 1 to 3 `n`.

use crate::error::ReadError;
use crate::format::Format;
pub use crate::imported::Imported;
use crate::options::ReadOptions;
use crate::{abc, hair, obj, tfx, usda, usdc};

/// Reads a file's bytes as `format`.
pub fn read(bytes: &[u8], format: Format, options: &ReadOptions) -> Result<Imported, ReadError> {
    match format {
        Format::Tfx => tfx::read_tfx(bytes, options),
        Format::Hair => hair::read_hair(bytes, options),
        Format::Usda => usda::read_usda(bytes, options),
        Format::Usdc => usdc::read_usdc(bytes, options),
        Format::Usdz => usdc::usdz::read_usdz(bytes, options),
        Format::Obj => obj::read_obj(bytes, options),
        Format::Abc => abc::read_abc(bytes, options),
    }
}
