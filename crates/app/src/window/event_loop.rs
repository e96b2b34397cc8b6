//! The winit event loop: opens the window, feeds input to egui, and each
//! frame steps the physics, draws the 3D pictures, lays out the panels and
//! presents.
//!
//! A frame, on `RedrawRequested`:
//!
//! 1. [`AppState::step_frame`]: edits reach the simulation, one frame of
//!    physics runs on the head's motion;
//! 2. the renderer draws the hair and head into the view's picture(s),
//!    sized as the view was in the previous frame;
//! 3. egui lays out the panels around the pictures and handles input;
//!    a finished drag becomes one undo step;
//! 4. egui is painted to the surface (and, for `--screenshot`, read back);
//!    on a software adapter the panels are repainted only where they
//!    changed ([`crate::window::present::panel_layer`]).
//!
//! The loop redraws continuously (`about_to_wait` requests the next frame);
//! the surface's vsync paces it.

use std::sync::Arc;
use std::time::Instant;

use anyhow::Context as _;
use glam::Mat4;
use helixhair_physics::gpu::GpuEngine;
use helixhair_render::{Light, Scene};
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::window::{Window, WindowId};

use crate::style::Style;

use super::{HEADLESS_HINT, WindowArgs};
use crate::window::live::drawn::DrawnCache;
use crate::window::live::live_sim::LiveSim;
use crate::window::panels::files::import_dialog::{ImportDialog, open_material};
use crate::window::panels::ui::draw;
use crate::window::panels::view_state::ViewState;
use crate::window::present::frame_profile::FrameProfile;
use crate::window::present::preview::{quality, wants_preview};
use crate::window::present::screenshot::save_png;
use crate::window::present::window_gpu::WindowGpu;
use crate::window::state::app_state::{AppState, CompareMethods};
use crate::window::state::default_style::default_style;
use crate::window::state::unsaved::Leave;

/// Frames run before a screenshot when `--frames` is not given.
const SCREENSHOT_FRAMES: u32 = 120;

