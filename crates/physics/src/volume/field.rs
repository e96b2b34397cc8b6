//! The volume field of one frame: the hair splatted onto the rest grid,
//! its excess density, and what each sample reads back from it (grid
//! velocity and pressure push). This is the model's whole arithmetic on
//! sample points; an engine only gathers its samples and hands the
//! answers to its step ([`super::reference`] for the f64 `HairSystem`).

use glam::DVec3;
use wide::f64x4;

use super::cell::{Cell, CellLanes, Locator, OUTSIDE};
use super::friction::{HeadVelocity, grid_velocity};
use super::pressure::{self, push_m_per_s2};
use super::rest::RestDensity;
use super::settings::InteractionSettings;
use super::splat::{NODES_PER_TASK, NodeSums, SamplePoint, for_each_node_block, splat_pieces};
use super::splat_lanes::{PointLanes, splat_lane_pieces};
use rayon::prelude::*;

/// What one sample reads from the field.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SampleReading {
    /// Grid velocity at the sample relative to the head's rigid motion
    /// there, u − c (the head as the update had it), world axes, m/s. A
    /// sample outside the grid reads its own relative velocity (no
    /// friction).
    pub relative_target_m_per_s: DVec3,
    /// Pressure acceleration, head coordinates, m/s² (zero outside).
    pub push_m_per_s2: DVec3,
}

/// The splatted hair of one frame; buffers are reused from frame to frame.
#[derive(Clone, Debug, Default)]
pub struct VolumeField {
    sums: NodeSums,
    /// The splat's per-piece sums, reused.
    pieces: Vec<NodeSums>,
    /// Per node n [u_n − c(x_n) (m/s, three lanes: the hair's mean
    /// velocity relative to the head's rigid motion at the node; zero at
    /// an empty node), 1 when some corner of the cell whose first corner
    /// is n is in excess, else 0]: what a read fetches with its cell's
    /// first node. Trilinear weights reproduce the head's affine velocity
    /// field exactly, so a read of these is u(x) − c(x), with no
    /// per-sample work for c.
    velocity_excess: Vec<f64x4>,
    /// The head's rigid velocity field at the last update.
    head_velocity: HeadVelocity,
    density: Vec<f64>,
    excess: Vec<f64>,
    /// The rest grid made ready for reads.
    locator: Option<Locator>,
    /// The cell of every point of the last update, the parts one after
    /// the other (`None` outside the grid): found once by the splat,
    /// reused by the read-back.
    cells: Vec<Option<Cell>>,
    /// The same for the points of the last [`Self::update_lanes`], four
    /// to a group.
    cell_lanes: Vec<CellLanes>,
}

impl VolumeField {
    /// Splats the points of `parts` (head coordinates; the parts one after
    /// the other, as the engine holds them) onto `rest`'s grid, in
    /// parallel when `parallel` (same numbers either way,
    /// [`splat_pieces`]), and finds each node's density excess over its
    /// rest threshold and its mean velocity relative to the head moving
    /// as `head` ([`HeadVelocity`]).
    pub fn update(
        &mut self,
        rest: &RestDensity,
        parts: &[&[SamplePoint]],
        head: &HeadVelocity,
        parallel: bool,
    ) {
        let grid = &rest.grid;
        let locator = grid.locator();
        self.locator = Some(locator);
        self.head_velocity = *head;
        let (sums, pieces, cells) = (&mut self.sums, &mut self.pieces, &mut self.cells);
        splat_pieces(grid, parts, sums, pieces, cells, parallel);
        self.finish(rest, locator, parallel);
    }

    /// [`Self::update`] for points held four to a group, lane by lane, as
    /// the batch engine gathers them ([`splat_lane_pieces`]: the same
    /// numbers as the scalar splat of the same points in the same order);
    /// their cells are [`Self::cell_lanes`].
    pub fn update_lanes(
        &mut self,
        rest: &RestDensity,
        parts: &[&[PointLanes]],
        head: &HeadVelocity,
        parallel: bool,
    ) {
        let grid = &rest.grid;
        let locator = grid.locator();
        self.locator = Some(locator);
        self.head_velocity = *head;
        let (sums, pieces) = (&mut self.sums, &mut self.pieces);
        splat_lane_pieces(grid, parts, sums, pieces, &mut self.cell_lanes, parallel);
        self.finish(rest, locator, parallel);
    }

