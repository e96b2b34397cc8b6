//! The WGSL kernels parse and validate without a GPU, and every host struct
//! of `gpu::layout` has the size and member offsets naga computes for its
//! WGSL twin.
#![cfg(feature = "gpu")]

use std::mem::{offset_of, size_of};

use helixhair_physics::Method;
use helixhair_physics::gpu::dense_kernels::{
    DENSE_WORKGROUP, DENSE_WORKGROUP_BYTES, MAX_DENSE_ELEMENTS,
};
use helixhair_physics::gpu::engine::{BLOCK_SLOTS, KRYLOV_SLOTS, engine_source};
use helixhair_physics::gpu::kernels::kernel_source;
use helixhair_physics::gpu::layout::*;
use helixhair_physics::gpu::measure::{BlockRecordGpu, StrandMeasureGpu};
use wgpu::naga;

fn module(method: Method) -> naga::Module {
    let source = kernel_source(method).expect("a kernel exists");
    validated(&source, &format!("{method:?}"))
}

fn validated(source: &str, name: &str) -> naga::Module {
    let module = naga::front::wgsl::parse_str(source)
        .unwrap_or_else(|e| panic!("{}", e.emit_to_string(source)));
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::empty(),
    )
    .validate(&module)
    .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
    module
}

/// (size, [(member, offset)]) of WGSL struct `name`.
fn reflect(module: &naga::Module, name: &str) -> (u32, Vec<(String, u32)>) {
    let ty = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("no struct {name}"))
        .1;
    match &ty.inner {
        naga::TypeInner::Struct { members, span } => (
            *span,
            members
                .iter()
                .map(|m| (m.name.clone().unwrap_or_default(), m.offset))
                .collect(),
        ),
        other => panic!("{name} is {other:?}"),
    }
}

/// The value of WGSL `const NAME: u32`.
fn constant_u32(module: &naga::Module, name: &str) -> u32 {
    let (_, c) = module
        .constants
        .iter()
        .find(|(_, c)| c.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("no constant {name}"));
    match module.global_expressions[c.init] {
        naga::Expression::Literal(naga::Literal::U32(v)) => v,
        ref other => panic!("{name} is {other:?}"),
    }
}

macro_rules! check {
    ($module:expr, $wgsl:literal, $host:ty, [$($field:ident => $wgsl_field:literal),* $(,)?]) => {{
        let (size, members) = reflect($module, $wgsl);
        assert_eq!(size as usize, size_of::<$host>(), "size of {}", $wgsl);
        $(
            let offset = members
                .iter()
                .find(|(n, _)| n == $wgsl_field)
                .unwrap_or_else(|| panic!("{} has no {}", $wgsl, $wgsl_field))
                .1;
            assert_eq!(offset as usize, offset_of!($host, $field), "{}.{}", $wgsl, $wgsl_field);
        )*
    }};
}

#[test]
fn kernels_validate_and_host_structs_match_the_shaders() {
    let dense = module(Method::Dense);
    {
        let m = &dense;
        check!(m, "Params", ParamsGpu, [
            strand_count => "strand_count", elements => "elements", points => "points",
            h_secs => "h_secs", mass_per_length => "mass_per_length", air_drag => "air_drag",
            mass_scale => "mass_scale", gravity_m_per_s2 => "gravity_m_per_s2",
            air_velocity_m_per_s => "air_velocity_m_per_s", nodes => "nodes", weights => "weights",
            head_rotation => "head_rotation", head_angular_velocity => "head_angular_velocity",
            head_angular_acceleration => "head_angular_acceleration",
            head_velocity => "head_velocity", head_acceleration => "head_acceleration",
        ]);
        check!(m, "ElementConst", ElementConstGpu, [
            stiffness_length => "stiffness_length", natural_friction => "natural_friction",
        ]);
        check!(m, "RootPose", RootPoseGpu, [position_m => "position_m", head_from_root => "head_from_root"]);
        check!(m, "Frame", FrameGpu, [
            frame => "frame", angular_velocity => "angular_velocity",
            angular_acceleration => "angular_acceleration", point_m => "point_m",
            point_velocity => "point_velocity", point_acceleration => "point_acceleration",
        ]);
        check!(m, "Jacobians", JacobiansGpu, [a => "a", b => "b"]);
        check!(m, "Own", OwnGpu, [
            mass_block => "mass_block", inertia => "inertia", force => "force",
            moment => "moment", force_sum => "force_sum", torque_sum => "torque_sum",
        ]);
        check!(m, "Beyond", BeyondGpu, [
            inertia => "inertia", moment => "moment", force => "force", torque => "torque",
        ]);
    }
    check!(&dense, "DenseOwn", DenseOwnGpu, [own => "own", u => "u", v => "v"]);
    // The Dense kernel's workgroup and array sizes are the host's.
    assert_eq!(constant_u32(&dense, "DENSE_WORKGROUP"), DENSE_WORKGROUP);
    assert_eq!(
        constant_u32(&dense, "MAX_DENSE_ELEMENTS") as usize,
        MAX_DENSE_ELEMENTS
    );
    let stage_dense = dense
        .entry_points
        .iter()
        .find(|e| e.name == "stage_dense")
        .expect("stage_dense");
    assert_eq!(stage_dense.workgroup_size, [DENSE_WORKGROUP, 1, 1]);
    let workgroup_bytes: u32 = dense
        .global_variables
        .iter()
        .filter(|(_, g)| g.space == naga::AddressSpace::WorkGroup)
        .map(|(_, g)| dense.types[g.ty].inner.size(dense.to_ctx()))
        .sum();
    assert_eq!(workgroup_bytes as usize, DENSE_WORKGROUP_BYTES);
    // Round trip: bytes written by the host read back as the same values.
    let params = ParamsGpu {
        strand_count: 3,
        h_secs: 0.25,
        head_rotation: [
            [1.0, 2.0, 3.0, 0.0],
            [4.0, 5.0, 6.0, 0.0],
            [7.0, 8.0, 9.0, 0.0],
        ],
        ..bytemuck::Zeroable::zeroed()
    };
    let bytes = bytemuck::bytes_of(&params);
    let back: ParamsGpu = bytemuck::pod_read_unaligned(bytes);
    assert_eq!(back, params);
}

