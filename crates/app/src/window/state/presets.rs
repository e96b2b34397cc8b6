//! Presets: named strand parameters a group can take in one click.
//!
//! The four built-in presets are the first groups of the example styles in
//! `assets/styles/` (compiled in, so the binary needs no asset folder), so
//! the presets and the documented examples can never drift apart. Each
//! carries the substeps its style needs (the straight and wavy 30 cm
//! strands need 4 per frame under a head shake; see the files' comments);
//! applying one raises the style's substeps to at least that.
//!
//! The user's own presets are saved, atomically, as a RON list in one file
//! ([`user_presets_path`]), and read back on start; a malformed file is
//! reported and ignored, never overwritten until the user saves a preset.

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use helixhair_physics::StrandParams;
use serde::{Deserialize, Serialize};

use crate::atomic_write::write_atomically;
use crate::style::Style;

/// A named set of strand parameters.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Preset {
    /// What the user sees.
    pub name: String,
    /// The parameters a group takes.
    pub params: StrandParams,
    /// Fewest substeps per frame the preset is stable with.
    #[serde(default = "one")]
    pub min_substeps: u32,
}

fn one() -> u32 {
    1
}

/// The example styles the built-in presets come from, in curl order.
const BUILT_IN_SOURCES: [(&str, &str); 4] = [
    (
        "straight",
        include_str!("../../../../../assets/styles/straight.ron"),
    ),
    (
        "wavy",
        include_str!("../../../../../assets/styles/wavy.ron"),
    ),
    (
        "curly",
        include_str!("../../../../../assets/styles/curly.ron"),
    ),
    (
        "coily",
        include_str!("../../../../../assets/styles/coily.ron"),
    ),
];

/// The built-in presets: straight, wavy, curly, coily.
pub fn built_in_presets() -> Vec<Preset> {
    BUILT_IN_SOURCES
        .iter()
        .filter_map(|(name, src)| {
            // The sources are checked by a test; a broken one is skipped.
            let style = Style::from_ron(src, Path::new(name)).ok()?;
            let group = style.groups.first()?;
            Some(Preset {
                name: (*name).to_string(),
                params: group.params.clone(),
                min_substeps: style.sim.substeps,
            })
        })
        .collect()
}

/// Where the user's presets live: `$XDG_CONFIG_HOME/helixhair/presets.ron`,
/// else `~/.config/helixhair/presets.ron`, else `./helixhair-presets.ron`.
pub fn user_presets_path() -> PathBuf {
    let config = std::env::var_os("XDG_CONFIG_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".config")));
    match config {
        Some(dir) => dir.join("helixhair").join("presets.ron"),
        None => PathBuf::from("helixhair-presets.ron"),
    }
}

/// Reads the user's presets; a missing file is an empty list.
pub fn load_user_presets(path: &Path) -> anyhow::Result<Vec<Preset>> {
    let text = match std::fs::read_to_string(path) {
        Ok(text) => text,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => return Err(e).with_context(|| format!("reading {}", path.display())),
    };
    let presets: Vec<Preset> = ron::from_str(&text).map_err(|e| {
        anyhow::anyhow!(
            "{}:{}:{}: {}",
            path.display(),
            e.span.start.line,
            e.span.start.col,
            e.code
        )
    })?;
    for preset in &presets {
        preset
            .params
            .validate()
            .map_err(|e| anyhow::anyhow!("{}: preset `{}`: {e}", path.display(), preset.name))?;
    }
    Ok(presets)
}

/// Writes the user's presets atomically, creating the folder.
pub fn save_user_presets(path: &Path, presets: &[Preset]) -> anyhow::Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    }
    let text = ron::ser::to_string_pretty(&presets, ron::ser::PrettyConfig::default())
        .context("writing presets as RON")?;
    write_atomically(path, text.as_bytes()).with_context(|| format!("saving {}", path.display()))
}

/// Gives group `group` of `style` the preset's parameters, keeping the
/// group's roots, and raises the substeps to what the preset needs.
pub fn apply_preset(style: &mut Style, group: usize, preset: &Preset) {
    if let Some(g) = style.groups.get_mut(group) {
        g.params = preset.params.clone();
        style.sim.substeps = style.sim.substeps.max(preset.min_substeps);
    }
}

#[cfg(test)]
mod tests {
    use helixhair_physics::NaturalShape;

    use super::*;

    #[test]
    fn built_ins_are_the_example_styles_curls() {
        let presets = built_in_presets();
        let names: Vec<&str> = presets.iter().map(|p| p.name.as_str()).collect();
        assert_eq!(names, ["straight", "wavy", "curly", "coily"]);
        assert_eq!(presets[0].params.natural_shape, NaturalShape::Straight);
        // Values as the example files state them in their comments.
        assert_eq!(
            presets[2].params.natural_shape,
            NaturalShape::Helix {
                radius_m: 0.012,
                step_m: 0.03
            }
        );
        assert_eq!(
            presets[3].params.natural_shape,
            NaturalShape::Helix {
                radius_m: 0.005,
                step_m: 0.008
            }
        );
        // The 30 cm examples take one substep since the velocity-implicit
        // step (docs/solvers.md, "Stability").
        assert_eq!(presets[1].min_substeps, 1);
    }

    #[test]
    fn user_presets_round_trip_and_a_bad_file_names_its_line() {
        let dir = std::env::temp_dir().join(format!("helixhair-presets-{}", std::process::id()));
        let path = dir.join("sub").join("presets.ron");
        assert!(load_user_presets(&path).unwrap().is_empty());
        let mine = Preset {
            name: "mine".into(),
            params: StrandParams {
                ellipticity: 1.5,
                ..StrandParams::default()
            },
            min_substeps: 2,
        };
        save_user_presets(&path, std::slice::from_ref(&mine)).unwrap();
        assert_eq!(load_user_presets(&path).unwrap(), vec![mine]);
        std::fs::write(&path, "[\n (name: \"x\", params: (radius_m: \"thick\"))\n]").unwrap();
        let error = load_user_presets(&path).unwrap_err().to_string();
        assert!(error.contains("presets.ron:2:"), "{error}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn applying_keeps_roots_and_never_lowers_substeps() {
        let presets = built_in_presets();
        let src = include_str!("../../../../../assets/styles/curly.ron");
        let mut style = Style::from_ron(src, Path::new("curly.ron")).unwrap();
        let roots = style.groups[0].roots.clone();
        apply_preset(&mut style, 0, &presets[1]);
        assert_eq!(style.groups[0].params, presets[1].params);
        assert_eq!(style.groups[0].roots, roots);
        assert_eq!(style.sim.substeps, 1);
        style.sim.substeps = 3;
        apply_preset(&mut style, 0, &presets[1]);
        assert_eq!(style.sim.substeps, 3);
    }
}
