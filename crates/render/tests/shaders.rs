//! Every WGSL shader parses and validates with naga (the version wgpu
//! uses), without a GPU, and the uniform structs the shaders declare have
//! the sizes of their Rust twins in `gpu_data`.

use helixhair_render::gpu::device_hair::{RibbonParamsGpu, RibbonStrandGpu};
use helixhair_render::gpu::gpu_data::{Lighting, View};
use helixhair_render::gpu::shaders::{ALL, ALONE, RIBBONS, composed};

fn validate(name: &str, source: &str) -> naga::Module {
    let module = naga::front::wgsl::parse_str(source)
        .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&module)
    .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
    module
}

/// The byte size naga gives the struct named `name`.
fn struct_size(module: &naga::Module, name: &str) -> u32 {
    module
        .types
        .iter()
        .find(|(_, ty)| ty.name.as_deref() == Some(name))
        .map(|(_, ty)| ty.inner.size(module.to_ctx()))
        .unwrap_or_else(|| panic!("no struct {name}"))
}

#[test]
fn every_shader_validates() {
    for file in ALL {
        validate(file.name, &composed(&file));
    }
    for file in ALONE {
        validate(file.name, file.source);
    }
}

#[test]
fn the_ribbon_pass_structs_match_their_rust_twins() {
    let module = validate(RIBBONS.name, RIBBONS.source);
    assert_eq!(
        struct_size(&module, "RibbonParams") as usize,
        size_of::<RibbonParamsGpu>()
    );
    assert_eq!(
        struct_size(&module, "RibbonStrand") as usize,
        size_of::<RibbonStrandGpu>()
    );
}

#[test]
fn every_wgsl_file_in_the_shaders_folder_is_compiled() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shaders");
    let mut on_disk: Vec<String> = std::fs::read_dir(dir)
        .expect("shaders/ is readable")
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.ends_with(".wgsl") && n != "common.wgsl")
        .collect();
    on_disk.sort();
    let mut compiled: Vec<&str> = ALL.iter().chain(&ALONE).map(|f| f.name).collect();
    compiled.sort();
    assert_eq!(on_disk, compiled);
}

#[test]
fn uniform_structs_match_their_rust_twins() {
    let module = validate("hair.wgsl", &composed(&ALL[0]));
    assert_eq!(struct_size(&module, "View") as usize, size_of::<View>());
    assert_eq!(
        struct_size(&module, "Lighting") as usize,
        size_of::<Lighting>()
    );
}
