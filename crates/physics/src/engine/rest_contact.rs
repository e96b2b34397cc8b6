//! The head's push on a strand at rest, exactly as an engine's contact
//! applies it: the head support of the sag-free solve.
//!
//! # Why the engine's own law
//!
//! A shape holds still in simulation only if it is a static equilibrium of
//! the forces the engine applies, contact included. The head's contact is
//! a penalty spring in a skin above the surface (`collision/contact.rs`):
//! at rest a point at distance d < skin from the surface is pushed out by
//! min(k (skin − d), ρS a_max) per unit length, k = α ρS / h². That push is
//! set by where the point is, not by how much of its weight presses on the
//! head. A strand posed on the head by the simulation sits at the depth
//! where the spring balances everything that presses it there: its weight
//! and its own elasticity bending it around the skull. An imported strand
//! sits wherever the groom put it. Solving the rest shape for any other
//! support (an earlier version assumed the head carried exactly the part
//! of the weight pressing into it) leaves the spring's actual push
//! unbalanced, and the strand moves until it balances: measured, 6 mm at
//! the tips of stiff 10 cm hair frozen on the head in the window, where
//! strands hanging free held to 1 µm.
//!
//! So the support is the engine's contact force at rest, in the shape:
//! the implicit contact (α = `implicit_stiffness_ratio`) at every
//! quadrature sample, the one law both CPU engines step
//! ([`crate::batch::contact`]), with h the engine's step, dt / substeps.
//! Solved this way, the shape is an equilibrium of either engine's step.

use glam::{DMat3, DVec3};

use crate::collision::{ContactInputs, ContactSettings, SignedDistanceField};
use crate::model::StrandModel;
use crate::motion::RigidMotion;
use crate::settings::SimSettings;
use crate::step::forces::project_sample_forces;
use crate::step::reconstruct::Kinematics;

/// The head as a support: its surface, where it is, and the contact law
/// of the engine that will hold the strand.
#[derive(Clone, Copy, Debug)]
pub struct RestContact<'a> {
    /// The head's signed distance field, head coordinates.
    pub collider: &'a SignedDistanceField,
    /// The head's pose (at rest).
    pub head: RigidMotion,
    /// The contact's settings (skin, stiffness ratios, cap).
    pub settings: ContactSettings,
    /// The engine's step h, seconds (k = α ρS / h²).
    pub h_secs: f64,
}

impl<'a> RestContact<'a> {
    /// The contact of an engine stepping with `settings` (its `contact` and
    /// step) against `collider` on a head at rest at `head`'s position and
    /// orientation (either engine: they step one law).
    pub fn for_engine(
        settings: &SimSettings,
        collider: &'a SignedDistanceField,
        head: RigidMotion,
    ) -> Self {
        Self {
            collider,
            head: RigidMotion::at_rest(head.position_m, head.world_from_body),
            settings: settings.contact,
            h_secs: settings.dt_secs / f64::from(settings.substeps.max(1)),
        }
    }

    /// The push per unit length (N/m) at rest on a point at `world_m` of a
    /// strand of mass per length `rho_s`; zero out of the skin.
    pub fn push_n_per_m(&self, world_m: DVec3, rho_s: f64) -> DVec3 {
        let inputs = ContactInputs {
            collider: self.collider,
            head: &self.head,
            settings: self.settings,
            h_secs: self.h_secs,
        };
        inputs
            .implicit_force(world_m, DVec3::ZERO, rho_s)
            .map_or(DVec3::ZERO, |c| c.force_n_per_m)
    }

    /// Adds the generalized contact force on the strand in shape `kin`
    /// (reconstructed at rest from `root`) to `out`, N·m².
    pub fn add_load(
        &self,
        model: &StrandModel,
        kin: &Kinematics,
        root: &RigidMotion,
        out: &mut [DVec3],
    ) {
        let rho_s = model.mass_per_length;
        project(
            model,
            kin,
            root,
            |_, world_m| self.push_n_per_m(world_m, rho_s),
            out,
        );
    }

