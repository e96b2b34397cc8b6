//! Hair drawn from strand points already on the device: a compute pass
//! (`shaders/ribbons.wgsl`, `stage_ribbons`) builds the ribbon vertices
//! there, so points that another part of the program wrote on the same
//! device (the physics' curves) are drawn without coming back to the CPU.
//!
//! # The contract
//!
//! [`DeviceStrands::points`] is a storage buffer of `vec4<f32>`, one per
//! point: x, y, z in metres in **head** coordinates (w unused), strand s's
//! points at `ranges[s]`, root first. This crate knows nothing of where
//! they come from. The pass keeps them out of the head as the CPU's drawn
//! hair does ([`HeadShell::drape`], in head coordinates), poses them into
//! the world by `world_from_head`, and writes what
//! [`crate::ribbons::ribbon_mesh`] writes: every point twice, with its
//! tangent, arc-length fraction, the strand's colour and random number.
//! That CPU path, on the same points, is the pass's reference
//! (`tests/device_hair.rs`).
//!
//! Where the strands ask for it ([`DeviceStrands::shaping`]), they are
//! first shaped by their guides on the device ([`super::device_shape`]:
//! clumped, curled, following) and the ribbons read the shaped points.
//!
//! The strand table, index buffer, vertex buffer and shell are made once
//! per layout (ranges, colours, shell) and kept; each frame only the pose
//! is written and the pass dispatched.

use std::ops::Range;

use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec3};
use helixhair_gpu::{bind_buffers, dispatch_dims, upload_buffer};

use super::device_shape::{DeviceShaper, DeviceShaping};
use super::frame_data::IndexedGeometry;
use crate::head_shell::HeadShell;
use crate::ribbons::{ribbon_indices, strand_colour, strand_random};

use super::shaders::RIBBONS;

/// Strands whose points are on the device (module docs for the layout).
#[derive(Clone, Copy, Debug)]
pub struct DeviceStrands<'a> {
    /// The points, `vec4<f32>` each, head coordinates, metres.
    pub points: &'a wgpu::Buffer,
    /// Strand s's points in `points`, in points.
    pub ranges: &'a [Range<usize>],
    /// Linear RGB colour per strand.
    pub colours: &'a [Vec3],
    /// The head's outer shell the hair is kept out of, with the gap kept
    /// from it in metres; `None`: drawn as they are.
    pub shell: Option<(&'a HeadShell, f32)>,
    /// World from head coordinates (the head's pose this frame).
    pub world_from_head: Mat4,
    /// The longest strand, metres: how far from the head the hair can
    /// reach, for the light's view (the points are not read back).
    pub reach_m: f32,
    /// How the strands are shaped by their guides first
    /// ([`super::device_shape`]); `None`: drawn as their points are.
    pub shaping: Option<DeviceShaping<'a>>,
}

/// WGSL `RibbonParams`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct RibbonParamsGpu {
    /// World from head, column-major.
    pub world_from_head: [[f32; 4]; 4],
    /// Shell centre (head coordinates, m); w: the gap, m.
    pub shell_centre_m: [f32; 4],
    /// Number of strands.
    pub strand_count: u32,
    /// 1 where the points are draped over the shell.
    pub has_shell: u32,
    /// The shell's latitude cells.
    pub shell_rows: u32,
    /// The shell's longitude cells.
    pub shell_columns: u32,
}

/// WGSL `RibbonStrand`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct RibbonStrandGpu {
    /// The strand's root in the points buffer.
    pub first_point: u32,
    /// Its points.
    pub point_count: u32,
    /// Its first vertex in the vertex buffer.
    pub first_vertex: u32,
    /// Its random number in [0, 1) ([`strand_random`]).
    pub seed: f32,
    /// Its colour (linear RGB), w unused.
    pub colour: [f32; 4],
}

const _: () = assert!(size_of::<RibbonParamsGpu>() == 96);
const _: () = assert!(size_of::<RibbonStrandGpu>() == 32);

/// What the layout decides: the strands, colours and shell it was made
/// for.
#[derive(Debug)]
struct LayoutKey {
    ranges: Vec<Range<usize>>,
    colours: Vec<Vec3>,
    shell: Option<(HeadShell, f32)>,
    /// The points buffer the ribbons read (a new one needs a new bind
    /// group).
    points: wgpu::Buffer,
}

impl LayoutKey {
    /// The key of `strands`' layout, its ribbons read from `points`.
    fn of(strands: &DeviceStrands<'_>, points: &wgpu::Buffer) -> Self {
        Self {
            ranges: strands.ranges.to_vec(),
            colours: strands.colours.to_vec(),
            shell: strands.shell.map(|(s, gap)| (s.clone(), gap)),
            points: points.clone(),
        }
    }

    /// Whether `strands` read from `points` has this layout, compared in
    /// place (every frame, without copying the strands' tables).
    fn matches(&self, strands: &DeviceStrands<'_>, points: &wgpu::Buffer) -> bool {
        let shell = match (&self.shell, strands.shell) {
            (Some((a, gap_a)), Some((b, gap_b))) => a == b && *gap_a == gap_b,
            (None, None) => true,
            _ => false,
        };
        self.ranges == strands.ranges
            && self.colours == strands.colours
            && shell
            && self.points == *points
    }
}

/// The pass and the buffers of one layout (module docs).
#[derive(Debug)]
pub struct DeviceRibbons {
    pipeline: wgpu::ComputePipeline,
    layout: Option<(LayoutKey, Built)>,
    /// The shaping passes, made on the first shaped strands.
    shaper: Option<DeviceShaper>,
}

