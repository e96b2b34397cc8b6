//! Checks of the groom sections (`scalp`, `render`) of a strand group,
//! naming the offending field as the rest of the style's checks do.

use crate::style::checks::{check_finite, invalid};
use crate::style::error::StyleIssue;
use crate::style::field_path::FieldPath;
use crate::style::groom::{RenderStrands, ScalpPlacement, ScalpRegion};

/// Most guide strands one group may place on the scalp: every one is
/// simulated, and a few thousand already cost seconds per frame.
pub const MAX_SCALP_GUIDES: u32 = 5_000;

/// Most strands one group may draw (about 100 MB of vertices at 60 points
/// per strand).
pub const MAX_RENDER_STRANDS: u32 = 200_000;

/// Checks `scalp` (at path `at`).
pub fn validate_scalp(scalp: &ScalpPlacement, at: &FieldPath) -> Result<(), StyleIssue> {
    check_count(scalp.count, MAX_SCALP_GUIDES, &at.field("count"))?;
    let comb = at.field("comb");
    check_finite(scalp.comb, &comb, None)?;
    if scalp.comb.length() < 1e-9 {
        return Err(invalid(
            comb,
            "must not be zero: it is the direction hair is combed in",
        ));
    }
    check_range(scalp.lift_deg, 0.0, 90.0, &at.field("lift_deg"))?;
    if let Some(region) = &scalp.region {
        validate_region(region, &at.field("region"))?;
    }
    Ok(())
}

fn validate_region(region: &ScalpRegion, at: &FieldPath) -> Result<(), StyleIssue> {
    let towards = at.field("towards");
    check_finite(region.towards, &towards, None)?;
    if region.towards.length() < 1e-9 {
        return Err(invalid(towards, "must not be zero: it is the band's axis"));
    }
    check_range(region.from_deg, 0.0, 180.0, &at.field("from_deg"))?;
    check_range(region.to_deg, region.from_deg, 180.0, &at.field("to_deg"))
}

/// Checks `render` (at path `at`).
pub fn validate_render(render: &RenderStrands, at: &FieldPath) -> Result<(), StyleIssue> {
    check_count(render.count, MAX_RENDER_STRANDS, &at.field("count"))?;
    check_range(
        render.length_variation,
        0.0,
        0.9,
        &at.field("length_variation"),
    )?;
    let colour = at.field("colour_srgb");
    check_finite(render.colour_srgb, &colour, None)?;
    for (k, c) in render.colour_srgb.to_array().into_iter().enumerate() {
        check_range(c, 0.0, 1.0, &colour.index(k))?;
    }
    check_range(
        render.colour_variation,
        0.0,
        1.0,
        &at.field("colour_variation"),
    )?;
    check_range(render.clump, 0.0, 1.0, &at.field("clump"))
}

fn check_count(count: u32, max: u32, at: &FieldPath) -> Result<(), StyleIssue> {
    if count == 0 || count > max {
        return Err(invalid(
            at.clone(),
            format!("must lie in 1..={max}; found {count}"),
        ));
    }
    Ok(())
}

fn check_range(x: f64, lo: f64, hi: f64, at: &FieldPath) -> Result<(), StyleIssue> {
    if !(lo..=hi).contains(&x) {
        return Err(invalid(
            at.clone(),
            format!("must lie in [{lo}, {hi}]; found {x}"),
        ));
    }
    Ok(())
}
