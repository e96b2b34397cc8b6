//! Where the Sintel groom and bust are: `../shared/data/sintel` beside the
//! checkout, or `HELIXHAIR_SINTEL`. Tests that read them skip, saying so,
//! where they are absent.

use std::path::PathBuf;

/// The Sintel data folder, if present.
pub fn sintel() -> Option<PathBuf> {
    let dir = std::env::var_os("HELIXHAIR_SINTEL").map_or_else(
        || {
            PathBuf::from(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../../../shared/data/sintel"
            ))
        },
        PathBuf::from,
    );
    dir.join("sintel_hair.16points.tfx").exists().then_some(dir)
}