    /// From the node sums: density, excess, and the node data reads
    /// fetch; node by node, in parallel when `parallel` (each node's
    /// numbers are its own).
    fn finish(&mut self, rest: &RestDensity, locator: Locator, parallel: bool) {
        let grid = &rest.grid;
        let count = grid.node_count();
        self.density.resize(count, 0.0);
        self.excess.resize(count, 0.0);
        self.velocity_excess.resize(count, f64x4::ZERO);
        let sums = &self.sums;
        let density_excess = |start: usize, (density, excess): (&mut [f64], &mut [f64])| {
            for (i, rho) in density.iter_mut().enumerate() {
                *rho = sums.density_kg_per_m3(grid, start + i);
            }
            let threshold = &rest.threshold_kg_per_m3[start..start + density.len()];
            pressure::excess(density, threshold, rest.typical_kg_per_m3, excess);
        };
        if parallel {
            let pairs = self.density.par_chunks_mut(NODES_PER_TASK);
            let pairs = pairs.zip(self.excess.par_chunks_mut(NODES_PER_TASK));
            pairs
                .enumerate()
                .for_each(|(t, pair)| density_excess(t * NODES_PER_TASK, pair));
        } else {
            let pairs = self.density.chunks_mut(NODES_PER_TASK);
            let pairs = pairs.zip(self.excess.chunks_mut(NODES_PER_TASK));
            pairs
                .enumerate()
                .for_each(|(t, pair)| density_excess(t * NODES_PER_TASK, pair));
        }
        let excess = &self.excess;
        // (A node past the grid's last cell along some axis is no cell's
        // first corner; its flag is never read.)
        let cell_in_excess = |n: usize| {
            let corner = |o: &usize| excess.get(n + o).is_some_and(|e| *e > 0.0);
            locator.offsets.iter().any(corner)
        };
        let head = &self.head_velocity;
        let [nx, ny, _] = grid.dims;
        let node_data = |(t, out): (usize, &mut [f64x4])| {
            for (i, node) in out.iter_mut().enumerate() {
                let n = t * NODES_PER_TASK + i;
                let u = if sums.mass_kg(n) > 0.0 {
                    let at = grid.node_position(n % nx, (n / nx) % ny, n / (nx * ny));
                    sums.velocity_m_per_s(n) - head.at(at)
                } else {
                    DVec3::ZERO
                };
                let flag = if cell_in_excess(n) { 1.0 } else { 0.0 };
                *node = f64x4::new([u.x, u.y, u.z, flag]);
            }
        };
        for_each_node_block(&mut self.velocity_excess, parallel, node_data);
    }

    /// What `point` reads from the field of the last [`Self::update`], on
    /// `rest` (the rest density of that update; its grid was made ready
    /// for reads there). A point outside the grid, or read before any
    /// update, reads its own velocity and no push.
    #[inline]
    pub fn read(
        &self,
        rest: &RestDensity,
        settings: &InteractionSettings,
        point: &SamplePoint,
    ) -> SampleReading {
        debug_assert!(self.locator.is_none_or(|l| l == rest.grid.locator()));
        let cell = self.locator.and_then(|l| l.locate(point.position_m));
        self.read_in(settings, cell, point)
    }

    /// Each point's cell in the last [`Self::update`], the parts one after
    /// the other; `None` outside the grid.
    pub fn cells(&self) -> &[Option<Cell>] {
        &self.cells
    }

    /// The cells of the points of the last [`Self::update_lanes`], four to
    /// a group, the parts one after the other.
    pub fn cell_lanes(&self) -> &[CellLanes] {
        &self.cell_lanes
    }

