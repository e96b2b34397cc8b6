//! The optional groom sections of a strand group: where its roots grow on
//! the scalp (`scalp`) and how many strands are drawn for it (`render`).
//!
//! Both are optional and default to what version-1 styles always meant
//! (roots listed one by one, every simulated strand drawn as it is), so
//! every existing style keeps loading unchanged. In a file they are plain
//! structs, `scalp: (count: 120, comb: (0.0, 0.0, -1.0))`, not RON
//! `Some(...)`: see [`inline_option`].

use glam::DVec3;
use serde::{Deserialize, Serialize};

/// Default combing direction: towards the back of the head (−z).
pub const DEFAULT_COMB: DVec3 = DVec3::new(0.0, 0.0, -1.0);
/// Default angle between a strand and the scalp at its root, degrees.
pub const DEFAULT_LIFT_DEG: f64 = 25.0;
/// Default hair colour, sRGB in [0, 1]: a medium brown.
pub const DEFAULT_COLOUR_SRGB: DVec3 = DVec3::new(0.36, 0.24, 0.15);

/// Roots placed evenly on the head's scalp instead of listed one by one.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScalpPlacement {
    /// Guide strands (simulated) to place, spread evenly (Poisson disk)
    /// over the scalp; 1 to [`crate::style::groom_validate::MAX_SCALP_GUIDES`].
    pub count: u32,
    /// The direction hair is combed in, head coordinates; at each root it
    /// is projected onto the scalp's tangent plane. Default back (−z).
    #[serde(default = "default_comb")]
    pub comb: DVec3,
    /// Angle between the strand and the scalp at the root, degrees, 0 (flat
    /// along the comb) to 90 (straight out along the normal).
    #[serde(default = "default_lift_deg")]
    pub lift_deg: f64,
    /// Seed of the placement: another seed, another even spread.
    #[serde(default = "default_seed")]
    pub seed: u64,
    /// The part of the scalp to use; default all of it.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        with = "inline_option"
    )]
    pub region: Option<ScalpRegion>,
    /// Which way a curl turns at the root; default [`CurlAxis::Hug`].
    #[serde(default, skip_serializing_if = "CurlAxis::is_hug")]
    pub curl_axis: CurlAxis,
}

/// Which way a curled strand's helix turns at its root
/// ([`crate::head::groom::scalp_root`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum CurlAxis {
    /// The strand leaves the scalp along the growth direction and its curl
    /// bends towards the scalp, so the hair hugs the head: waves lying on
    /// it. A tight coil grown this way has its helix axis far off the
    /// growth direction (76° for a 5 mm coil of 8 mm per turn), along the
    /// scalp, and its loops press into the head.
    #[default]
    Hug,
    /// The helix's axis follows the growth direction, on the side of the
    /// root away from the scalp: the strand leaves the root along the
    /// growth direction, bends into the helix over its first element
    /// ([`crate::head::coil`]), and its coils stand off the scalp
    /// instead of pressing into it. For tight curls and coils.
    Growth,
}

impl CurlAxis {
    /// Whether this is the default, [`CurlAxis::Hug`] (left out of saved
    /// styles).
    pub fn is_hug(&self) -> bool {
        *self == CurlAxis::Hug
    }
}

/// A band of the scalp: the points whose direction from the head's origin
/// lies between `from_deg` and `to_deg` of `towards`. A cone around the
/// forehead makes a fringe (`to_deg: 35`), its complement the rest
/// (`from_deg: 35`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScalpRegion {
    /// The band's axis, head coordinates (any non-zero length).
    pub towards: DVec3,
    /// Inner angle from the axis, degrees, 0 to 180; default 0.
    #[serde(default)]
    pub from_deg: f64,
    /// Outer angle from the axis, degrees, `from_deg` to 180; default 180.
    #[serde(default = "default_to_deg")]
    pub to_deg: f64,
}

impl ScalpRegion {
    /// Whether the point `p` (head coordinates) lies in the band.
    pub fn contains(&self, p: DVec3) -> bool {
        let angle = p.angle_between(self.towards).to_degrees();
        (self.from_deg..=self.to_deg).contains(&angle)
    }
}

/// How render strands take their shape from the guides.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum StrandInterpolation {
    /// The nearest guide's shape, translated: crisp curls, clumps.
    Nearest,
    /// The three nearest guides, weighted by inverse squared distance:
    /// smooth transitions (straight and wavy hair).
    #[default]
    Blend3,
}

/// The strands drawn for a group: many more than are simulated.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RenderStrands {
    /// Strands drawn for the group, 1 to
    /// [`crate::style::groom_validate::MAX_RENDER_STRANDS`]; their roots are
    /// spread on the scalp (scalp groups) or scattered around the guides'
    /// roots.
    pub count: u32,
    /// How each takes its shape from the guides. Default `Blend3`.
    #[serde(default)]
    pub method: StrandInterpolation,
    /// Largest fraction by which a drawn strand is shorter than its
    /// guides, 0 to 0.9; default 0.15, so tips thin out.
    #[serde(default = "default_length_variation")]
    pub length_variation: f64,
    /// Mean colour, sRGB components in [0, 1].
    #[serde(default = "default_colour")]
    pub colour_srgb: DVec3,
    /// Per-strand brightness variation, 0 to 1; default 0.15.
    #[serde(default = "default_colour_variation")]
    pub colour_variation: f64,
    /// How far drawn strands gather onto their nearest guide at the tip,
    /// 0 (not at all) to 1 (onto it), rising from nothing at the root:
    /// curly hair forms ringlets around its guides instead of a frizz of
    /// curls out of phase. Default 0.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub clump: f64,
}

impl Default for RenderStrands {
    /// One drawn strand per guide would be the guides themselves; this
    /// default is what the `render` command uses for a group with no
    /// `render` section: the guides, drawn in the default colour.
    fn default() -> Self {
        Self {
            count: 0,
            method: StrandInterpolation::default(),
            length_variation: 0.0,
            colour_srgb: DEFAULT_COLOUR_SRGB,
            colour_variation: default_colour_variation(),
            clump: 0.0,
        }
    }
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

fn default_comb() -> DVec3 {
    DEFAULT_COMB
}

fn default_lift_deg() -> f64 {
    DEFAULT_LIFT_DEG
}

fn default_seed() -> u64 {
    1
}

fn default_to_deg() -> f64 {
    180.0
}

fn default_length_variation() -> f64 {
    0.15
}

fn default_colour() -> DVec3 {
    DEFAULT_COLOUR_SRGB
}

fn default_colour_variation() -> f64 {
    0.15
}

/// Serde for an optional struct field written as the bare struct: absent
/// means `None` (with `#[serde(default)]`), present means `Some`, so files
/// say `scalp: (count: 100)` rather than `scalp: Some((count: 100))`.
pub mod inline_option {
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    /// Writes the value inside (use with `skip_serializing_if =
    /// "Option::is_none"`).
    pub fn serialize<T: Serialize, S: Serializer>(
        value: &Option<T>,
        serializer: S,
    ) -> Result<S::Ok, S::Error> {
        match value {
            Some(v) => v.serialize(serializer),
            None => serializer.serialize_none(),
        }
    }

    /// Reads the bare value as `Some`.
    pub fn deserialize<'de, T: Deserialize<'de>, D: Deserializer<'de>>(
        deserializer: D,
    ) -> Result<Option<T>, D::Error> {
        T::deserialize(deserializer).map(Some)
    }
}
