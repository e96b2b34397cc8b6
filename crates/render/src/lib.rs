//! Draws hair strands and a head mesh from plain buffers.
//!
//! The renderer knows nothing of the physics: it takes strand polylines
//! (points per strand) and colours. This crate is a placeholder for the
//! wgpu renderer of a later issue; today it holds the plain-data buffer the
//! renderer will consume, so the app already hands strands over in that
//! form.

#![warn(missing_docs)]

use glam::Vec3;

/// Strand polylines in one flat buffer, as the renderer consumes them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StrandBuffers {
    /// All points, strand after strand, metres in world coordinates.
    pub points: Vec<Vec3>,
    /// Start of each strand in `points`, plus a final end index.
    pub offsets: Vec<u32>,
}

impl StrandBuffers {
    /// Appends one strand's polyline.
    pub fn push_strand(&mut self, points: impl IntoIterator<Item = Vec3>) {
        if self.offsets.is_empty() {
            self.offsets.push(0);
        }
        self.points.extend(points);
        self.offsets.push(self.points.len() as u32);
    }

    /// Number of strands.
    pub fn strand_count(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// The points of strand `i`.
    pub fn strand(&self, i: usize) -> &[Vec3] {
        &self.points[self.offsets[i] as usize..self.offsets[i + 1] as usize]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strands_round_trip_through_the_flat_buffer() {
        let mut b = StrandBuffers::default();
        b.push_strand([Vec3::ZERO, Vec3::X]);
        b.push_strand([Vec3::Y, Vec3::Z, Vec3::ONE]);
        assert_eq!(b.strand_count(), 2);
        assert_eq!(b.strand(1), &[Vec3::Y, Vec3::Z, Vec3::ONE]);
    }
}
