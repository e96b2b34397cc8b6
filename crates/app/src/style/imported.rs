//! Imported strands in a style: a group's strands fitted from a groom made
//! elsewhere (`helixhair import`, docs/import.md).
//!
//! A procedural group shares one [`StrandParams`] among its strands: one
//! length, one element count, one natural shape. An imported groom has
//! none of that in common: each strand has its own length, its own number
//! of elements (the fewest that reproduce it) and its own rest strains. So
//! an `imported` section lists, per strand, its root (position, growth
//! direction, frame reference: the [`Root`] of listed roots), its element
//! length, the fitted strains it starts in (`strains`) and its natural
//! strains (`natural`: sag-free, or the fitted ones with `--no-sag-free`).
//! The group's `params` still give the material (radius, density, moduli,
//! friction, drag); their `length_m`, `elements`, `layout` and
//! `natural_shape` are replaced per strand ([`ImportedStrand::params`]).
//!
//! `guide: false` marks a strand that is not simulated (`--guides K`); a
//! group whose strands are all guides simulates every one. Every strand is
//! drawn: the others as their own imported shape bent by the strain change
//! of their three nearest guides ([`crate::hair::layout`]).

use glam::DVec3;
use helixhair_physics::fit::stiffen::stiffened_params;
use helixhair_physics::{ElementLayout, NaturalShape, RootPose, StrandParams};
use serde::{Deserialize, Serialize};

use crate::style::root::Root;

/// Most imported strands one group may hold (a dense real groom has about
/// 100,000 hairs; public grooms ship 10,000 to 50,000 guides).
pub const MAX_IMPORTED_STRANDS: usize = 200_000;

/// The strands of an imported groom.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImportedStrands {
    /// The groom file it came from, relative to the style's folder (a
    /// record: the strands below are complete without it).
    pub source: String,
    /// The head mesh the roots were attached to, relative to the style's
    /// folder, if one was given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub head: Option<String>,
    /// The mesh the hair collides with and rests on, relative to the
    /// style's folder, when it is not `head`: a coarse closed stand-in (an
    /// offset hull) for a detailed bust whose lips and ears would catch
    /// the hair. `head` stays the mesh drawn and exported.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub collider: Option<String>,
    /// One entry per strand, in the groom's order.
    pub strands: Vec<ImportedStrand>,
}

/// One fitted strand.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImportedStrand {
    /// Root point, growth direction and frame reference (head coordinates).
    pub root: Root,
    /// Length of each of the strand's elements, metres.
    pub element_length_m: f64,
    /// Fitted strains (τ, κ₁, κ₂) per element, m⁻¹: the imported shape,
    /// which the simulation starts in.
    pub strains: Vec<DVec3>,
    /// Natural strains per element, m⁻¹ (as many as `strains`).
    pub natural: Vec<DVec3>,
    /// Whether the strand is simulated (a guide). Default true.
    #[serde(default = "yes", skip_serializing_if = "is_true")]
    pub guide: bool,
    /// Factor on the group's Young's and shear moduli for this strand, ≥ 1.
    /// Default 1. The import raises it for a strand whose sag-free
    /// equilibrium is unstable, by the least that holds it
    /// (`helixhair_physics::fit::stiffen`); at most
    /// `helixhair_physics::fit::stiffen::MAX_STIFFNESS_SCALE` (1000), and
    /// the scaled moduli within their range (at most 1e12 Pa).
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub stiffness_scale: f64,
}

fn one() -> f64 {
    1.0
}

fn is_one(x: &f64) -> bool {
    *x == 1.0
}

fn yes() -> bool {
    true
}

fn is_true(b: &bool) -> bool {
    *b
}

impl ImportedStrand {
    /// The strand's physics: `material`'s fields with this strand's length,
    /// elements and natural strains, its moduli scaled by its
    /// `stiffness_scale`.
    pub fn params(&self, material: &StrandParams) -> StrandParams {
        let material = &stiffened_params(material, self.stiffness_scale);
        StrandParams {
            length_m: self.element_length_m * self.strains.len() as f64,
            elements: self.strains.len(),
            layout: ElementLayout::Uniform,
            natural_shape: NaturalShape::PerElement(
                self.natural.iter().map(|k| k.to_array()).collect(),
            ),
            ..material.clone()
        }
    }

    /// The strand's root frame.
    pub fn pose(&self) -> RootPose {
        self.root.pose()
    }
}

impl ImportedStrands {
    /// The strands that are simulated, in order.
    pub fn guides(&self) -> impl Iterator<Item = &ImportedStrand> {
        self.strands.iter().filter(|s| s.guide)
    }
}
