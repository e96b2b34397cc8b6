//! Fuzzes the head loader: any text, no panic. A head it accepts is one the
//! renderer can draw: indices in range, a normal per position, finite
//! positions, scalp triangles that exist. A head without a `scalp` group is
//! accepted (styles that list their roots need none; the caller that grows
//! hair on the scalp refuses it with its own message).

#![no_main]

use std::path::Path;

use helixhair_render::obj::parse_head_obj;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let Ok(head) = parse_head_obj(&text, Path::new("fuzz.obj")) else {
        return;
    };
    let mesh = &head.mesh;
    let vertices = mesh.positions.len();
    assert_eq!(mesh.normals.len(), vertices, "a normal per position");
    assert_eq!(mesh.indices.len() % 3, 0, "whole triangles");
    assert!(
        mesh.indices.iter().all(|&i| (i as usize) < vertices),
        "index out of range"
    );
    assert!(
        mesh.positions.iter().all(|p| p.is_finite()),
        "position not finite"
    );
    let triangles = mesh.triangle_count();
    assert!(
        head.scalp_triangles
            .iter()
            .all(|&t| (t as usize) < triangles),
        "scalp triangle out of range"
    );
});
