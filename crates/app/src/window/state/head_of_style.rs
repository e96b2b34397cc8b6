//! The window takes the head a style names: an imported groom opened
//! (at start, File → Open, an import, a drop) brings its own head mesh,
//! drawn and collided with (or its `collider` mesh, collided with), and
//! the pivot the head turns about ([`crate::head::of_style`]); any other style gets the default
//! head back.

use std::sync::Arc;

use glam::DVec3;
use helixhair_render::HeadMesh;
use helixhair_render::head_generate::default_head;

use crate::head::of_style::{HeadFiles, OwnHead, style_head_files};

use super::app_state::AppState;
use super::document::StyleDoc;
use crate::window::live::collision::HeadCollider;
use crate::window::live::live_sim::LiveSim;

/// A head for the window: its meshes, the files they came from (`None`:
/// the default head) and the point it turns about.
pub struct StyleHead {
    /// The mesh drawn, picked by the brush and exported.
    pub mesh: Arc<HeadMesh>,
    /// The mesh collided with, when the style names one apart from `mesh`.
    pub collider: Option<HeadMesh>,
    /// Their files.
    pub files: Option<HeadFiles>,
    /// Its pivot, world, metres.
    pub pivot_m: DVec3,
}

impl StyleHead {
    /// The default head, turning about the origin.
    pub fn default_head() -> Self {
        Self {
            mesh: Arc::new(default_head()),
            collider: None,
            files: None,
            pivot_m: DVec3::ZERO,
        }
    }
}

/// The head meshes `doc`'s style names, if it names any it can use.
fn wanted_head(doc: &StyleDoc) -> Option<HeadFiles> {
    style_head_files(doc.style(), doc.path()?)
}

/// The head `doc`'s style names, read, or the default head; an error
/// (naming file and line) when a named mesh cannot be read.
pub fn style_head(doc: &StyleDoc) -> Result<StyleHead, String> {
    let Some(path) = doc.path() else {
        return Ok(StyleHead::default_head());
    };
    match OwnHead::of_style(doc.style(), path).map_err(|e| e.to_string())? {
        Some(own) => Ok(StyleHead {
            mesh: Arc::new(own.drawn),
            collider: own.collider,
            files: Some(own.files),
            pivot_m: own.pivot_m,
        }),
        None => Ok(StyleHead::default_head()),
    }
}

/// A simulation of `doc`'s style colliding with `head`.
pub fn simulate_on(doc: &StyleDoc, head: &StyleHead) -> Result<LiveSim, String> {
    let collider = HeadCollider::from_head(head.collider.as_ref().unwrap_or(&head.mesh))?;
    let mut sim =
        LiveSim::new(doc.style(), head.mesh.clone(), None, None).map_err(|e| e.to_string())?;
    sim.set_collider(Some(collider));
    Ok(sim)
}

impl AppState {
    /// Switches to the head the open style names (or back to the default
    /// head) when it is not the one in use: a new simulation colliding with
    /// it, the head turning about its pivot. On error (an unreadable mesh)
    /// the head in use stays and the message says why.
    pub fn adopt_head(&mut self) {
        if wanted_head(&self.doc) == self.head_files {
            return;
        }
        let built =
            style_head(&self.doc).and_then(|head| Ok((simulate_on(&self.doc, &head)?, head)));
        match built {
            Ok((sim, head)) => {
                self.sim = sim;
                self.compare = None;
                self.head_mesh = head.mesh;
                self.head.pivot_m = head.pivot_m;
                self.head_files = head.files;
            }
            Err(e) => self.message = Some(format!("the style's head is not used: {e}")),
        }
    }
}

#[cfg(test)]
#[path = "tests/head_of_style_tests.rs"]
mod tests;
