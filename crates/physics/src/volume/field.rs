//! The volume field of one frame: the hair splatted onto the rest grid,
//! its excess density, and what each sample reads back from it (grid
//! velocity and pressure push). This is the model's whole arithmetic on
//! sample points; an engine only gathers its samples and hands the
//! answers to its step ([`super::reference`] for the f64 `HairSystem`).

use glam::DVec3;

use super::friction::grid_velocity;
use super::pressure::{excess, push_m_per_s2};
use super::rest::RestDensity;
use super::settings::InteractionSettings;
use super::splat::{NodeSums, SamplePoint, splat};

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
    density: Vec<f64>,
    excess: Vec<f64>,
}

impl VolumeField {
    /// Splats `points` (head coordinates) onto `rest`'s grid and finds
    /// each node's density excess over its rest threshold.
    pub fn update<'a>(
        &mut self,
        rest: &RestDensity,
        points: impl IntoIterator<Item = &'a SamplePoint>,
    ) {
        let grid = &rest.grid;
        splat(grid, points, &mut self.sums);
        self.density.clear();
        self.density
            .extend((0..grid.node_count()).map(|n| self.sums.density_kg_per_m3(grid, n)));
        excess(
            &self.density,
            &rest.threshold_kg_per_m3,
            rest.typical_kg_per_m3,
            &mut self.excess,
        );
    }

    /// What `point` reads from the field of the last [`Self::update`].
    pub fn read(
        &self,
        rest: &RestDensity,
        settings: &InteractionSettings,
        point: &SamplePoint,
    ) -> SampleReading {
        match rest.grid.stencil(point.position_m) {
            Some(stencil) => SampleReading {
                target_m_per_s: grid_velocity(&stencil, &self.sums),
                push_m_per_s2: push_m_per_s2(&stencil, &self.excess, settings.pressure_m2_per_s2),
            },
            None => SampleReading {
                target_m_per_s: point.velocity_m_per_s,
                push_m_per_s2: DVec3::ZERO,
            },
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
