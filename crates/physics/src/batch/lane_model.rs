//! Per-lane constants: [`LANES`] strands of the same element count and
//! quadrature, each with its own lengths, stiffness, natural strains,
//! friction, mass per length and drag, stepped as one batch.
//!
//! # Why
//!
//! A groom made elsewhere gives every strand its own length and rest shape
//! (`docs/import.md`), so no two imported strands share a [`BatchModel`].
//! Were the constants one scalar per batch, every such strand would fill a
//! batch of [`LANES`] alone, seven lanes of padding: eight times the work.
//! Here a batch's constants are [`Lanes`] values too, one per strand, so
//! strands that share only N and the quadrature fill a batch.
//!
//! # How it works
//!
//! The step's arithmetic reads its constants through [`Constants`]: per
//! element the length ℓ, stiffness diagonal K, natural strains qⁿ and
//! friction γℓ; per strand ρS and ν; the quadrature's nodes and weights
//! (shared by every lane). [`BatchModel`] (one strand, scalar f32; the f32
//! Dense twin and the GPU kernels' CPU twins step with it) answers with
//! the same value in every lane, [`LaneModel`] with one value per lane.
//! Each value is the same f32 either way, and every lane runs the same
//! IEEE operations in the same order (`node · ℓ` as a scalar product or a
//! lane product gives the same bits), so a strand's results do not depend
//! on which model type carries its constants, nor on its neighbours
//! (`tests/batch_lanes.rs` checks this bit for bit).

use super::lanes::{LANES, Lanes, Real};
use super::layout::BatchModel;
use super::vec::V3;
use crate::model::StrandModel;

/// The constants one step reads, as values of `T` (one per lane).
pub trait Constants<T: Real> {
    /// Number of elements N.
    fn element_count(&self) -> usize;
    /// Element `e`'s length ℓ_Q, metres.
    fn length_m(&self, e: usize) -> T;
    /// Element `e`'s stiffness diagonal K_Q, N·m³.
    fn stiffness(&self, e: usize) -> V3<T>;
    /// Element `e`'s natural strains qⁿ_Q, m⁻¹.
    fn natural(&self, e: usize) -> V3<T>;
    /// Element `e`'s friction diagonal γℓ_Q, N·m³·s.
    fn friction(&self, e: usize) -> T;
    /// ρS, kg/m.
    fn mass_per_length(&self) -> T;
    /// ν, N·s/m².
    fn air_drag(&self) -> T;
    /// Quadrature points per element (the same for every lane).
    fn node_count(&self) -> usize;
    /// Quadrature node `j` in [0, 1] (the same for every lane).
    fn node(&self, j: usize) -> T;
    /// Quadrature weight `j`; the weights sum to 1 (the same for every lane).
    fn weight(&self, j: usize) -> T;
}

/// One strand's constants, the same in every lane.
impl<T: Real> Constants<T> for BatchModel {
    #[inline(always)]
    fn element_count(&self) -> usize {
        self.lengths_m.len()
    }
    #[inline(always)]
    fn length_m(&self, e: usize) -> T {
        T::splat(self.lengths_m[e])
    }
    #[inline(always)]
    fn stiffness(&self, e: usize) -> V3<T> {
        V3::splat(self.stiffness[e])
    }
    #[inline(always)]
    fn natural(&self, e: usize) -> V3<T> {
        V3::splat(self.natural[e])
    }
    #[inline(always)]
    fn friction(&self, e: usize) -> T {
        T::splat(self.friction[e])
    }
    #[inline(always)]
    fn mass_per_length(&self) -> T {
        T::splat(self.mass_per_length)
    }
    #[inline(always)]
    fn air_drag(&self) -> T {
        T::splat(self.air_drag)
    }
    #[inline(always)]
    fn node_count(&self) -> usize {
        self.nodes.len()
    }
    #[inline(always)]
    fn node(&self, j: usize) -> T {
        T::splat(self.nodes[j])
    }
    #[inline(always)]
    fn weight(&self, j: usize) -> T {
        T::splat(self.weights[j])
    }
}

/// A batch's constants, lane i from the i-th strand's [`BatchModel`];
/// see the [module docs](self).
#[derive(Clone, Debug, PartialEq)]
pub struct LaneModel {
    /// Element lengths ℓ_Q, metres.
    pub lengths_m: Vec<Lanes>,
    /// Stiffness diagonals K_Q, N·m³.
    pub stiffness: Vec<V3<Lanes>>,
    /// Natural strains qⁿ_Q, m⁻¹.
    pub natural: Vec<V3<Lanes>>,
    /// Friction diagonals γℓ_Q, N·m³·s.
    pub friction: Vec<Lanes>,
    /// ρS, kg/m.
    pub mass_per_length: Lanes,
    /// ν, N·s/m².
    pub air_drag: Lanes,
    /// Quadrature nodes in [0, 1], shared by every lane.
    pub nodes: Vec<f32>,
    /// Quadrature weights, shared by every lane.
    pub weights: Vec<f32>,
}