#[test]
fn the_engine_kernel_validates_and_its_host_structs_match() {
    let engine = validated(&engine_source(), "engine");
    check!(&engine, "Params", EngineParamsGpu, [
        strand_count => "strand_count", points => "points", iterations => "iterations",
        has_collider => "has_collider", h_secs => "h_secs", gmres_tolerance => "gmres_tolerance",
        skin_m => "skin_m", implicit_stiffness_ratio => "implicit_stiffness_ratio",
        max_acceleration_m_per_s2 => "max_acceleration_m_per_s2", field_cell_m => "field_cell_m",
        method => "method", slots => "slots",
        field_dims => "field_dims", field_origin_m => "field_origin_m",
        gravity_m_per_s2 => "gravity_m_per_s2", air_velocity_m_per_s => "air_velocity_m_per_s",
        nodes => "nodes", weights => "weights", head_rotation => "head_rotation",
        head_position_m => "head_position_m", head_angular_velocity => "head_angular_velocity",
        head_angular_acceleration => "head_angular_acceleration",
        head_velocity => "head_velocity", head_acceleration => "head_acceleration",
        block_h_secs => "block_h_secs",
    ]);
    check!(&engine, "Strand", StrandGpu, [
        first => "first", elements => "elements", index => "index",
        mass_per_length => "mass_per_length",
        air_drag => "air_drag", position_m => "position_m", head_from_root => "head_from_root",
    ]);
    check!(&engine, "ElementConst", ElementConstGpu, [
        stiffness_length => "stiffness_length", natural_friction => "natural_friction",
    ]);
    check!(&engine, "ElementData", ElementDataGpu, [
        a => "a", b => "b", own_mass_block => "own_mass_block", inertia => "inertia",
        u => "u", v => "v", contact => "contact", own_force => "own_force", moment => "moment",
        force_sum => "force_sum", torque_sum => "torque_sum", span => "span",
    ]);
    check!(&engine, "Elimination", EliminationGpu, [
        w_top => "w_top", w_bottom => "w_bottom", s_inv => "s_inv", rhs => "rhs",
    ]);
    check!(&engine, "StrandMeasure", StrandMeasureGpu, [
        energies => "energies", sums => "sums", momentum => "momentum", angular => "angular",
        force => "force", torque => "torque", first_moment => "first_moment",
    ]);
    check!(&engine, "BlockRecord", BlockRecordGpu, [
        u => "u", beta => "beta", span => "span", first => "first", second => "second",
    ]);
    assert_eq!(constant_u32(&engine, "KRYLOV_SLOTS") as usize, KRYLOV_SLOTS);
    assert_eq!(constant_u32(&engine, "BLOCK_SLOTS") as usize, BLOCK_SLOTS);
    assert_eq!(
        constant_u32(&engine, "RECORD") + constant_u32(&engine, "RECORD_SLOTS"),
        constant_u32(&engine, "BLOCK_SLOTS"),
        "Block-diagonal's record ends the slots"
    );
    assert_eq!(
        constant_u32(&engine, "MAX_GMRES") as usize,
        helixhair_physics::gmres::MAX_GMRES
    );
}