/// Opens the window and runs until it is closed (or `--frames` are done).
pub fn run_window(args: &WindowArgs) -> anyhow::Result<()> {
    let mut app = start_state(args)?;
    if let Some(kind) = args.engine {
        app.edit_style(|style| style.engine = kind);
    }
    if args.compare {
        app.set_compare(Some(CompareMethods::default()));
    }
    if let Some(clip) = args.play {
        app.play(clip);
    }
    let event_loop = EventLoop::new().map_err(|e| {
        let message = e.to_string();
        let why = without_source_location(&message);
        anyhow::anyhow!("cannot open a window ({why}).\n{HEADLESS_HINT}")
    })?;
    let mut handler = Handler {
        args: args.clone(),
        drawn: DrawnCache::default(),
        view: ViewState::new(app.sim().engine().strand_count()),
        app,
        open: None,
        error: None,
        frames: 0,
        last_frame: None,
        interacting: false,
        profile: FrameProfile::default(),
    };
    if let Some(groom) = &args.import {
        let material = open_material(handler.app.doc().style());
        handler.view.files.import = Some(ImportDialog::new(groom, material));
    }
    event_loop
        .run_app(&mut handler)
        .context("the window's event loop failed")?;
    match handler.error {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

/// winit's OS errors start `os error at FILE:LINE: ` with FILE a path in
/// the cargo registry of the machine that built the program: of no use to
/// a user, so it is cut off, leaving the reason.
pub fn without_source_location(message: &str) -> &str {
    match message.strip_prefix("os error at ") {
        Some(rest) => rest.split_once(": ").map_or(message, |(_, reason)| reason),
        None => message,
    }
}

fn start_state(args: &WindowArgs) -> anyhow::Result<AppState> {
    let style = match &args.style {
        Some(path) => Style::load(path)?,
        None => default_style(args.guides),
    };
    AppState::new(style, args.style.as_deref()).map_err(|e| anyhow::anyhow!(e))
}

struct Open {
    gpu: WindowGpu,
    egui: egui_winit::State,
    title: String,
}

struct Handler {
    args: WindowArgs,
    app: AppState,
    drawn: DrawnCache,
    view: ViewState,
    open: Option<Open>,
    error: Option<anyhow::Error>,
    frames: u32,
    last_frame: Option<Instant>,
    /// The user was dragging (a slider, the view, the head) last frame.
    interacting: bool,
    /// Per-stage frame times (`--profile`).
    profile: FrameProfile,
}

impl Handler {
    fn open(&mut self, event_loop: &ActiveEventLoop) -> anyhow::Result<Open> {
        let attributes = Window::default_attributes()
            .with_title(self.app.doc().title())
            .with_inner_size(winit::dpi::LogicalSize::new(1280.0, 800.0));
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .context("creating the window")?,
        );
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_with_display_handle_from_env(
                Box::new(event_loop.owned_display_handle()),
            ));
        let gpu = WindowGpu::new(&instance, window.clone(), self.args.preview)?;
        let ctx = egui::Context::default();
        let egui = egui_winit::State::new(
            ctx,
            egui::ViewportId::ROOT,
            &window,
            Some(window.scale_factor() as f32),
            None,
            None,
        );
        Ok(Open {
            gpu,
            egui,
            title: String::new(),
        })
    }

    fn frame(&mut self, event_loop: &ActiveEventLoop) -> anyhow::Result<()> {
        let Some(open) = &mut self.open else {
            return Ok(());
        };
        let now = Instant::now();
        if let Some(last) = self.last_frame.replace(now) {
            self.app
                .record_frame_time(now.duration_since(last).as_secs_f64());
        }
        self.profile.start();
        // The GPU engine steps on the window's device, so that the hair
        // can be drawn from its own buffers (a no-op once it does).
        self.app.sim_mut().set_gpu_context(open.gpu.context());
        self.app.step_frame();
        self.profile.lap(1);
        let head = self.app.sim().engine().head();
        let head_mesh = self
            .app
            .head_mesh()
            .posed(head.world_from_body.as_mat3(), head.position_m.as_vec3());
        let preview = wants_preview(self.args.preview, open.gpu.is_software(), self.interacting);
        let quality = quality(self.args.render_strands, self.view.view_px, preview);
        let world_from_head = Mat4::from_translation(head.position_m.as_vec3())
            * Mat4::from_mat3(head.world_from_body.as_mat3());
        let runs = 1 + usize::from(self.app.compare().is_some());
        for slot in 0..runs {
            let Some(run) = run_of(&self.app, slot) else {
                continue;
            };
            let (style, head_of_style) = (self.app.doc().style(), self.app.head_mesh());
            let max = quality.render_strands;
            if !self.drawn.prepare(style, head_of_style, run.engine(), max) {
                continue;
            }
            // The main run on the GPU engine draws from the engine's own
            // buffers where its layout allows; else the drawn hair is
            // rebuilt on the CPU.
            if slot == 0 {
                let view = (&head_mesh, self.view.camera, world_from_head);
                let drawn = draw_from_device(
                    &mut self.drawn,
                    &mut self.app,
                    &mut open.gpu,
                    view,
                    &quality,
                )?;
                self.app.record_drawing(drawn.map(|(_, n)| n));
                if let Some((texture, _)) = drawn {
                    self.profile.lap(2);
                    self.view.textures[slot] = Some(texture);
                    if self.args.profile {
                        open.gpu.wait_idle();
                    }
                    self.profile.lap(3);
                    continue;
                }
            }
            let Some(run) = run_of(&self.app, slot) else {
                continue;
            };
            let (style, head_of_style) = (self.app.doc().style(), self.app.head_mesh());
            let Some(hair) = self.drawn.strands(style, head_of_style, run.engine(), max) else {
                continue;
            };
            self.profile.lap(2);
            let scene = Scene {
                hair: &hair,
                head: &head_mesh,
                camera: self.view.camera,
                light: Light::default(),
            };
            self.view.textures[slot] = Some(open.gpu.draw_scene(slot, &scene, None, &quality)?);
            if self.args.profile {
                open.gpu.wait_idle();
            }
            self.profile.lap(3);
        }
        let raw = open.egui.take_egui_input(&open.gpu.window);
        let ctx = open.egui.egui_ctx().clone();
        let mut output = ctx.run_ui(raw, |ui| draw(ui, &mut self.app, &mut self.view));
        self.profile.lap(4);
        let platform = std::mem::take(&mut output.platform_output);
        open.egui.handle_platform_output(&open.gpu.window, platform);
        self.app.settle_edits(ctx.egui_is_using_pointer());
        self.interacting = ctx.egui_is_using_pointer() || ctx.input(|i| i.pointer.any_down());
        let title = self.app.doc().title();
        if title != open.title {
            open.gpu.window.set_title(&title);
            open.title = title;
        }
        self.frames += 1;
        let last = self
            .args
            .frames
            .or(self.args.screenshot.as_ref().map(|_| SCREENSHOT_FRAMES));
        let done = last.is_some_and(|n| self.frames >= n);
        let shot = open.gpu.present(
            output,
            &ctx,
            done && self.args.screenshot.is_some(),
            (&mut self.profile, self.args.profile),
        )?;
        self.profile.finish(open.gpu.panels_repainted_px());
        if let (Some(image), Some(path)) = (shot, &self.args.screenshot) {
            save_png(&image, path)?;
        }
        if done {
            let adapter = open.gpu.adapter_label();
            self.summary(&adapter);
            event_loop.exit();
        }
        if self.app.wants_to_quit() {
            event_loop.exit();
        }
        Ok(())
    }

    /// Prints frame and physics times over the second half of the run.
    fn summary(&self, adapter: &str) {
        let n = (self.frames / 2).max(1) as usize;
        let r = self.app.readouts();
        let ms = |s: Option<f64>| s.map_or(f64::NAN, |s| 1e3 * s);
        println!(
            "helixhair window: {} frames on {adapter}; {} engine, {} guide strands, at most {} drawn strands (--render-strands), {} elements",
            self.frames,
            self.app.sim().kind().label(),
            self.app.sim().engine().strand_count(),
            self.args.render_strands,
            self.app.sim().engine().element_count()
        );
        println!(
            "last {n} frames: frame time {:.1} ms (median {:.1} ms), physics {:.1} ms per frame (median {:.1} ms), {:.3e} element-steps/s",
            ms(r.mean_frame_secs(n)),
            ms(r.median_frame_secs(n)),
            ms(r.mean_physics_secs(n)),
            ms(r.median_physics_secs(n)),
            r.element_steps_per_sec(n).unwrap_or(0.0)
        );
        match r.drawn_on_device() {
            Some(n) => println!("hair: {n} strands drawn from the GPU engine's buffers"),
            None => println!("hair: drawn strands rebuilt on the CPU from the guides"),
        }
        if let Some(side) = self.app.sim().engine().gpu_side() {
            println!(
                "state: read back from the GPU {} times in {} frames (a retry's reads aside)",
                side.state_reads(),
                self.frames
            );
        }
        if self.args.profile {
            println!("{}", self.profile.line(n));
        }
    }
}