#[derive(Debug)]
struct Built {
    params: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    geometry: IndexedGeometry,
    vertices: wgpu::Buffer,
    strand_count: u32,
    shell_centre_m: [f32; 4],
    has_shell: u32,
}

impl DeviceRibbons {
    /// The pass's pipeline on `device`.
    pub fn new(device: &wgpu::Device) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(RIBBONS.name),
            source: wgpu::ShaderSource::Wgsl(RIBBONS.source.into()),
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("stage_ribbons"),
            layout: None,
            module: &module,
            entry_point: Some("stage_ribbons"),
            compilation_options: Default::default(),
            cache: None,
        });
        Self {
            pipeline,
            layout: None,
            shaper: None,
        }
    }

    /// Records the passes that shape `strands` (where they ask for it) and
    /// build their ribbons into `encoder`, and returns the geometry the
    /// hair passes draw (`None`: nothing to draw, or a shaping the device
    /// cannot hold, which [`super::device_shape::shape_table`] tells
    /// beforehand).
    pub fn encode(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        strands: &DeviceStrands<'_>,
        encoder: &mut wgpu::CommandEncoder,
    ) -> Option<&IndexedGeometry> {
        let points = match &strands.shaping {
            Some(shaping) => self
                .shaper
                .get_or_insert_with(|| DeviceShaper::new(device))
                .encode(device, queue, strands.points, shaping, encoder)
                .ok()?
                .clone(),
            None => strands.points.clone(),
        };
        if self
            .layout
            .as_ref()
            .is_none_or(|(k, _)| !k.matches(strands, &points))
        {
            let built = build(device, queue, &self.pipeline, strands, &points)?;
            self.layout = Some((LayoutKey::of(strands, &points), built));
        }
        let (_, built) = self.layout.as_ref()?;
        let params = RibbonParamsGpu {
            world_from_head: strands.world_from_head.to_cols_array_2d(),
            shell_centre_m: built.shell_centre_m,
            strand_count: built.strand_count,
            has_shell: built.has_shell,
            shell_rows: HeadShell::ROWS as u32,
            shell_columns: HeadShell::COLUMNS as u32,
        };
        queue.write_buffer(&built.params, 0, bytemuck::bytes_of(&params));
        let (x, y) = dispatch_dims(&device.limits(), built.strand_count.div_ceil(64));
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("stage_ribbons"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &built.bind_group, &[]);
        pass.dispatch_workgroups(x, y, 1);
        drop(pass);
        Some(&built.geometry)
    }

    /// The vertex buffer the last [`Self::encode`] wrote (48-byte
    /// `StrandVertex`es), for tests and tools.
    pub fn vertices(&self) -> Option<&wgpu::Buffer> {
        self.layout.as_ref().map(|(_, b)| &b.vertices)
    }
}

/// The strand table, index buffer, vertex buffer, shell and bind group of
/// `strands`' layout; `None` when no strand has two points.
fn build(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    pipeline: &wgpu::ComputePipeline,
    strands: &DeviceStrands<'_>,
    points: &wgpu::Buffer,
) -> Option<Built> {
    let mut table = Vec::with_capacity(strands.ranges.len());
    let mut indices = Vec::new();
    let mut vertex_count = 0u32;
    for (i, range) in strands.ranges.iter().enumerate() {
        let count = range.len() as u32;
        let colour = strand_colour(strands.colours, i);
        table.push(RibbonStrandGpu {
            first_point: range.start as u32,
            point_count: count,
            first_vertex: vertex_count,
            seed: strand_random(i as u32),
            colour: [colour.x, colour.y, colour.z, 0.0],
        });
        if count < 2 {
            continue;
        }
        ribbon_indices(vertex_count, count, &mut indices);
        vertex_count += 2 * count;
    }
    if indices.is_empty() {
        return None;
    }
    let storage = wgpu::BufferUsages::STORAGE;
    let table_buffer = upload_buffer(
        device,
        queue,
        "ribbon strands",
        bytemuck::cast_slice(&table),
        storage,
    );
    let (shell_radii, shell_centre_m, has_shell) = match strands.shell {
        Some((shell, gap_m)) => {
            let c = shell.centre_m();
            (shell.radii_m().to_vec(), [c.x, c.y, c.z, gap_m], 1)
        }
        None => (vec![0.0f32], [0.0; 4], 0),
    };
    let shell_buffer = upload_buffer(
        device,
        queue,
        "head shell",
        bytemuck::cast_slice(&shell_radii),
        storage,
    );
    let vertices = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("device ribbons"),
        size: u64::from(vertex_count) * 48,
        usage: wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::VERTEX
            | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let index_buffer = upload_buffer(
        device,
        queue,
        "device ribbon indices",
        bytemuck::cast_slice(&indices),
        wgpu::BufferUsages::INDEX,
    );
    let params = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("ribbon params"),
        size: size_of::<RibbonParamsGpu>() as u64,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let buffers = [&params, points, &table_buffer, &shell_buffer, &vertices];
    let bind_group = bind_buffers(
        device,
        "stage_ribbons",
        &pipeline.get_bind_group_layout(0),
        &buffers,
    );
    let geometry = IndexedGeometry::from_buffers(vertices.clone(), index_buffer, indices.len());
    Some(Built {
        params,
        bind_group,
        geometry,
        vertices,
        strand_count: table.len() as u32,
        shell_centre_m,
        has_shell,
    })
}
