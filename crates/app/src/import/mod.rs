//! Grooms from other tools made into styles (`helixhair import` and the
//! window's File → Import groom…).
//!
//! [`command`] reads a curve file (through `helixhair-formats`), attaches
//! each root to the head ([`roots`]), fits each curve with Super-Helices
//! and solves its rest shape sag-free against gravity and the head
//! ([`fit`]) for the hair's material ([`material`]), and writes the
//! style; [`report`] says what it held, stiffened or could not hold.

pub mod command;
pub mod fit;
pub mod material;
pub mod report;
pub mod roots;
