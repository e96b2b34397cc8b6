//! The geometry of a Super-Helix strand, in closed form: no state, no
//! dynamics.
//!
//! An element is a piece of helix whose curvatures and twist are its
//! generalized coordinates q. [`helix`] gives its centreline, frame and
//! Jacobians in closed form, [`helix_rates`] their time derivatives (for
//! the velocity terms), differentiated with the second-order jets of
//! [`jet`]; [`quadrature`] places the Gauss–Legendre nodes every integral
//! along an element uses; [`shape`] chains the elements from the root into
//! a strand's shape alone.

pub mod helix;
pub mod helix_rates;
pub mod jet;
pub mod quadrature;
pub mod shape;
