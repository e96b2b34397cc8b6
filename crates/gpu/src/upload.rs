//! Buffers made from bytes, without wgpu's `create_buffer_init`.
//!
//! `wgpu::util::DeviceExt::create_buffer_init` maps the new buffer at
//! creation and *panics* when the mapping fails, which it does on a lost
//! device (found by `tests/lost_device.rs`). [`upload_buffer`] creates an
//! unmapped buffer and queues the bytes instead: on a lost device both calls
//! only report an error to the device's handler ([`crate::GpuContext`]
//! records it for [`crate::GpuContext::check`]), and nothing panics.

/// wgpu copies buffers in multiples of this many bytes.
const COPY_ALIGNMENT_BYTES: usize = wgpu::COPY_BUFFER_ALIGNMENT as usize;

/// A buffer holding `bytes` (zero-padded to a multiple of four bytes),
/// usable as `usage`; the copy is queued on `queue` and done before any
/// later submission reads it.
pub fn upload_buffer(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    bytes: &[u8],
    usage: wgpu::BufferUsages,
) -> wgpu::Buffer {
    let padded_len = bytes.len().div_ceil(COPY_ALIGNMENT_BYTES) * COPY_ALIGNMENT_BYTES;
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: padded_len.max(COPY_ALIGNMENT_BYTES) as u64,
        usage: usage | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    if padded_len == bytes.len() {
        queue.write_buffer(&buffer, 0, bytes);
    } else {
        let mut padded = bytes.to_vec();
        padded.resize(padded_len, 0);
        queue.write_buffer(&buffer, 0, &padded);
    }
    buffer
}
