//! The hair as drawn and exported: from the simulated guides to the
//! strands a picture or a file shows.
//!
//! The physics steps a few guide strands; a style draws many more.
//! [`layout`] places the drawn strands on the scalp once and picks the
//! guides each follows; [`drawn`] rebuilds them every frame from their
//! guides' strains ([`strain_blend`]), curls a clump's strands each in
//! its own phase ([`curl_variation`]), colours them ([`colours`]) and
//! drapes them over the head. [`guide_curves`] samples the guides
//! themselves finely enough to draw their curls, and [`sampling`] gives
//! every strand a fixed point count for the file formats.

pub mod colours;
pub mod curl_variation;
pub mod drawn;
pub mod guide_curves;
pub mod layout;
pub mod sampling;
pub mod strain_blend;

#[cfg(test)]
mod groom_tests;
#[cfg(test)]
mod layout_tests;
