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
//! engine's measure), the measures come back, and the batch system's
//! guard judges the frame's end from them and recovers a failing strand
//! on the CPU with its usual policy (the check and the retries are the
//! batch engine's, so the two engines judge alike). The state comes back
//! only where the CPU needs it: for a retry (with the frame's start, which
//! the device keeps), for a reader ([`GpuSide::current`]: the engine's
//! `q`, `v`, points, energies, export, once a frame on the first ask) and
//! before anything changes the state or steps it on the CPU
//! ([`GpuSide::sync`]). A window that draws from the device and shows
//! nothing of the state reads none ([`GpuSide::state_reads`]). A state set
//! from outside goes back to the device before the next frame. The
//! device is built on
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
//! device lost mid-run (the hair then goes on on the CPU from the last
//! state read back: the frame's start if the guard read it, else the last
//! frame a reader or a retry read; the device's memory is gone), a build
//! without the cargo feature `gpu`, the hair–hair model (not on the GPU).
//! Exact and Block-diagonal, the batch engine's two methods, both step on
//! the device.

use std::fmt;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, OnceLock};

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
    /// With the state on the device, the batch system made current from
    /// it for readers, once a frame on the first ask (`None`: the device
    /// could not be read): [`GpuSide::current`].
    synced: OnceLock<Option<Box<BatchSystem>>>,
    /// Times a reader or a change brought the state back from the device
    /// ([`Self::state_reads`]).
    state_reads: AtomicUsize,
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
            synced: OnceLock::new(),
            state_reads: AtomicUsize::new(0),
        }
    }

    /// How many times the state was read back from the device for a reader
    /// or a change on the CPU since this side was built (the guard's own
    /// reads for a retry are not counted): a window that draws from the
    /// device and shows nothing of the state reads none.
    pub fn state_reads(&self) -> usize {
        self.state_reads.load(Ordering::Relaxed)
    }

    /// `system` as its state stands now: itself, or, where its state is on
    /// the device ([`BatchSystem::state_is_elsewhere`]), a copy made
    /// current from the device, read back once a frame on the first ask
    /// (if the device cannot be read, `system` itself, the last state
    /// read).
    pub fn current<'a>(&'a self, system: &'a BatchSystem) -> &'a BatchSystem {
        if !system.state_is_elsewhere() {
            return system;
        }
        let synced = self.synced.get_or_init(|| {
            let (q, v) = self.read_device_state()?;
            let mut copy = Box::new(system.clone());
            copy.set_state_flat(&q, &v);
            Some(copy)
        });
        synced.as_deref().unwrap_or(system)
    }

    /// Brings the state back into `system` where it is on the device:
    /// before anything changes it, steps it on the CPU or builds the device
    /// again. If the device cannot be read, the hair goes on from the last
    /// state read, and [`Self::note`] says so.
    pub fn sync(&mut self, system: &mut BatchSystem) {
        if !system.state_is_elsewhere() {
            return;
        }
        let read = match self.synced.take() {
            Some(Some(copy)) => Some(copy.state_flat()),
            _ => self.read_device_state(),
        };
        match read {
            Some((q, v)) => system.set_state_flat(&q, &v),
            None => {
                system.keep_last_read_state();
                self.failed = true;
                self.note = "the GPU could not be read back; the CPU batch engine steps the \
                             hair from its last state read"
                    .to_string();
            }
        }
    }

    /// The device's state, if it can be read.
    #[cfg(feature = "gpu")]
    fn read_device_state(&self) -> Option<crate::batch::FlatState> {
        self.state_reads.fetch_add(1, Ordering::Relaxed);
        self.device.as_deref()?.read_state().ok()
    }

    #[cfg(not(feature = "gpu"))]
    fn read_device_state(&self) -> Option<crate::batch::FlatState> {
        None
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
            self.sync(system);
            self.note = reason;
            system.step_frame(head);
            return;
        }
        self.step_on_device(system, strands, head);
        // The readers' copy is of the last frame.
        self.synced = OnceLock::new();
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
            self.sync(system);
            system.step_frame(head);
            return;
        }
        if self.stale || self.device.is_none() {
            // A device built again starts from this system's state.
            self.sync(system);
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
            self.sync(system);
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
                // The device's memory is gone: the hair goes on from the
                // last state read back (this frame's start, where the
                // guard read it).
                let behind = system.state_is_elsewhere();
                system.keep_last_read_state();
                self.failed = true;
                self.device = None;
                self.note = format!(
                    "the GPU was lost ({e}); the CPU batch engine steps the hair from {}",
                    if behind {
                        "its last state read back"
                    } else {
                        "this frame on"
                    }
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
