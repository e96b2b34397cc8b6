//! CSV tables: every study writes its raw numbers next to its chart, one
//! row per measurement, so that a chart can be redrawn or checked by hand.

use std::path::Path;

use anyhow::Context as _;
use serde::Serialize;

/// Writes `rows` as CSV with a header taken from the row type's fields.
pub fn write_csv<T: Serialize>(path: &Path, rows: &[T]) -> anyhow::Result<()> {
    let mut writer = csv::Writer::from_path(path)
        .with_context(|| format!("cannot create {}", path.display()))?;
    for row in rows {
        writer
            .serialize(row)
            .with_context(|| format!("cannot write a row to {}", path.display()))?;
    }
    writer
        .flush()
        .with_context(|| format!("cannot write {}", path.display()))
}
