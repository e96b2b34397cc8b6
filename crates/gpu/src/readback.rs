//! Reading what the GPU wrote: a buffer copied into a staging buffer,
//! mapped, and waited for. The physics reads its state back with it, the
//! renderer its pictures, tests what a pass wrote. Beside it, the two
//! plain helpers every compute pass of both needs: a bind group of whole
//! buffers, and workgroup counts split over two dimensions.

/// Maps `slice` (of a `MAP_READ` buffer) for reading and waits until it is
/// mapped or mapping failed: what wgpu said, in words.
pub fn map_and_wait(device: &wgpu::Device, slice: wgpu::BufferSlice<'_>) -> Result<(), String> {
    let (sender, receiver) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |result| {
        // The receiver waits below; a send can only fail if it is gone.
        let _ = sender.send(result);
    });
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| e.to_string())?;
    receiver
        .recv()
        .map_err(|e| e.to_string())?
        .map_err(|e| e.to_string())
}

/// Copies `buffer` (made with `COPY_SRC`) into a staging buffer, waits, and
/// returns its bytes; what wgpu said, in words, where that failed.
pub fn read_bytes(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    buffer: &wgpu::Buffer,
) -> Result<Vec<u8>, String> {
    let staging = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: buffer.size(),
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, buffer.size());
    queue.submit([encoder.finish()]);
    let slice = staging.slice(..);
    map_and_wait(device, slice)?;
    let bytes = slice
        .get_mapped_range()
        .map_err(|e| e.to_string())?
        .to_vec();
    staging.unmap();
    Ok(bytes)
}

/// Workgroup counts (x, y) for `groups` workgroups (at least one), split
/// over y past `limits`' per-dimension count; a kernel reads them back as
/// one index, `id.x + id.y * num_workgroups.x * workgroup_size`.
pub fn dispatch_dims(limits: &wgpu::Limits, groups: u32) -> (u32, u32) {
    let groups = groups.max(1);
    let x = groups.min(limits.max_compute_workgroups_per_dimension);
    (x, groups.div_ceil(x))
}

/// A bind group of `buffers`, each bound whole at its index in the slice,
/// on `layout`.
pub fn bind_buffers(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    buffers: &[&wgpu::Buffer],
) -> wgpu::BindGroup {
    let entries: Vec<wgpu::BindGroupEntry> = buffers
        .iter()
        .enumerate()
        .map(|(i, b)| wgpu::BindGroupEntry {
            binding: i as u32,
            resource: b.as_entire_binding(),
        })
        .collect();
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &entries,
    })
}
