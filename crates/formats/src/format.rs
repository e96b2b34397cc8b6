//! The file formats this crate knows, and how a file name picks one.

use std::fmt;
use std::path::Path;

/// A hair curve file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Format {
    /// AMD TressFX binary `.tfx` (versions 3.x and 4.x read, 4.0 written).
    Tfx,
    /// Cem Yuksel's binary `.hair` (the hair model library's format).
    Hair,
    /// USD text layers (`.usda`): `BasisCurves` prims.
    Usda,
    /// USD binary crate files (`.usdc`, and `.usd`, which USD writes as a
    /// crate file; a `.usd` that is text is read as text).
    Usdc,
    /// USD packages (`.usdz`): an uncompressed zip whose first file is the
    /// layer (`.usdc` or `.usda`).
    Usdz,
    /// Wavefront OBJ polylines (`l` elements).
    Obj,
    /// Alembic archives (`.abc`, Ogawa): `AbcGeom` curves.
    Abc,
}

impl Format {
    /// Every format, in a fixed order.
    pub const ALL: [Format; 7] = [
        Format::Tfx,
        Format::Hair,
        Format::Usda,
        Format::Usdc,
        Format::Usdz,
        Format::Obj,
        Format::Abc,
    ];

    /// Every file extension read and written (lower case, no dot): each
    /// format's name, and `usd` (USD's default extension, binary or text).
    pub const EXTENSIONS: [&'static str; 8] =
        ["tfx", "hair", "usda", "usdc", "usd", "usdz", "obj", "abc"];

    /// The short lower-case name, also the usual file extension.
    pub fn name(self) -> &'static str {
        match self {
            Format::Tfx => "tfx",
            Format::Hair => "hair",
            Format::Usda => "usda",
            Format::Usdc => "usdc",
            Format::Usdz => "usdz",
            Format::Obj => "obj",
            Format::Abc => "abc",
        }
    }

    /// Whether the format is one of USD's (text, binary or package).
    pub fn is_usd(self) -> bool {
        matches!(self, Format::Usda | Format::Usdc | Format::Usdz)
    }

    /// Whether one file holds an animation and a head mesh (USD and
    /// Alembic); the others hold one frame of hair.
    pub fn holds_animation(self) -> bool {
        self.is_usd() || self == Format::Abc
    }

    /// The format a file name's extension names (any case), if any. A
    /// `.usd` file is [`Format::Usdc`], as USD writes it; its reader reads
    /// a text `.usd` as text.
    pub fn from_path(path: &Path) -> Option<Format> {
        let extension = path.extension()?.to_str()?.to_ascii_lowercase();
        if extension == "usd" {
            return Some(Format::Usdc);
        }
        Format::ALL
            .into_iter()
            .find(|format| format.name() == extension)
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