impl LaneModel {
    /// `model` in every lane.
    pub fn splat(model: &BatchModel) -> Self {
        let n = model.elements();
        Self {
            lengths_m: (0..n).map(|e| model.length_m(e)).collect(),
            stiffness: (0..n).map(|e| model.stiffness(e)).collect(),
            natural: (0..n).map(|e| model.natural(e)).collect(),
            friction: (0..n).map(|e| model.friction(e)).collect(),
            mass_per_length: model.mass_per_length(),
            air_drag: model.air_drag(),
            nodes: model.nodes.clone(),
            weights: model.weights.clone(),
        }
    }

    /// Lane i from `models[i]`; lanes past the end copy the last model (a
    /// short batch's padding). Panics if `models` is empty, longer than
    /// [`LANES`], or its models differ in element count or quadrature:
    /// those share a batch only by [`super::BatchSystem`]'s packing, which
    /// never mixes them.
    pub fn from_lanes(models: &[&BatchModel]) -> Self {
        assert!(
            (1..=LANES).contains(&models.len()),
            "a batch holds 1 to {LANES} strands, not {}",
            models.len()
        );
        let mut out = Self::splat(models[0]);
        for (lane, model) in models.iter().enumerate().skip(1) {
            out.set_lanes_from(lane, model);
        }
        out
    }

    /// Lanes `first..LANES` from `model`: a strand placed in lane `first`,
    /// the lanes after it its padding. Panics if `model`'s element count or
    /// quadrature differ from this batch's (see [`Self::from_lanes`]).
    pub fn set_lanes_from(&mut self, first: usize, model: &BatchModel) {
        assert!(
            model.elements() == self.lengths_m.len()
                && model.nodes == self.nodes
                && model.weights == self.weights,
            "a batch holds strands of one element count and quadrature"
        );
        let set = |x: &mut Lanes, value: f32| {
            for lane in first..LANES {
                x.set_lane(lane, value);
            }
        };
        let set3 = |x: &mut V3<Lanes>, value: [f32; 3]| {
            set(&mut x.x, value[0]);
            set(&mut x.y, value[1]);
            set(&mut x.z, value[2]);
        };
        for e in 0..model.elements() {
            set(&mut self.lengths_m[e], model.lengths_m[e]);
            set3(&mut self.stiffness[e], model.stiffness[e]);
            set3(&mut self.natural[e], model.natural[e]);
            set(&mut self.friction[e], model.friction[e]);
        }
        set(&mut self.mass_per_length, model.mass_per_length);
        set(&mut self.air_drag, model.air_drag);
    }

    /// Lane `lane`'s natural strains, element by element.
    pub fn natural_of_lane(&self, lane: usize) -> impl Iterator<Item = [f32; 3]> + '_ {
        self.natural
            .iter()
            .map(move |k| [k.x.lane(lane), k.y.lane(lane), k.z.lane(lane)])
    }
}

impl Constants<Lanes> for LaneModel {
    #[inline(always)]
    fn element_count(&self) -> usize {
        self.lengths_m.len()
    }
    #[inline(always)]
    fn length_m(&self, e: usize) -> Lanes {
        self.lengths_m[e]
    }
    #[inline(always)]
    fn stiffness(&self, e: usize) -> V3<Lanes> {
        self.stiffness[e]
    }
    #[inline(always)]
    fn natural(&self, e: usize) -> V3<Lanes> {
        self.natural[e]
    }
    #[inline(always)]
    fn friction(&self, e: usize) -> Lanes {
        self.friction[e]
    }
    #[inline(always)]
    fn mass_per_length(&self) -> Lanes {
        self.mass_per_length
    }
    #[inline(always)]
    fn air_drag(&self) -> Lanes {
        self.air_drag
    }
    #[inline(always)]
    fn node_count(&self) -> usize {
        self.nodes.len()
    }
    #[inline(always)]
    fn node(&self, j: usize) -> Lanes {
        Lanes::splat(self.nodes[j])
    }
    #[inline(always)]
    fn weight(&self, j: usize) -> Lanes {
        Lanes::splat(self.weights[j])
    }
}

/// The f64 reference's constants, exactly: the step's f64 instance reads
/// them unrounded; any other width rounds each once ([`Real::splat_f64`]).
impl<T: Real> Constants<T> for StrandModel {
    #[inline(always)]
    fn element_count(&self) -> usize {
        self.lengths_m.len()
    }
    #[inline(always)]
    fn length_m(&self, e: usize) -> T {
        T::splat_f64(self.lengths_m[e])
    }
    #[inline(always)]
    fn stiffness(&self, e: usize) -> V3<T> {
        V3::splat_f64(self.stiffness[e].to_array())
    }
    #[inline(always)]
    fn natural(&self, e: usize) -> V3<T> {
        V3::splat_f64(self.natural[e].to_array())
    }
    #[inline(always)]
    fn friction(&self, e: usize) -> T {
        T::splat_f64(self.friction[e])
    }
    #[inline(always)]
    fn mass_per_length(&self) -> T {
        T::splat_f64(self.mass_per_length)
    }
    #[inline(always)]
    fn air_drag(&self) -> T {
        T::splat_f64(self.air_drag)
    }
    #[inline(always)]
    fn node_count(&self) -> usize {
        self.quadrature.nodes.len()
    }
    #[inline(always)]
    fn node(&self, j: usize) -> T {
        T::splat_f64(self.quadrature.nodes[j])
    }
    #[inline(always)]
    fn weight(&self, j: usize) -> T {
        T::splat_f64(self.quadrature.weights[j])
    }
}
