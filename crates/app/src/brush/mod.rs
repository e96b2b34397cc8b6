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
//! - [`host`]: what a brush acts on (the headless session, the window's
//!   live run), and the brush's reach and forces on it;
//! - [`stroke_run`]: one stroke as it happens, begun, dragged frame by
//!   frame and finished, the same code live and replayed;
//! - [`tools`]: what each tool leaves in the style (cut, grown, curled,
//!   stiffened, smoothed, parted, frozen);
//! - [`session`]: a style's hair on its head, stroke by stroke, every
//!   change kept as a per-strand edit of the style
//!   ([`crate::style::strand_edit`]);
//! - [`freeze`]: a strand's current shape made its rest shape;
//! - [`command`]: `helixhair groom --style IN --strokes S --out OUT`.

pub mod command;
pub mod freeze;
pub mod host;
pub mod session;
pub mod sphere;
pub mod stroke_run;
pub mod strokes;
pub mod tools;
