//! What the model keeps from frame to frame on either engine: its
//! settings, the rest density (built on first use), the field of the last
//! frame and how long the last frame's pass took. The engines' passes
//! ([`super::reference`], `crate::batch::volume`) gather their samples
//! their own way and run the rest through this.

use super::field::VolumeField;
use super::friction::HeadVelocity;
use super::rest::RestDensity;
use super::settings::InteractionSettings;
use super::splat::SamplePoint;
use super::splat_lanes::PointLanes;

/// The model's state between frames.
#[derive(Clone, Debug)]
pub struct ModelState {
    settings: InteractionSettings,
    rest: Option<RestDensity>,
    field: VolumeField,
    last_secs: f64,
}

impl ModelState {
    /// The model with `settings`; the rest density waits for the first frame.
    pub fn new(settings: InteractionSettings) -> Self {
        Self {
            settings,
            rest: None,
            field: VolumeField::default(),
            last_secs: 0.0,
        }
    }

    /// The settings.
    pub fn settings(&self) -> &InteractionSettings {
        &self.settings
    }

    /// New strengths take effect at the next frame; a new cell size
    /// rebuilds the rest density.
    pub fn set_settings(&mut self, settings: InteractionSettings) {
        if settings.cell_m != self.settings.cell_m {
            self.rest = None;
        }
        self.settings = settings;
    }

    /// Forgets the rest density (strands were added), rebuilt next frame.
    pub fn forget_rest(&mut self) {
        self.rest = None;
    }

    /// The rest density, once a frame has built it.
    pub fn rest(&self) -> Option<&RestDensity> {
        self.rest.as_ref()
    }

    /// The field of the last frame.
    pub fn field(&self) -> &VolumeField {
        &self.field
    }

    /// Wall time of the last frame's pass, seconds.
    pub fn last_secs(&self) -> f64 {
        self.last_secs
    }

    /// Records the wall time of this frame's pass, seconds.
    pub fn set_last_secs(&mut self, secs: f64) {
        self.last_secs = secs;
    }

    /// Builds the rest density with `build` if there is none yet; whether
    /// there is one now (none without strands).
    pub fn ensure_rest(
        &mut self,
        build: impl FnOnce(&InteractionSettings) -> Option<RestDensity>,
    ) -> bool {
        if self.rest.is_none() {
            self.rest = build(&self.settings);
        }
        self.rest.is_some()
    }

    /// Splats this frame's points, `parts` (head coordinates), in parallel
    /// when `parallel`, and returns what reading the field back needs;
    /// `None` before a rest density exists.
    pub fn update(
        &mut self,
        parts: &[&[SamplePoint]],
        head: &HeadVelocity,
        parallel: bool,
    ) -> Option<(&RestDensity, &VolumeField, &InteractionSettings)> {
        let rest = self.rest.as_ref()?;
        self.field.update(rest, parts, head, parallel);
        Some((rest, &self.field, &self.settings))
    }

    /// [`Self::update`] for points four to a group, lane by lane
    /// ([`VolumeField::update_lanes`]).
    pub fn update_lanes(
        &mut self,
        parts: &[&[PointLanes]],
        head: &HeadVelocity,
        parallel: bool,
    ) -> Option<(&RestDensity, &VolumeField, &InteractionSettings)> {
        let rest = self.rest.as_ref()?;
        self.field.update_lanes(rest, parts, head, parallel);
        Some((rest, &self.field, &self.settings))
    }
}
