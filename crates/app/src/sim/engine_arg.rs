//! The engine options `sim`, `render` and `export` share: `--engine` and
//! `--interaction`, parsed as the physics crate spells them.

use helixhair_physics::engine::EngineKind;

/// Parses an engine name as [`EngineKind::label`] spells it.
pub fn parse_engine(name: &str) -> Result<EngineKind, String> {
    EngineKind::from_name(name).ok_or_else(|| {
        let names: Vec<&str> = EngineKind::ALL.iter().map(|k| k.label()).collect();
        format!(
            "unknown engine `{name}`; expected one of {}",
            names.join(", ")
        )
    })
}

/// Parses `--interaction`: `on` or `off`.
pub fn parse_interaction(name: &str) -> Result<bool, String> {
    match name {
        "on" => Ok(true),
        "off" => Ok(false),
        _ => Err(format!("unknown interaction `{name}`; expected on or off")),
    }
}