    /// The contact in shape `kin` linearized, for the stability test: each
    /// point's push f n changes by −k (n·Δx) n as the point moves in, and
    /// by f (∂n/∂x) Δx as the surface's normal turns under it. The signed
    /// distance field's gradient is piecewise (its grid's cells), so the
    /// exact push has no derivative where a point sits on a cell face;
    /// ∂n/∂x is taken instead by central differences of the normal over
    /// one cell (`surface_turn`): the surface's curvature. That term
    /// matters: on a convex head the normal turns the way the point moves,
    /// so a point pressed hard into the skin (f / R beside the strand's own
    /// stiffness) is pushed further along the surface, like a ball on a
    /// dome. Measured on Sintel: strands whose tips press into the
    /// neck, judged stable without this term, slid up to 58 mm off in a second.
    pub fn linearize(&self, model: &StrandModel, kin: &Kinematics, root: &RigidMotion) -> Springs {
        let rho_s = model.mass_per_length;
        let alpha = self.settings.implicit_stiffness_ratio;
        let stiffness = alpha * rho_s / (self.h_secs * self.h_secs);
        let cap = rho_s * self.settings.max_acceleration_m_per_s2;
        let springs = contact_points(kin, root)
            .into_iter()
            .map(|(world_m, _)| {
                let push = self.push_n_per_m(world_m, rho_s);
                let magnitude = push.length();
                if magnitude == 0.0 {
                    return Spring::default();
                }
                Spring {
                    at_m: world_m,
                    normal: push / magnitude,
                    push_n_per_m: magnitude,
                    // Capped, the push does not change with depth.
                    stiffness_n_per_m2: if magnitude < cap { stiffness } else { 0.0 },
                    turn_per_m: self.surface_turn(world_m),
                }
            })
            .collect();
        Springs { springs }
    }
}

impl RestContact<'_> {
    /// ∂n/∂x of the surface's outward normal at `world_m`, 1/m: central
    /// differences of the field's normalised gradient over ±half a cell
    /// along each axis (head coordinates, turned into world ones).
    fn surface_turn(&self, world_m: DVec3) -> DMat3 {
        let rotation = self.head.world_from_body;
        let local = rotation.transpose() * (world_m - self.head.position_m);
        let half_m = 0.5 * self.collider.cell_m;
        let normal = |p: DVec3| {
            self.collider
                .sample(p)
                .map_or(DVec3::ZERO, |(_, gradient)| gradient.normalize_or_zero())
        };
        let columns = [DVec3::X, DVec3::Y, DVec3::Z].map(|axis| {
            (normal(local + axis * half_m) - normal(local - axis * half_m)) / (2.0 * half_m)
        });
        rotation * DMat3::from_cols(columns[0], columns[1], columns[2]) * rotation.transpose()
    }
}

/// One point's contact frozen about a shape.
#[derive(Clone, Copy, Debug, Default)]
struct Spring {
    /// Where the point was, world, metres.
    at_m: DVec3,
    /// The push's direction there.
    normal: DVec3,
    /// The push there, N/m (zero: out of contact).
    push_n_per_m: f64,
    /// How fast the push grows as the point moves in along the normal,
    /// N/m².
    stiffness_n_per_m2: f64,
    /// How the normal turns as the point moves, ∂n/∂x, 1/m.
    turn_per_m: DMat3,
}

/// The head's contact linearized about a shape ([`RestContact::linearize`]).
#[derive(Clone, Debug)]
pub struct Springs {
    springs: Vec<Spring>,
}

impl Springs {
    /// Adds the linearized contact's generalized force on shape `kin`
    /// (reconstructed at rest from `root`) to `out`, N·m².
    pub fn add_load(
        &self,
        model: &StrandModel,
        kin: &Kinematics,
        root: &RigidMotion,
        out: &mut [DVec3],
    ) {
        project(
            model,
            kin,
            root,
            |i, world_m| {
                let s = &self.springs[i];
                let moved_m = world_m - s.at_m;
                let inward_m = -s.normal.dot(moved_m);
                s.normal * (s.push_n_per_m + s.stiffness_n_per_m2 * inward_m)
                    + s.turn_per_m * moved_m * s.push_n_per_m
            },
            out,
        );
    }
}

/// The quadrature samples of shape `kin` (reconstructed at rest from
/// `root`), world, metres, each with the length of strand it stands for
/// (its weight), metres.
fn contact_points(kin: &Kinematics, root: &RigidMotion) -> Vec<(DVec3, f64)> {
    kin.samples
        .iter()
        .map(|s| (root.position_m + s.position_m, s.weight_m))
        .collect()
}

/// Adds to `out` the generalized force of `force_n_per_m(sample, world_m)`
/// acting at every quadrature sample.
fn project(
    model: &StrandModel,
    kin: &Kinematics,
    root: &RigidMotion,
    force_n_per_m: impl Fn(usize, DVec3) -> DVec3,
    out: &mut [DVec3],
) {
    let forces: Vec<DVec3> = contact_points(kin, root)
        .into_iter()
        .enumerate()
        .map(|(i, (world_m, length_m))| force_n_per_m(i, world_m) * length_m)
        .collect();
    let mut load = vec![DVec3::ZERO; out.len()];
    project_sample_forces(model, kin, |i| forces[i], &mut load);
    for (o, l) in out.iter_mut().zip(load) {
        *o += l;
    }
}