impl ApplicationHandler for Handler {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.open.is_some() {
            return;
        }
        match self.open(event_loop) {
            Ok(open) => {
                open.gpu.window.request_redraw();
                self.open = Some(open);
            }
            Err(e) => {
                self.error = Some(e.context(format!("cannot open the window.\n{HEADLESS_HINT}")));
                event_loop.exit();
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let Some(open) = &mut self.open else {
            return;
        };
        let _ = open.egui.on_window_event(&open.gpu.window, &event);
        match event {
            WindowEvent::CloseRequested => {
                // Unsaved edits: ask first (the frame loop exits once the
                // user has answered).
                self.app.request_leave(Leave::Close);
                if self.app.wants_to_quit() {
                    event_loop.exit();
                }
            }
            WindowEvent::Resized(size) => open.gpu.resize(size.width, size.height),
            WindowEvent::RedrawRequested => {
                if let Err(e) = self.frame(event_loop) {
                    self.error = Some(e);
                    event_loop.exit();
                }
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, _event_loop: &ActiveEventLoop) {
        if let Some(open) = &self.open {
            open.gpu.window.request_redraw();
        }
    }
}

/// The run picture `slot` shows: 0 the main run, 1 the compare view's.
fn run_of(app: &AppState, slot: usize) -> Option<&LiveSim> {
    match slot {
        0 => Some(app.sim()),
        _ => app.compare().map(|c| &c.0),
    }
}

/// Draws the main run's hair into picture 0 from the GPU engine's own
/// buffers on the window's device ([`crate::window::live::device_plan`]),
/// where the engine steps there and the layout [`DrawnCache::prepare`]
/// made allows it, with the strands drawn; `None` where the CPU must
/// rebuild the drawn hair. The view is the posed head, the camera and the
/// head's pose.
fn draw_from_device(
    drawn: &mut DrawnCache,
    app: &mut AppState,
    gpu: &mut WindowGpu,
    (head_mesh, camera, world_from_head): (
        &helixhair_render::HeadMesh,
        helixhair_render::OrbitCamera,
        Mat4,
    ),
    quality: &crate::window::present::preview::Quality,
) -> anyhow::Result<Option<(egui::TextureId, usize)>> {
    let Some((plan, shell)) = drawn.device_plan(app.sim().engine()) else {
        return Ok(None);
    };
    let Some(side) = app.sim_mut().engine_mut().gpu_side_mut() else {
        return Ok(None);
    };
    let on_window = |d: &&mut GpuEngine| d.context().same_device(gpu.context());
    let Some(device) = side.device_mut().filter(on_window) else {
        return Ok(None);
    };
    let mut ranges = Vec::new();
    let Some(strands) = plan.strands(device, &mut ranges, shell, world_from_head) else {
        return Ok(None);
    };
    let scene = Scene {
        hair: &plan.hair,
        head: head_mesh,
        camera,
        light: Light::default(),
    };
    let texture = gpu.draw_scene(0, &scene, Some(&strands), quality)?;
    Ok(Some((texture, plan.drawn_count())))
}

#[cfg(test)]
mod tests {
    use super::without_source_location;

    #[test]
    fn os_errors_lose_the_source_location_and_keep_the_reason() {
        let winit = "os error at /root/.cargo/registry/src/index/winit-0.30.13/src/platform_impl/\
                     linux/mod.rs:766: neither WAYLAND_DISPLAY nor DISPLAY is set";
        assert_eq!(
            without_source_location(winit),
            "neither WAYLAND_DISPLAY nor DISPLAY is set"
        );
        assert_eq!(without_source_location("no adapter"), "no adapter");
    }
}
