//! [`GpuSide`]: what [`super::EngineKind::Gpu`] adds to the batch engine,
//! the device that takes its substeps ([`crate::gpu::GpuEngine`]).
//!
//! # How it works
//!
//! The GPU engine is the batch engine with its substeps taken on the GPU
//! ([`BatchSystem::step_frame_offloaded`]): the batch system keeps every
//! strand's constants, roots and a copy of the state; each frame the
//! device steps every substep in its own memory and measures every
//! strand for the guard there ([`crate::gpu::measure`], the batch
//! engine's measure), the state and the measures come back once, and the
//! batch system's guard judges the frame's end from those measures and
//! recovers a failing strand on the CPU with its usual policy (the check
//! and the retries are the batch engine's, so the two engines judge
//! alike). A state set from outside goes back to the device before
//! the next frame. The device is built on
//! the first frame and again after anything it holds changes (strands,
//! collider, contact); a clone of the engine builds its own. It is built on
//! a headless device of its own, or on the one [`GpuSide::use_context`]
//! gives (a window's, whose renderer then draws the strands from the
//! engine's own buffers, [`crate::gpu::curves`]). After a frame the guard
//! changed, the changed state goes back to the device at once, so the
//! device always holds the frame's end the engine reports.
//!
//! Where the GPU cannot take the frame, the batch engine steps it on the
//! CPU and [`GpuSide::note`] says why, once in words: no adapter or a
//! device lost mid-run (the frame is then stepped again on the CPU from
//! its start), a build without the cargo feature `gpu`, the hair–hair
//! model (not on the GPU). Exact and Block-diagonal, the batch engine's
//! two methods, both step on the device.

use std::fmt;
use std::sync::Arc;

use crate::batch::BatchSystem;
use crate::model::StrandModel;
use crate::motion::{HeadTrajectory, RootPose};
use crate::settings::Method;

/// The GPU engine's device and its standing (module docs).
pub struct GpuSide {
    #[cfg(feature = "gpu")]
    device: Option<Box<crate::gpu::GpuEngine>>,
    /// The device to build on (a window's, so that its renderer draws
    /// from the engine's buffers); `None`: a headless one of its own.
    #[cfg(feature = "gpu")]
    context: Option<Box<crate::gpu::GpuContext>>,
    /// The device must be built again before the next frame.
    stale: bool,
    /// The batch system's state must go to the device before the next
    /// frame.
    upload: bool,
    /// Whether building or reading the device failed: the CPU steps on.
    failed: bool,
    /// What steps the frames, in words: the adapter, or why the CPU does.
    note: String,
}

impl GpuSide {
    /// Nothing built yet: the first frame builds the device.
    pub fn new() -> Self {
        Self {
            #[cfg(feature = "gpu")]
            device: None,
            #[cfg(feature = "gpu")]
            context: None,
            stale: true,
            upload: true,
            failed: false,
            note: "the GPU engine starts on the first frame".to_string(),
        }
    }

    /// Strands, collider or contact changed: build the device again.
    pub fn invalidate(&mut self) {
        self.stale = true;
    }

    /// The batch system's state changed: send it before the next frame.
    pub fn state_changed(&mut self) {
        self.upload = true;
    }

    /// What steps the frames, in words: "physics on the GPU (adapter)",
    /// or why the CPU batch engine steps them.
    pub fn note(&self) -> &str {
        &self.note
    }

    /// The device, once built and working.
    #[cfg(feature = "gpu")]
    pub fn device(&self) -> Option<&crate::gpu::GpuEngine> {
        self.device.as_deref().filter(|_| !self.failed)
    }

    /// The device, once built and working, to write its curves
    /// ([`crate::gpu::GpuEngine::write_curves`]). At a frame's end it holds
    /// the batch system's state, the guard's recoveries included.
    #[cfg(feature = "gpu")]
    pub fn device_mut(&mut self) -> Option<&mut crate::gpu::GpuEngine> {
        if self.failed {
            return None;
        }
        self.device.as_deref_mut()
    }

    /// Builds the device on `context` from the next frame on (a window's
    /// device, shared with its renderer), or on a headless device of its
    /// own with `None`. A different device rebuilds.
    #[cfg(feature = "gpu")]
    pub fn use_context(&mut self, context: Option<crate::gpu::GpuContext>) {
        let same = match (&self.context, &context) {
            (Some(a), Some(b)) => a.same_device(b),
            (None, None) => true,
            _ => false,
        };
        if !same {
            self.context = context.map(Box::new);
            self.stale = true;
        }
    }

