//! The fast path's data: one strand's constants in f32 ([`BatchModel`];
//! a batch's, one per lane, are a [`super::LaneModel`]), the root motion
//! of a batch, and the per-element scratch one step fills.
//!
//! Layout. Strands of one element count are cut into batches of
//! [`LANES`](super::LANES) strands (packed as they are added, see
//! [`super::BatchSystem`]). A batch's state is N strain triples
//! and N rate triples, each a [`V3`] of [`Lanes`](super::Lanes): element e's
//! κ₁ for the 8 strands of the batch are 8 consecutive floats, so every
//! operation of the step loads and stores whole SIMD registers
//! (structure of arrays inside a batch, array of batches outside). A short
//! last batch is padded with copies of its last strand, whose results are
//! computed and ignored. The per-element scratch is reused from step to
//! step (one per worker thread), so a step allocates nothing.

use glam::{DMat3, DVec3};

use super::lanes::Real;
use super::vec::{M3, V3};
use crate::model::StrandModel;
use crate::motion::RigidMotion;

/// One strand's per-element constants in f32 (see [`StrandModel`]): what
/// the f32 twins of the GPU kernels step, and what a [`super::LaneModel`]
/// is built from, lane by lane.
#[derive(Clone, Debug, PartialEq)]
pub struct BatchModel {
    /// Element lengths ℓ_Q, metres.
    pub lengths_m: Vec<f32>,
    /// Stiffness diagonal K_Q, N·m³.
    pub stiffness: Vec<[f32; 3]>,
    /// Natural strains qⁿ_Q, m⁻¹.
    pub natural: Vec<[f32; 3]>,
    /// Friction diagonal γℓ_Q, N·m³·s.
    pub friction: Vec<f32>,
    /// ρS, kg/m.
    pub mass_per_length: f32,
    /// ν, N·s/m².
    pub air_drag: f32,
    /// Quadrature nodes in [0, 1].
    pub nodes: Vec<f32>,
    /// Quadrature weights, summing to 1.
    pub weights: Vec<f32>,
}

fn f32x3(v: DVec3) -> [f32; 3] {
    v.as_vec3().to_array()
}

impl BatchModel {
    /// The f32 constants of `model`.
    pub fn new(model: &StrandModel) -> Self {
        Self {
            lengths_m: model.lengths_m.iter().map(|&l| l as f32).collect(),
            stiffness: model.stiffness.iter().map(|&k| f32x3(k)).collect(),
            natural: model.natural.iter().map(|&k| f32x3(k)).collect(),
            friction: model.friction.iter().map(|&g| g as f32).collect(),
            mass_per_length: model.mass_per_length as f32,
            air_drag: model.air_drag as f32,
            nodes: model.quadrature.nodes.iter().map(|&x| x as f32).collect(),
            weights: model.quadrature.weights.iter().map(|&w| w as f32).collect(),
        }
    }

    /// Number of elements N.
    pub fn elements(&self) -> usize {
        self.lengths_m.len()
    }
}

/// What one step needs besides the strand: the same for every strand.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepEnv {
    /// Step length h, seconds.
    pub h_secs: f64,
    /// Gravity, m/s².
    pub gravity_m_per_s2: [f64; 3],
    /// Air velocity, m/s.
    pub air_velocity_m_per_s: [f64; 3],
}

/// The motion of each lane's root frame at the start of a step.
#[derive(Clone, Copy, Debug)]
pub struct RootMotion<T> {
    /// Root frame, columns (n₀, n₁, n₂) in world coordinates.
    pub world_from_root: M3<T>,
    /// Angular velocity, rad/s, world.
    pub angular_velocity_rad_per_s: V3<T>,
    /// Angular acceleration, rad/s², world.
    pub angular_acceleration_rad_per_s2: V3<T>,
    /// Velocity of the root point, m/s.
    pub velocity_m_per_s: V3<T>,
    /// Acceleration of the root point, m/s².
    pub acceleration_m_per_s2: V3<T>,
}