    /// What `point` reads, in `cell` (its entry of [`Self::cells`] or
    /// [`Self::cell_lanes`], found by the update's splat; the very cell
    /// [`Self::read`] finds).
    #[inline]
    pub fn read_in(
        &self,
        settings: &InteractionSettings,
        cell: Option<Cell>,
        point: &SamplePoint,
    ) -> SampleReading {
        let found = self.locator.as_ref().zip(cell);
        let Some((locator, cell)) = found else {
            return SampleReading {
                relative_target_m_per_s: self.own_relative_velocity(point),
                push_m_per_s2: DVec3::ZERO,
            };
        };
        let offsets = &locator.offsets;
        // One bounds check for the cell's nodes, not one per node.
        let first = cell.first as usize;
        let around = &self.velocity_excess[first..=first + offsets[7]];
        // The weights' gradients only where some node is in excess: the
        // push is exactly zero elsewhere, and that is most of the hair.
        let push = if around[0].as_array()[3] > 0.0 {
            let stencil = locator.stencil(&cell);
            push_m_per_s2(&stencil, &self.excess, settings.pressure_m2_per_s2)
        } else {
            DVec3::ZERO
        };
        SampleReading {
            relative_target_m_per_s: grid_velocity(around, offsets, &cell.weights()),
            push_m_per_s2: push,
        }
    }

    /// What the four `points` of a group read, lane by lane, in `cells`
    /// (their entry of [`Self::cell_lanes`]): `each(k, u, a)` for lane
    /// k in turn, with u the grid velocity relative to the head in the
    /// first three lanes of an f64x4 (the fourth is not a velocity) and a
    /// the push, head
    /// coordinates, `None` where it is +0 for want of a node in excess
    /// (most of the hair: [`Self::read_in`] reads `DVec3::ZERO` there). Each lane's numbers are [`Self::read_in`]'s for that
    /// point; only the eight weights are found for the four points at once
    /// (the same products, lane by lane).
    #[inline(always)]
    pub fn read_lanes(
        &self,
        settings: &InteractionSettings,
        cells: &CellLanes,
        points: &PointLanes,
        mut each: impl FnMut(usize, f64x4, Option<DVec3>),
    ) {
        let own = |k: usize| {
            let v = self.own_relative_velocity(&points.lane(k));
            f64x4::new([v.x, v.y, v.z, 0.0])
        };
        let Some(locator) = self.locator.as_ref() else {
            (0..4).for_each(|k| each(k, own(k), None));
            return;
        };
        let one = f64x4::splat(1.0);
        let [x, y, z] = cells.frac.map(|f| [one - f, f]);
        let weights: [[f64; 4]; 8] =
            std::array::from_fn(|c| (x[c & 1] * y[(c >> 1) & 1] * z[c >> 2]).to_array());
        let offsets = &locator.offsets;
        for k in 0..4 {
            let first = cells.first[k];
            if first == OUTSIDE {
                each(k, own(k), None);
                continue;
            }
            let first = first as usize;
            let node = &self.velocity_excess;
            // The corners two by two, each pair along x one slice (one
            // bounds check for two nodes), summed in the order of
            // `offsets`.
            let mut target = f64x4::ZERO;
            let mut flag = 0.0;
            let pairs = offsets.chunks_exact(2).zip(weights.chunks_exact(2));
            for (i, (pair, w)) in pairs.enumerate() {
                if let [lower, upper] = &node[first + pair[0]..first + pair[0] + 2] {
                    // The cell's first node: its flag.
                    if i == 0 {
                        flag = lower.as_array()[3];
                    }
                    target += f64x4::splat(w[0][k]) * *lower;
                    target += f64x4::splat(w[1][k]) * *upper;
                }
            }
            let push = (flag > 0.0).then(|| {
                let cell = Cell {
                    first: first as u32,
                    frac: cells.frac.map(|f| f.as_array()[k]),
                };
                let stencil = locator.stencil(&cell);
                push_m_per_s2(&stencil, &self.excess, settings.pressure_m2_per_s2)
            });
            each(k, target, push);
        }
    }

    /// A point's own velocity relative to the head's rigid motion at it,
    /// what a point outside the grid reads (it feels no friction).
    fn own_relative_velocity(&self, point: &SamplePoint) -> DVec3 {
        point.velocity_m_per_s - self.head_velocity.at(point.position_m)
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
