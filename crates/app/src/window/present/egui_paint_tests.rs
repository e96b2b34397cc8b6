//! The panels' layer changes nothing on screen: a frame painted after a
//! partial repaint of the layer is byte-identical to the same frame
//! painted whole, as egui paints it.

use egui::{Pos2, RawInput, Rect, vec2};
use helixhair_gpu::context_or_skip;
use helixhair_render::gpu::readback::{copy_to_buffer, padded_bytes_per_row, read_buffer};

use super::*;

const SIZE_PX: [u32; 2] = [320, 200];
const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// A left panel with a slider at `value` and its digits, and a central
/// panel with a label.
fn frame(ctx: &egui::Context, value: f64) -> egui::FullOutput {
    let raw = RawInput {
        screen_rect: Some(Rect::from_min_size(
            Pos2::ZERO,
            vec2(SIZE_PX[0] as f32, SIZE_PX[1] as f32),
        )),
        ..Default::default()
    };
    ctx.run_ui(raw, |ui| {
        egui::Panel::left("style").show(ui, |ui| {
            let mut v = value;
            ui.add(egui::Slider::new(&mut v, 0.0..=1.0).text("curl"));
            ui.label(format!("value {value:.2}"));
        });
        egui::CentralPanel::default().show(ui, |ui| ui.label("view 0.1 0.3"));
    })
}

/// Paints `output` with `painter` into a new target and reads it back.
fn paint(
    gpu: &helixhair_render::GpuContext,
    painter: &mut EguiPainter,
    ctx: &egui::Context,
    output: egui::FullOutput,
) -> Vec<u8> {
    let (device, queue) = (&gpu.device, &gpu.queue);
    for (id, deltas) in &output.textures_delta.set {
        for delta in deltas {
            painter.renderer.update_texture(device, queue, *id, delta);
        }
    }
    let target = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("target"),
        size: wgpu::Extent3d {
            width: SIZE_PX[0],
            height: SIZE_PX[1],
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: FORMAT,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::COPY_DST
            | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: u64::from(padded_bytes_per_row(SIZE_PX[0])) * u64::from(SIZE_PX[1]),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let jobs = ctx.tessellate(output.shapes, output.pixels_per_point);
    let screen = egui_wgpu::ScreenDescriptor {
        size_in_pixels: SIZE_PX,
        pixels_per_point: output.pixels_per_point,
    };
    let mut encoder = device.create_command_encoder(&Default::default());
    let changed = !output.textures_delta.set.is_empty();
    let extra = painter.paint(&mut encoder, &[&target], jobs, &screen, &[], changed);
    copy_to_buffer(&mut encoder, &target, &buffer);
    queue.submit(extra.into_iter().chain([encoder.finish()]));
    read_buffer(device, &buffer, SIZE_PX[0], SIZE_PX[1])
        .expect("reads back")
        .rgba
}

#[test]
fn a_partly_repainted_layer_paints_what_a_whole_repaint_paints() {
    let Some(gpu) = context_or_skip("a_partly_repainted_layer_paints_what_a_whole_repaint_paints")
    else {
        return;
    };
    let mut cached = EguiPainter::new(&gpu.device, &gpu.queue, FORMAT, true);
    let mut whole = EguiPainter::new(&gpu.device, &gpu.queue, FORMAT, false);
    let ctx = egui::Context::default();
    // The first frames make the font atlas (every digit the label will
    // need, at every sub-pixel offset it is drawn at) and settle egui's
    // layout; the layer is painted whole while egui's textures change.
    let full_px = u64::from(SIZE_PX[0] * SIZE_PX[1]);
    for k in 0..6 {
        let first = frame(&ctx, if k % 2 == 0 { 0.13 } else { 0.31 });
        let new_glyphs = !first.textures_delta.set.is_empty();
        paint(&gpu, &mut whole, &ctx, first.clone());
        paint(&gpu, &mut cached, &ctx, first);
        if new_glyphs {
            assert_eq!(cached.repainted_px, full_px, "new glyphs: painted whole");
        }
    }
    // The slider moves back and the digits change.
    let second = frame(&ctx, 0.13);
    assert!(
        second.textures_delta.set.is_empty(),
        "no new glyphs, so the layer is reused"
    );
    let a = paint(&gpu, &mut cached, &ctx, second.clone());
    let b = paint(&gpu, &mut whole, &ctx, second);
    assert!(
        cached.repainted_px > 0 && cached.repainted_px < full_px / 4,
        "{} of {full_px} pixels repainted",
        cached.repainted_px
    );
    let differing = a.chunks(4).zip(b.chunks(4)).filter(|(p, q)| p != q).count();
    assert_eq!(differing, 0, "pixels differ from egui's own painting");
}
