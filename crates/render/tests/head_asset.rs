//! The committed `assets/head.obj` is what the default head generator
//! writes, and loads back as the same head.

use std::path::Path;

use helixhair_render::head_generate::default_head;
use helixhair_render::obj::load_head_obj;

#[test]
fn the_committed_head_matches_the_generator() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/head.obj");
    let loaded = load_head_obj(&path).unwrap_or_else(|e| panic!("{e}"));
    let generated = default_head();
    assert_eq!(
        loaded.mesh.triangle_count(),
        generated.mesh.triangle_count(),
        "regenerate with `cargo run -p helixhair-render --example make_head`"
    );
    assert_eq!(
        loaded.scalp_triangles.len(),
        generated.scalp_triangles.len()
    );
    // Written with 6 decimals: a micrometre.
    let area = (loaded.scalp_area_m2() - generated.scalp_area_m2()).abs();
    assert!(area < 1e-6, "scalp area differs by {area} m²");
    let (lo, hi) = loaded.mesh.bounds_m();
    let (glo, ghi) = generated.mesh.bounds_m();
    assert!((lo - glo).abs().max_element() < 1e-5 && (hi - ghi).abs().max_element() < 1e-5);
}