fn gather_v3<T: Real>(motions: &[RigidMotion], f: impl Fn(&RigidMotion) -> DVec3) -> V3<T> {
    let at = |i: usize| f(&motions[i.min(motions.len() - 1)]);
    V3::new(
        T::from_fn_f64(|i| at(i).x),
        T::from_fn_f64(|i| at(i).y),
        T::from_fn_f64(|i| at(i).z),
    )
}

fn gather_m3<T: Real>(motions: &[RigidMotion], f: impl Fn(&RigidMotion) -> DMat3) -> M3<T> {
    M3::from_cols(
        gather_v3(motions, |m| f(m).x_axis),
        gather_v3(motions, |m| f(m).y_axis),
        gather_v3(motions, |m| f(m).z_axis),
    )
}

impl<T: Real> RootMotion<T> {
    /// Lane i from `motions[i]`; lanes past the end repeat the last motion.
    /// `motions` must not be empty.
    pub fn gather(motions: &[RigidMotion]) -> Self {
        Self {
            world_from_root: gather_m3(motions, |m| m.world_from_body),
            angular_velocity_rad_per_s: gather_v3(motions, |m| m.angular_velocity_rad_per_s),
            angular_acceleration_rad_per_s2: gather_v3(motions, |m| {
                m.angular_acceleration_rad_per_s2
            }),
            velocity_m_per_s: gather_v3(motions, |m| m.velocity_m_per_s),
            acceleration_m_per_s2: gather_v3(motions, |m| m.acceleration_m_per_s2),
        }
    }
}

/// What the root-to-tip sweep leaves for each element: its beyond
/// Jacobians and its own sums (see [`crate::step::mass`] and [`crate::step::forces`]
/// for the algebra).
#[derive(Clone, Copy, Debug)]
pub struct ElementData<T> {
    /// A_Q, metres².
    pub a: M3<T>,
    /// B_Q, metres.
    pub b: M3<T>,
    /// D_Q = Σ_own wρS GᵀG, kg·m³.
    pub own_mass_block: M3<T>,
    /// Σ_own Gᵀ F w, N·m².
    pub own_force: V3<T>,
    /// Σ_own wρS, kg.
    pub mass: T,
    /// Σ_own wρS r, kg·m.
    pub first_moment: V3<T>,
    /// Σ_own wρS (|r|²𝟙 − rrᵀ), kg·m².
    pub inertia: M3<T>,
    /// Σ_own w F, N.
    pub force_sum: V3<T>,
    /// Σ_own w r × F, N·m.
    pub torque_sum: V3<T>,
    /// U_Q = Σ_own wρS G (Exact only), kg·m.
    pub u: M3<T>,
    /// V_Q = Σ_own wρS \[r\]×G (Exact only), kg·m².
    pub v: M3<T>,
    /// The element's end point minus its start point, metres (set by the
    /// sweep with local moments, see [`super::forward::forward_with`]).
    pub span: V3<T>,
    /// The implicit contact of the element's own quadrature samples
    /// ([`super::contact`]): the point inertias they add to the rigid
    /// motion of the element's start frame, for the elimination's
    /// articulated inertia and Block-diagonal's suffix sums. Zero out of
    /// contact, and when no lane of the batch touched (`touching` false).
    pub contact: ContactInertia<T>,
    /// Whether any lane's sample of this element is in contact this step.
    pub touching: bool,
}

/// The rigid-motion inertia of point inertias a aᵀ (one per sample in
/// contact, each at offset d from the moments' origin: the element's start
/// with local moments, else the root): the 6×6 Σ φ φᵀ, φ = (a, d × a), as
/// four 3×3 blocks in the order the Exact elimination holds its
/// articulated inertia H (twist to wrench: linear-linear, linear-angular,
/// angular-linear, angular-angular). For a twist (linear velocity u at
/// the origin, angular velocity ω) the points' normal speeds are
/// φᵀ(u, ω) = a·(u + ω × d). Units: kg, kg·m, kg·m, kg·m².
#[derive(Clone, Copy, Debug)]
pub struct ContactInertia<T> {
    /// Σ a aᵀ, Σ a (d × a)ᵀ, Σ (d × a) aᵀ, Σ (d × a)(d × a)ᵀ.
    pub blocks: [M3<T>; 4],
}

