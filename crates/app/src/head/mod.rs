//! The head the hair grows on: roots grown from a style's scalp
//! placements, the head a style names, and the collider made from it.
//!
//! [`groom`] grows a style's `scalp` groups into roots on the head mesh
//! (and builds the head collider the physics steps against), a coil's
//! roots framed by [`coil`]; [`of_style`]
//! finds the head an imported groom belongs to and the pivot its clips
//! turn about; [`load_head`] reads a head mesh or gives the default head.

pub mod coil;
pub mod groom;
pub mod of_style;

use std::path::Path;

use helixhair_render::HeadMesh;
use helixhair_render::head_generate::default_head;
use helixhair_render::obj::load_head_obj;

/// The head to grow hair on: `path`'s OBJ, or the default head.
pub fn load_head(path: Option<&Path>) -> anyhow::Result<HeadMesh> {
    match path {
        // An OBJ error names the file and line: no context to add.
        Some(path) => Ok(load_head_obj(path)?),
        None => Ok(default_head()),
    }
}
