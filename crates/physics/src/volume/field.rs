//! The volume field of one frame: the hair splatted onto the rest grid,
//! its excess density, and what each sample reads back from it (grid
//! velocity and pressure push). This is the model's whole arithmetic on
//! sample points; an engine only gathers its samples and hands the
//! answers to its step ([`super::reference`] for the f64 `HairSystem`).

use glam::DVec3;
use wide::f64x4;

use super::friction::grid_velocity;
use super::pressure::{excess, push_m_per_s2};
use super::rest::RestDensity;
use super::settings::InteractionSettings;
use super::splat::{NodeSums, SamplePoint, splat_pieces};

/// What one sample reads from the field.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SampleReading {
    /// Grid velocity u at the sample, world coordinates, m/s. A sample
    /// outside the grid reads its own velocity (no friction).
    pub target_m_per_s: DVec3,
    /// Pressure acceleration, head coordinates, m/s² (zero outside).
    pub push_m_per_s2: DVec3,
}

/// The splatted hair of one frame; buffers are reused from frame to frame.
#[derive(Clone, Debug, Default)]
pub struct VolumeField {
    sums: NodeSums,
    /// The splat's per-piece sums, reused.
    pieces: Vec<NodeSums>,
    /// Per node [u_n (m/s, three lanes; zero at an empty node), e_n]:
    /// the mean velocity and the excess a read fetches together.
    velocity_excess: Vec<f64x4>,
    density: Vec<f64>,
    excess: Vec<f64>,
}

impl VolumeField {
    /// Splats the points of `parts` (head coordinates; the parts one after
    /// the other, as the engine holds them) onto `rest`'s grid, in
    /// parallel when `parallel` (same numbers either way,
    /// [`splat_pieces`]), and finds each node's density excess over its
    /// rest threshold.
    pub fn update(&mut self, rest: &RestDensity, parts: &[&[SamplePoint]], parallel: bool) {
        let grid = &rest.grid;
        splat_pieces(grid, parts, &mut self.sums, &mut self.pieces, parallel);
        self.density.clear();
        self.density
            .extend((0..grid.node_count()).map(|n| self.sums.density_kg_per_m3(grid, n)));
        excess(
            &self.density,
            &rest.threshold_kg_per_m3,
            rest.typical_kg_per_m3,
            &mut self.excess,
        );
        self.velocity_excess.clear();
        self.velocity_excess
            .extend(self.excess.iter().enumerate().map(|(n, e)| {
                let u = self.sums.velocity_m_per_s(n);
                f64x4::new([u.x, u.y, u.z, *e])
            }));
    }

    /// What `point` reads from the field of the last [`Self::update`].
    pub fn read(
        &self,
        rest: &RestDensity,
        settings: &InteractionSettings,
        point: &SamplePoint,
    ) -> SampleReading {
        let Some((nodes, weights)) = rest.grid.weights(point.position_m) else {
            return SampleReading {
                target_m_per_s: point.velocity_m_per_s,
                push_m_per_s2: DVec3::ZERO,
            };
        };
        // The weights' gradients only where some node is in excess: the
        // push is exactly zero elsewhere, and that is most of the hair.
        let in_excess = nodes
            .iter()
            .any(|n| self.velocity_excess[*n].as_array()[3] > 0.0);
        // (The stencil is built only then: a `match` on it with an
        // `if in_excess` guard would build it for every sample.)
        let stencil = in_excess.then(|| rest.grid.stencil(point.position_m));
        let push = match stencil.flatten() {
            Some(stencil) => push_m_per_s2(&stencil, &self.excess, settings.pressure_m2_per_s2),
            None => DVec3::ZERO,
        };
        SampleReading {
            target_m_per_s: grid_velocity(&nodes, &weights, &self.velocity_excess),
            push_m_per_s2: push,
        }
    }

    /// Hair density per node, kg/m³ (empty before the first update).
    pub fn density_kg_per_m3(&self) -> &[f64] {
        &self.density
    }

    /// Density excess per node, as a fraction of the typical rest density.
    pub fn excess(&self) -> &[f64] {
        &self.excess
    }

    /// Volume of the nodes whose density is at least `fraction` of the
    /// typical rest density ρ̄, m³: the space the hair fills.
    pub fn occupied_volume_m3(&self, rest: &RestDensity, fraction: f64) -> f64 {
        let limit = fraction * rest.typical_kg_per_m3;
        let count = self.density.iter().filter(|rho| **rho >= limit).count();
        count as f64 * rest.grid.cell_volume_m3()
    }
}
