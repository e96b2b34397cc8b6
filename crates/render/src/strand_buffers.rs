//! Strand polylines in one flat buffer: the form in which every strand
//! source (the physics today, a GPU buffer later) hands strands over.
//!
//! Strand `i` is `points[offsets[i]..offsets[i + 1]]`, root first. One flat
//! `Vec` instead of a `Vec<Vec<_>>` is what a GPU upload wants, and it lets
//! strands of different lengths share one allocation.

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

    /// Iterates over the strands' polylines.
    pub fn iter(&self) -> impl Iterator<Item = &[Vec3]> {
        (0..self.strand_count()).map(|i| self.strand(i))
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
        assert_eq!(b.iter().map(<[Vec3]>::len).collect::<Vec<_>>(), [2, 3]);
    }
}
