//! Styling by hand: brush strokes that move, cut, curl, part and freeze
//! real Super-Helix hair, the physics running, and what they leave in the
//! style.
//!
//! Curve groomers (Blender's curves sculpt mode, XGen, Houdini) move
//! curves, and the simulation is a later step that sags what was groomed.
//! Here the brush acts on the simulated hair itself: a combed strand stays
//! inextensible, collides with the head and keeps its curl, and what is
//! combed stays combed, because the strand's new shape becomes its rest
//! shape (the sag-free solve the import uses, [`freeze`]).
//!
//! - [`strokes`]: the stroke file (tools, brush path, radius, strength,
//!   falloff), read with errors naming file, line and field;
//! - [`sphere`]: which points a brush reaches and with what weight;
//! - [`session`]: a style's hair on its head, stroke by stroke, every
//!   change kept as a per-strand edit of the style
//!   ([`crate::style::strand_edit`]);
//! - [`freeze`]: a strand's current shape made its rest shape;
//! - [`command`]: `helixhair groom --style IN --strokes S --out OUT`.

pub mod command;
pub mod freeze;
pub mod session;
pub mod sphere;
pub mod strokes;
