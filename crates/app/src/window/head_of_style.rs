//! The window takes the head a style names: an imported groom opened
//! (at start, File → Open, an import, a drop) brings its own head mesh,
//! which becomes the collider, the head drawn, and the pivot the head
//! turns about ([`crate::style_head`]); any other style gets the default
//! head back.

use std::path::PathBuf;
use std::sync::Arc;

use glam::DVec3;
use helixhair_render::head_generate::default_head;
use helixhair_render::obj::load_mesh_obj;

use crate::groom::needs_head;
use crate::style_head::{head_pivot_m, style_head_path};

use super::app_state::AppState;
use super::collision::HeadCollider;
use super::live_sim::LiveSim;

impl AppState {
    /// The head mesh the open style names, if it names one it can use.
    fn wanted_head(&self) -> Option<PathBuf> {
        let style = self.doc.style();
        let path = self.doc.path()?;
        style_head_path(style, path).filter(|_| !needs_head(style))
    }

    /// Switches to the head the open style names (or back to the default
    /// head) when it is not the one in use: a new simulation colliding with
    /// it, the head turning about its pivot. On error (an unreadable mesh)
    /// the head in use stays and the message says why.
    pub fn adopt_head(&mut self) {
        let wanted = self.wanted_head();
        if wanted == self.head_path {
            return;
        }
        let mesh = match &wanted {
            Some(path) => match load_mesh_obj(path) {
                Ok(mesh) => mesh,
                Err(e) => {
                    self.message = Some(format!("the style's head is not used: {e}"));
                    return;
                }
            },
            None => default_head(),
        };
        let mesh = Arc::new(mesh);
        let style = self.doc.style().clone();
        let built = HeadCollider::from_head(&mesh).and_then(|collider| {
            let mut sim = LiveSim::new(&style, mesh.clone(), None, None)?;
            sim.set_collider(Some(collider));
            Ok(sim)
        });
        match built {
            Ok(sim) => {
                self.sim = sim;
                self.compare = None;
                self.head_mesh = mesh;
                self.head.pivot_m = match &wanted {
                    Some(_) => head_pivot_m(&style),
                    None => DVec3::ZERO,
                };
                self.head_path = wanted;
            }
            Err(e) => self.message = Some(format!("the style's head is not used: {e}")),
        }
    }
}

#[cfg(test)]
#[path = "head_of_style_tests.rs"]
mod tests;
