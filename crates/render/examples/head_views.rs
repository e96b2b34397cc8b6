//! Renders the default head (no hair) from the front, the side and three
//! quarters, to check its shape and its scalp:
//!
//! ```sh
//! cargo run --release -p helixhair-render --example head_views [OUT_DIR]
//! ```

use std::path::PathBuf;

use helixhair_render::head_generate::default_head;
use helixhair_render::{
    GpuContext, HairStrands, Light, OffscreenRenderer, OrbitCamera, RenderSettings, Scene,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| ".".into()));
    let head = default_head();
    let hair = HairStrands::default();
    let mut renderer =
        OffscreenRenderer::new(GpuContext::new_headless()?, RenderSettings::new(480, 480))?;
    for (name, yaw_deg) in [("front", 0.0f32), ("side", 90.0), ("three-quarter", 35.0)] {
        let camera = OrbitCamera {
            yaw_rad: yaw_deg.to_radians(),
            ..OrbitCamera::default()
        };
        let image = renderer.render(&Scene {
            hair: &hair,
            head: &head,
            camera,
            light: Light::default(),
        })?;
        let path = dir.join(format!("head-{name}.png"));
        image::save_buffer(
            &path,
            &image.rgba,
            image.width_px,
            image.height_px,
            image::ExtendedColorType::Rgba8,
        )?;
        println!("wrote {}", path.display());
    }
    Ok(())
}
