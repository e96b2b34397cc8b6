//! One entry point over the single-frame writers.

pub(crate) mod checks;
pub(crate) mod usd_checks;

use std::io::Write;

use crate::curve_set::CurveSet;
use crate::error::WriteError;
use crate::format::Format;
use crate::{abc, hair, obj, tfx, usda, usdc};

/// Writes one frame of curves as `format` (USD without animation or head;
/// call [`crate::write_usda`], [`crate::write_usdc`], [`crate::write_usdz`] or
/// [`crate::write_abc`] for those).
pub fn write(out: &mut impl Write, format: Format, curves: &CurveSet) -> Result<(), WriteError> {
    match format {
        Format::Tfx => tfx::write_tfx(out, curves),
        Format::Hair => hair::write_hair(out, curves),
        Format::Usda => usda::write::write_usda(out, curves, None, None),
        Format::Usdc => usdc::write::write_usdc(out, curves, None, None, &[]),
        Format::Usdz => usdc::usdz::write_usdz(out, curves, None, None, &[]),
        Format::Obj => obj::write_obj(out, curves),
        Format::Abc => abc::write::write_abc(out, curves, None, None, &[]),
    }
}
