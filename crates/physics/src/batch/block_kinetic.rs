//! Block-diagonal's own strain kinetic energy T_bd = ½ Σ_Q q̇_Qᵀ M_QQ q̇_Q,
//! for the guard's measure of a Block-diagonal frame on both engines
//! ([`super::measure`]; why the guard needs it:
//! [`crate::frame_balance::KineticEnergy`]).
//!
//! # How it works
//!
//! Element Q's rate alone moves its own samples by w = R_Q ḣ(σ) (the
//! sample's velocity less the rigid motion of the element's start frame)
//! and everything beyond it rigidly: by u_Q + β_Q × (r − p_Q+1), where β_Q
//! is the turn the element adds to its end frame (ω_Q+1 − ω_Q) and u_Q the
//! velocity it adds to its end point. The sweep that measures the strand
//! ([`super::forward::sweep_samples`]) visits the samples root to tip; per
//! element it records u_Q, β_Q, the span p_Q+1 − p_Q and its own samples'
//! mass moments about its start point, and sums their ½ ρS|w|². A
//! tip-to-root pass then carries the suffix moments (m, c = Σ m d,
//! S = Σ m d dᵀ, d = r − p) from each element's end point to its start,
//! and adds each element's beyond term
//! Σ m|u + β × d|² = m|u|² + 2 u·(β × c) + |β|² tr S − βᵀ S β.
//! Moments about nearby points, not the root, keep f32's digits.

use super::forward::FrameState;
use super::lanes::Real;
use super::vec::{M3, V3};

/// Mass moments of samples about a point: Σ m, Σ m d, Σ m d dᵀ.
#[derive(Clone, Copy, Debug)]
struct Moments<T> {
    mass: T,
    first: V3<T>,
    second: M3<T>,
}

impl<T: Real> Moments<T> {
    fn zero() -> Self {
        Self {
            mass: T::splat(0.0),
            first: V3::zero(),
            second: M3::zero(),
        }
    }

    /// Adds a sample of mass `m` at `d` from the point.
    fn add(&mut self, m: T, d: V3<T>) {
        self.mass += m;
        self.first = d.scale_add(m, self.first);
        self.second = M3::outer_add(d.scale(m), d, self.second);
    }

    /// The same samples about a point `by` behind this one (d → d + by).
    fn moved(self, by: V3<T>) -> Self {
        let c = self.first;
        Self {
            mass: self.mass,
            first: by.scale_add(self.mass, c),
            second: M3::outer_add(
                by.scale(self.mass),
                by,
                M3::outer_add(by, c, M3::outer_add(c, by, self.second)),
            ),
        }
    }

    /// Both sets of samples, about the same point.
    fn plus(self, o: Self) -> Self {
        Self {
            mass: self.mass + o.mass,
            first: self.first + o.first,
            second: self.second + o.second,
        }
    }

    /// Σ m |u + β × d|².
    fn rigid_motion_square(&self, u: V3<T>, beta: V3<T>) -> T {
        let s = &self.second;
        let trace = s.c0.x + s.c1.y + s.c2.z;
        let two = T::splat(2.0);
        self.mass * u.dot(u) + two * u.dot(beta.cross(self.first)) + beta.dot(beta) * trace
            - beta.dot(s.mul_vec(beta))
    }
}

/// One element's record from the root-to-tip sweep.
#[derive(Clone, Copy, Debug)]
struct ElementRecord<T> {
    /// Velocity its rate adds to its end point, m/s.
    u: V3<T>,
    /// Turn its rate adds to its end frame, rad/s.
    beta: V3<T>,
    /// End point less start point, m.
    span: V3<T>,
    /// Its own samples about its start point.
    own: Moments<T>,
}

/// T_bd summed over a strand (or batch) as [`super::forward::sweep_samples`]
/// visits it: call [`Self::sample`] for each sample and
/// [`Self::element_end`] at each element's end, in the sweep's order, then
/// [`Self::finish`].
#[derive(Debug)]
pub struct BlockKinetic<T> {
    /// The current element's start state.
    start: FrameState<T>,
    /// Σ ρS w |w_own|² so far.
    own_twice: T,
    current: Moments<T>,
    elements: Vec<ElementRecord<T>>,
}

impl<T: Real> BlockKinetic<T> {
    /// Starts at the root state `root`, reusing `buffer`'s allocation.
    pub fn new(root: FrameState<T>, mut buffer: BlockKineticBuffer<T>) -> Self {
        buffer.0.clear();
        Self {
            start: root,
            own_twice: T::splat(0.0),
            current: Moments::zero(),
            elements: buffer.0,
        }
    }

    /// A sample of mass `mass` (ρS × weight × length) at `r` (relative to
    /// the root) moving at `velocity` (world).
    pub fn sample(&mut self, mass: T, r: V3<T>, velocity: V3<T>) {
        let s = &self.start;
        let d = r - s.point_m;
        let own = velocity - s.point_velocity - s.angular_velocity.cross(d);
        self.own_twice = own.dot(own).mul_add(mass, self.own_twice);
        self.current.add(mass, d);
    }

    /// The current element ends in state `end`.
    pub fn element_end(&mut self, end: &FrameState<T>) {
        let s = &self.start;
        let span = end.point_m - s.point_m;
        self.elements.push(ElementRecord {
            u: end.point_velocity - s.point_velocity - s.angular_velocity.cross(span),
            beta: end.angular_velocity - s.angular_velocity,
            span,
            own: std::mem::replace(&mut self.current, Moments::zero()),
        });
        self.start = *end;
    }

    /// T_bd, joules per lane, and the buffer back for the next sweep.
    pub fn finish(self) -> (T, BlockKineticBuffer<T>) {
        let mut twice = self.own_twice;
        let mut beyond = Moments::zero();
        for e in self.elements.iter().rev() {
            twice += beyond.rigid_motion_square(e.u, e.beta);
            // To the element's start point, then its own samples.
            beyond = beyond.moved(e.span).plus(e.own);
        }
        (twice * T::splat(0.5), BlockKineticBuffer(self.elements))
    }
}

/// The per-element records' allocation, kept between sweeps.
#[derive(Debug, Default)]
pub struct BlockKineticBuffer<T>(Vec<ElementRecord<T>>);