    /// Why the GPU cannot take `system`'s frames, if it cannot.
    fn unsupported(&self, system: &BatchSystem) -> Option<String> {
        let settings = system.settings();
        if !matches!(settings.method, Method::Exact | Method::BlockDiagonal) {
            return Some(format!(
                "the GPU engine runs Exact and Block-diagonal; {} steps on the CPU batch engine",
                settings.method.label()
            ));
        }
        if settings.interaction.enabled {
            return Some(
                "the GPU engine has no hair–hair model; the CPU batch engine steps the hair"
                    .to_string(),
            );
        }
        if system.strand_count() == 0 {
            return Some("no strands".to_string());
        }
        None
    }

    /// One frame of `system` (whose strands are `strands`, in index
    /// order): on the device where it can, else on the CPU (module docs).
    pub fn step_frame(
        &mut self,
        system: &mut BatchSystem,
        strands: &[(Arc<StrandModel>, RootPose)],
        head: &dyn HeadTrajectory,
    ) {
        if let Some(reason) = self.unsupported(system) {
            self.note = reason;
            system.step_frame(head);
            return;
        }
        self.step_on_device(system, strands, head);
    }

    #[cfg(feature = "gpu")]
    fn step_on_device(
        &mut self,
        system: &mut BatchSystem,
        strands: &[(Arc<StrandModel>, RootPose)],
        head: &dyn HeadTrajectory,
    ) {
        use crate::batch::layout::BatchModel;
        use crate::gpu::{GpuContext, GpuEngine, GpuError};
        if self.failed {
            system.step_frame(head);
            return;
        }
        if self.stale || self.device.is_none() {
            let models: Vec<BatchModel> = strands.iter().map(|(m, _)| BatchModel::new(m)).collect();
            let roots: Vec<RootPose> = strands.iter().map(|(_, r)| *r).collect();
            let collider = system.collider().map(|c| &**c);
            let context = match &self.context {
                Some(ctx) => Ok((**ctx).clone()),
                None => GpuContext::new_headless(),
            };
            let built = context
                .map_err(GpuError::from)
                .and_then(|ctx| GpuEngine::new(ctx, system.settings(), &models, &roots, collider));
            match built {
                Ok(device) => {
                    self.note = format!("physics on the GPU ({})", device.adapter_name());
                    self.device = Some(Box::new(device));
                    self.stale = false;
                    self.upload = true;
                }
                Err(e) => {
                    self.failed = true;
                    self.device = None;
                    self.note = format!("{e}; the CPU batch engine steps the hair");
                    system.step_frame(head);
                    return;
                }
            }
        }
        let Some(device) = self.device.as_deref_mut() else {
            system.step_frame(head);
            return;
        };
        match system.step_frame_offloaded(head, device, self.upload) {
            Ok(changed) => {
                // The device holds the frame's end as the guard left it, so
                // that what is drawn from it is what the frame reports.
                if changed {
                    let (q, v) = system.state_flat();
                    device.set_state(&q, &v);
                }
                self.upload = false;
            }
            Err(e) => {
                self.failed = true;
                self.device = None;
                self.note = format!(
                    "the GPU was lost ({e}); the CPU batch engine steps the hair from this frame on"
                );
                system.step_frame(head);
            }
        }
    }

    #[cfg(not(feature = "gpu"))]
    fn step_on_device(
        &mut self,
        system: &mut BatchSystem,
        _strands: &[(Arc<StrandModel>, RootPose)],
        head: &dyn HeadTrajectory,
    ) {
        self.note = "this build has no GPU path (cargo feature `gpu`); the CPU batch engine \
                     steps the hair"
            .to_string();
        system.step_frame(head);
    }
}

impl Default for GpuSide {
    fn default() -> Self {
        Self::new()
    }
}

/// A clone builds its own device on its first frame.
impl Clone for GpuSide {
    fn clone(&self) -> Self {
        Self {
            failed: self.failed,
            note: self.note.clone(),
            #[cfg(feature = "gpu")]
            context: self.context.clone(),
            ..Self::new()
        }
    }
}

impl fmt::Debug for GpuSide {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("GpuSide")
            .field("stale", &self.stale)
            .field("failed", &self.failed)
            .field("note", &self.note)
            .finish()
    }
}
