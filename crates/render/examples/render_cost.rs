//! Render cost per frame against strand count, points per strand, picture
//! size and shadow map size, on the adapter the environment selects
//! (`WGPU_BACKEND=vulkan` for lavapipe):
//!
//! ```sh
//! cargo run --release -p helixhair-render --example render_cost
//! ```
//!
//! The hair is synthetic: straight strands hanging from the default head's
//! scalp, so the numbers isolate the renderer from the simulation.

use std::time::Instant;

use glam::Vec3;
use helixhair_render::head_generate::default_head;
use helixhair_render::scalp_sampling::poisson_disk_on_scalp;
use helixhair_render::{
    GpuContext, HairStrands, HeadMesh, Light, OffscreenRenderer, OrbitCamera, RenderSettings,
    Scene, StrandBuffers,
};

/// `count` strands of `points` points, 30 cm long, hanging from the scalp.
fn hanging(head: &HeadMesh, count: usize, points: usize) -> HairStrands {
    let mut strands = StrandBuffers::default();
    for root in poisson_disk_on_scalp(head, count, 1) {
        let p = root.position_m;
        strands.push_strand((0..points).map(|k| {
            let s = k as f32 / (points - 1) as f32;
            p + root.normal * 0.01 * s.min(0.1) * 10.0 - Vec3::Y * 0.3 * s
        }));
    }
    HairStrands {
        strands,
        colours: vec![Vec3::new(0.1, 0.05, 0.02); count],
        root_width_m: 2e-4,
        tip_width_m: 7e-5,
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let head = default_head();
    println!("strands,points_per_strand,width_px,height_px,shadow_map_px,ms_per_frame");
    let cases = [
        (4000, 20, 1280, 720, 1024),
        (8000, 20, 1280, 720, 1024),
        (16000, 20, 1280, 720, 1024),
        (8000, 40, 1280, 720, 1024),
        (8000, 20, 320, 180, 1024),
        (8000, 20, 1280, 720, 256),
    ];
    for (count, points, width_px, height_px, shadow_map_px) in cases {
        let hair = hanging(&head, count, points);
        let settings = RenderSettings {
            shadow_map_px,
            ..RenderSettings::new(width_px, height_px)
        };
        let mut renderer = OffscreenRenderer::new(GpuContext::new_headless()?, settings)?;
        let scene = Scene {
            hair: &hair,
            head: &head,
            camera: OrbitCamera::default(),
            light: Light::default(),
        };
        renderer.render(&scene)?; // warm-up: shader compilation, allocation
        let frames = 3;
        let start = Instant::now();
        for _ in 0..frames {
            renderer.render(&scene)?;
        }
        let ms = 1e3 * start.elapsed().as_secs_f64() / f64::from(frames);
        println!("{count},{points},{width_px},{height_px},{shadow_map_px},{ms:.0}");
    }
    Ok(())
}
