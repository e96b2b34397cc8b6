//! The model on the f64 reference engine ([`crate::HairSystem`]): once per
//! frame, before the strands step, gather every strand's quadrature
//! samples, splat them ([`super::field`]), and hand each strand its pull
//! ([`super::friction::VolumePull`]) for the frame's steps.
//!
//! The rest density is built on first use from every strand's rest shape
//! (natural strains, at rest, head at the origin: head coordinates), on a
//! grid fitted to those samples with half the longest strand to spare on
//! each side, room for hair that swings out.

use std::time::Instant;

use glam::DVec3;
use rayon::prelude::*;

use super::friction::HeadVelocity;
use super::rest::RestDensity;
use super::settings::InteractionSettings;
use super::splat::SamplePoint;
use super::state::ModelState;
use crate::motion::RigidMotion;
use crate::reconstruct::{Kinematics, reconstruct};
use crate::strand::Strand;

/// The model's state on a reference engine.
#[derive(Clone, Debug)]
pub struct ReferenceVolume {
    state: ModelState,
    points: Vec<Vec<SamplePoint>>,
}

impl ReferenceVolume {
    /// The model with `settings`; the rest density waits for the first frame.
    pub fn new(settings: InteractionSettings) -> Self {
        Self {
            state: ModelState::new(settings),
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
        self.points.resize_with(strands.len(), Vec::new);
        let gather = |(s, out): (&Strand, &mut Vec<SamplePoint>)| {
            let kin = s.kinematics(&head.carry(s.root()));
            head_points(s, &kin, head, out);
        };
        if parallel {
            strands.par_iter().zip(&mut self.points).for_each(gather);
        } else {
            strands.iter().zip(&mut self.points).for_each(gather);
        }
        let parts: Vec<&[SamplePoint]> = self.points.iter().map(Vec::as_slice).collect();
        let carried = HeadVelocity::of(head);
        let Some((rest, field, settings)) = self.state.update(&parts, &carried, parallel) else {
            return;
        };
        let hand_out = |(s, points): (&mut Strand, &Vec<SamplePoint>)| {
            let readings = points.iter().map(|p| field.read(rest, settings, p));
            let (target, push): (Vec<DVec3>, Vec<DVec3>) = readings
                .map(|r| {
                    let push = head.world_from_body * r.push_m_per_s2;
                    (r.relative_target_m_per_s, push)
                })
                .unzip();
            s.exchange_volume_pull((settings.friction_per_s, target, push), points, head);
        };
        if parallel {
            strands.par_iter_mut().zip(&self.points).for_each(hand_out);
        } else {
            strands.iter_mut().zip(&self.points).for_each(hand_out);
        }
        self.state.set_last_secs(start.elapsed().as_secs_f64());
    }
}

/// Strand `s`'s quadrature samples of `kin` (reconstructed with the head
/// at `head`) as points in head coordinates, written to `out`.
pub fn head_points(s: &Strand, kin: &Kinematics, head: &RigidMotion, out: &mut Vec<SamplePoint>) {
    let root_m = head.carry(s.root()).position_m;
    let body_from_world = head.world_from_body.transpose();
    let rho_s = s.model().mass_per_length;
    out.clear();
    out.extend(kin.samples.iter().map(|sample| SamplePoint {
        position_m: body_from_world * (root_m + sample.position_m - head.position_m),
        velocity_m_per_s: sample.velocity_m_per_s,
        mass_kg: rho_s * sample.weight_m,
    }));
}

/// The rest density of `strands`' rest shapes, or `None` without strands.
pub fn rest_density(strands: &[Strand], settings: &InteractionSettings) -> Option<RestDensity> {
    let head = RigidMotion::default();
    let mut points = Vec::new();
    let mut one = Vec::new();
    let mut kin = Kinematics::default();
    let mut longest_m: f64 = 0.0;
    for s in strands {
        let model = s.model();
        let still = vec![DVec3::ZERO; model.elements()];
        reconstruct(
            model,
            &model.natural,
            &still,
            &head.carry(s.root()),
            &mut kin,
        );
        head_points(s, &kin, &head, &mut one);
        points.extend_from_slice(&one);
        longest_m = longest_m.max(model.lengths_m.iter().sum());
    }
    RestDensity::new(&points, settings.cell_m, 0.5 * longest_m)
}
