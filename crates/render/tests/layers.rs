//! The render crate knows nothing of the physics: it draws plain buffers.
//! This test keeps it so (ARCHITECTURE.md, "Layers are strict").

#[test]
fn render_does_not_depend_on_the_physics_or_the_app() {
    let manifest = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/Cargo.toml"))
        .expect("the render crate's manifest is readable");
    for crate_name in ["helixhair-physics", "helixhair-app"] {
        assert!(
            !manifest.contains(crate_name),
            "helixhair-render depends on {crate_name}"
        );
    }
}
