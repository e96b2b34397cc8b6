//! What every fuzz target checks: the reader returns (an error or a groom)
//! without panicking, and a groom holds no more points than the file has
//! bytes (the allocation bound of `helixhair_formats::read`).

use helixhair_formats::{Format, ReadOptions, read};

pub fn check(data: &[u8], format: Format) {
    if let Ok(imported) = read(data, format, &ReadOptions::default()) {
        let points = imported.points_held();
        assert!(
            points <= data.len(),
            "{points} points from {} bytes",
            data.len()
        );
    }
}
