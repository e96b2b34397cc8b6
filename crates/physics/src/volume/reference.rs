//! The model on the f64 reference engine ([`crate::HairSystem`]): once per
//! frame, before the strands step, reconstruct every strand, keep its
//! quadrature samples (for the pull's work) and its points
//! ([`super::pair_points`]), splat the points ([`super::field`]), and
//! hand each strand its pull ([`super::friction::VolumePull`]) for the
//! frame's steps.
//!
//! The rest density is built on first use from every strand's rest pose
//! ([`Strand::rest_pose`]: its natural strains unless told, an imported
//! sag-free strand its groomed shape; at rest, head at the origin: head
//! coordinates), on a
//! grid fitted to those points with half the longest strand to spare on
//! each side, room for hair that swings out.

use std::time::Instant;

use glam::DVec3;
use rayon::prelude::*;

use super::friction::HeadVelocity;
use super::pair_points::SampleMotion;
use super::pair_points::{Placement, pair_points};
use super::rest::RestDensity;
use super::settings::InteractionSettings;
use super::splat::SamplePoint;
use super::state::ModelState;
use crate::motion::RigidMotion;
use crate::step::reconstruct::{Kinematics, reconstruct};
use crate::strand::Strand;

/// The model's state on a reference engine.
#[derive(Clone, Debug)]
pub struct ReferenceVolume {
    state: ModelState,
    /// Per strand, its quadrature samples at the frame's start.
    samples: Vec<Vec<SampleMotion>>,
    /// Per strand, its points, one per pair of quadrature nodes.
    points: Vec<Vec<SamplePoint>>,
}

impl ReferenceVolume {
    /// The model with `settings`; the rest density waits for the first frame.
    pub fn new(settings: InteractionSettings) -> Self {
        Self {
            state: ModelState::new(settings),
            samples: Vec::new(),
            points: Vec::new(),
        }
    }

    /// Settings, rest density, last field and the last pass's time.
    pub fn state(&self) -> &ModelState {
        &self.state
    }

    /// The state, to retune the model or forget its rest density.
    pub fn state_mut(&mut self) -> &mut ModelState {
        &mut self.state
    }

    /// Gathers the strands' samples with the head at `head`, splats them
    /// and sets every strand's pull for the coming frame.
    pub fn prepare(&mut self, strands: &mut [Strand], head: &RigidMotion, parallel: bool) {
        let start = Instant::now();
        if !self
            .state
            .ensure_rest(|settings| rest_density(strands, settings))
        {
            return;
        }
        self.samples.resize_with(strands.len(), Vec::new);
        self.points.resize_with(strands.len(), Vec::new);
        let gather = |(s, (samples, points)): (&Strand, (&mut Vec<_>, &mut Vec<_>))| {
            let kin = s.kinematics(&head.carry(s.root()));
            strand_points(s, &kin, head, samples, points);
        };
        let outs = self.samples.iter_mut().zip(&mut self.points);
        if parallel {
            let outs = self.samples.par_iter_mut().zip(&mut self.points);
            strands.par_iter().zip(outs).for_each(gather);
        } else {
            strands.iter().zip(outs).for_each(gather);
        }
        let parts: Vec<&[SamplePoint]> = self.points.iter().map(Vec::as_slice).collect();
        let carried = HeadVelocity::of(head);
        let Some((rest, field, settings)) = self.state.update(&parts, &carried, parallel) else {
            return;
        };
        let hand_out = |(s, (samples, points)): (&mut Strand, (&Vec<_>, &Vec<SamplePoint>))| {
            let readings = points.iter().map(|p| field.read(rest, settings, p));
            let (target, push): (Vec<DVec3>, Vec<DVec3>) = readings
                .map(|r| {
                    let push = head.world_from_body * r.push_m_per_s2;
                    (r.relative_target_m_per_s, push)
                })
                .unzip();
            s.exchange_volume_pull((settings.friction_per_s, target, push), samples, head);
        };
        let ins = self.samples.iter().zip(&self.points);
        if parallel {
            let ins = self.samples.par_iter().zip(&self.points);
            strands.par_iter_mut().zip(ins).for_each(hand_out);
        } else {
            strands.iter_mut().zip(ins).for_each(hand_out);
        }
        self.state.set_last_secs(start.elapsed().as_secs_f64());
    }
}

/// Strand `s`'s quadrature samples of `kin` (reconstructed with the head
/// at `head`), written to `samples`, and its points in head coordinates
/// ([`pair_points`]), written to `points`.
pub fn strand_points(
    s: &Strand,
    kin: &Kinematics,
    head: &RigidMotion,
    samples: &mut Vec<SampleMotion>,
    points: &mut Vec<SamplePoint>,
) {
    let model = s.model();
    samples.clear();
    samples.extend(kin.samples.iter().map(|sample| SampleMotion {
        position_m: sample.position_m,
        velocity_m_per_s: sample.velocity_m_per_s,
        weight_m: sample.weight_m,
    }));
    let at = Placement {
        root_m: head.carry(s.root()).position_m,
        head,
        mass_per_length: model.mass_per_length,
    };
    let weights = &model.quadrature.weights;
    pair_points(samples, weights, &model.lengths_m, &at, points);
}

/// The rest density of `strands`' rest poses ([`Strand::rest_pose`]: their
/// natural shapes unless told), or `None` without strands.
pub fn rest_density(strands: &[Strand], settings: &InteractionSettings) -> Option<RestDensity> {
    let head = RigidMotion::default();
    let mut points = Vec::new();
    let (mut samples, mut one) = (Vec::new(), Vec::new());
    let mut kin = Kinematics::default();
    let mut longest_m: f64 = 0.0;
    for s in strands {
        let model = s.model();
        let still = vec![DVec3::ZERO; model.elements()];
        reconstruct(
            model,
            s.rest_pose(),
            &still,
            &head.carry(s.root()),
            &mut kin,
        );
        strand_points(s, &kin, &head, &mut samples, &mut one);
        points.extend_from_slice(&one);
        longest_m = longest_m.max(model.lengths_m.iter().sum());
    }
    RestDensity::new(&points, settings.cell_m, 0.5 * longest_m)
}