impl<T: Real> ContactInertia<T> {
    /// No contact.
    pub fn zero() -> Self {
        Self {
            blocks: [M3::zero(); 4],
        }
    }

    /// Adds the point inertia a aᵀ at offset `d_m`.
    #[inline(always)]
    pub fn add_point(&mut self, a: V3<T>, d_m: V3<T>) {
        let turn = d_m.cross(a);
        let [aa, ab, ba, bb] = &mut self.blocks;
        *aa = M3::outer_add(a, a, *aa);
        *ab = M3::outer_add(a, turn, *ab);
        *ba = M3::outer_add(turn, a, *ba);
        *bb = M3::outer_add(turn, turn, *bb);
    }

    /// Adds `o`.
    #[inline(always)]
    pub fn add(&mut self, o: &Self) {
        for (block, other) in self.blocks.iter_mut().zip(&o.blocks) {
            *block += *other;
        }
    }

    /// Moves the origin by `delta` (new origin minus old), as the
    /// elimination moves H ([`shift_spatial_inertia`]).
    #[inline(always)]
    pub fn shift(&mut self, delta: V3<T>) {
        shift_spatial_inertia(&mut self.blocks, delta);
    }

    /// [A; B]ᵀ (Σ φ φᵀ) [A; B] for a 3-column map (A, B) from rates to the
    /// twist, kg·m⁴ (the Block-diagonal mass block's share of the points
    /// beyond an element).
    #[inline(always)]
    pub fn project(&self, a: &M3<T>, b: &M3<T>) -> M3<T> {
        let [aa, ab, ba, bb] = &self.blocks;
        let top = aa.mul_mat_add(a, &ab.mul_mat(b));
        let bottom = ba.mul_mat_add(a, &bb.mul_mat(b));
        a.t_mul_mat_add(&top, &b.t_mul_mat(&bottom))
    }
}

/// A 6×6 twist-to-wrench matrix H (as four 3×3 blocks) moved to an origin
/// `delta` from the current one: with S = \[δ\]×, a twist about the new
/// origin is (a − Sb, b) and a wrench (f, τ − δ × f), so H′ = XᵀHX with
/// X = [[𝟙, S], [0, 𝟙]]. The Exact elimination's articulated inertia and
/// the contact's point inertias ([`ContactInertia`]) move by it.
#[inline(always)]
pub fn shift_spatial_inertia<T: Real>(h: &mut [M3<T>; 4], delta: V3<T>) {
    let [h_aa, h_ab, h_ba, h_bb] = *h;
    let skew = M3::skew(delta);
    let h_aa_s = h_aa.mul_mat(&skew);
    *h = [
        h_aa,
        h_aa_s + h_ab,
        h_ba - skew.mul_mat(&h_aa),
        h_bb + h_ba.mul_mat(&skew) - skew.mul_mat(&h_ab) - skew.mul_mat(&h_aa_s),
    ];
}

impl<T: Real> ElementData<T> {
    /// All zero.
    pub fn zero() -> Self {
        Self {
            a: M3::zero(),
            b: M3::zero(),
            own_mass_block: M3::zero(),
            own_force: V3::zero(),
            mass: T::splat(0.0),
            first_moment: V3::zero(),
            inertia: M3::zero(),
            force_sum: V3::zero(),
            torque_sum: V3::zero(),
            u: M3::zero(),
            v: M3::zero(),
            span: V3::zero(),
            contact: ContactInertia::zero(),
            touching: false,
        }
    }
}
