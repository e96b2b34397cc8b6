//! What one picture shows, as plain data: the hair, the head, the camera
//! and the light. Nothing here knows where the strands came from.

use glam::Vec3;

use crate::camera::OrbitCamera;
use crate::mesh::HeadMesh;
use crate::strand_buffers::StrandBuffers;

/// Strands to draw, with their colours and ribbon widths.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct HairStrands {
    /// The polylines, root first, metres, world coordinates.
    pub strands: StrandBuffers,
    /// Linear RGB colour per strand.
    pub colours: Vec<Vec3>,
    /// Ribbon width at the root, metres. Thicker than a real fibre (about
    /// 80 µm): one drawn strand stands for several real ones.
    pub root_width_m: f32,
    /// Ribbon width at the tip, metres (tapering from the root's).
    pub tip_width_m: f32,
}

impl HairStrands {
    /// Total number of points.
    pub fn point_count(&self) -> usize {
        self.strands.points.len()
    }
}

/// A directional key light and an ambient sky.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light {
    /// Unit direction from the scene towards the light.
    pub direction: Vec3,
    /// Linear RGB colour of the key light.
    pub colour: Vec3,
    /// Strength of the key light.
    pub intensity: f32,
    /// Linear RGB colour of the ambient sky.
    pub ambient_colour: Vec3,
    /// Strength of the ambient sky.
    pub ambient_strength: f32,
}

impl Default for Light {
    /// A warm key light above, in front and to the camera's right (a
    /// portrait's classic 45° light), and a cool, dim sky.
    fn default() -> Self {
        Self {
            direction: Vec3::new(0.55, 0.75, 0.65).normalize(),
            colour: Vec3::new(1.0, 0.96, 0.9),
            intensity: 1.7,
            ambient_colour: Vec3::new(0.6, 0.68, 0.8),
            ambient_strength: 0.3,
        }
    }
}

/// One picture's content.
#[derive(Clone, Copy, Debug)]
pub struct Scene<'a> {
    /// The strands.
    pub hair: &'a HairStrands,
    /// The head they grow on.
    pub head: &'a HeadMesh,
    /// Where the picture is taken from.
    pub camera: OrbitCamera,
    /// How it is lit.
    pub light: Light,
}

impl Scene<'_> {
    /// Smallest and largest corners of a box around hair and head.
    pub fn bounds_m(&self) -> (Vec3, Vec3) {
        let (lo, hi) = self.head.mesh.bounds_m();
        self.hair
            .strands
            .points
            .iter()
            .fold((lo, hi), |(lo, hi), &p| (lo.min(p), hi.max(p)))
    }

    /// The strands' mean colour (the scalp's tint), grey without strands.
    pub fn mean_hair_colour(&self) -> Vec3 {
        let n = self.hair.colours.len();
        if n == 0 {
            return Vec3::splat(0.2);
        }
        self.hair.colours.iter().sum::<Vec3>() / n as f32
    }
}
