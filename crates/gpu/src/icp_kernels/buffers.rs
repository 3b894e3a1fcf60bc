//! Buffer helpers: creation, uploads that reuse a large enough buffer, and read-backs.

use crate::context::GpuContext;
use crate::error::{GpuError, Result};
use bytemuck::Pod;
use std::time::Instant;

/// Milliseconds since `t`.
pub(super) fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

/// A buffer of `size` bytes, at least 16.
pub(super) fn buffer(
    d: &wgpu::Device,
    label: &str,
    size: u64,
    usage: wgpu::BufferUsages,
) -> wgpu::Buffer {
    d.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size.max(16),
        usage,
        mapped_at_creation: false,
    })
}

/// Writes `bytes` into `old` if it is large enough, else into a new buffer with 25% headroom;
/// returns the buffer and whether it is new.
pub(super) fn upload(
    ctx: &GpuContext,
    old: Option<wgpu::Buffer>,
    label: &str,
    bytes: &[u8],
) -> (wgpu::Buffer, bool) {
    let need = (bytes.len() as u64).max(16);
    let (b, fresh) = match old {
        Some(b) if b.size() >= need => (b, false),
        _ => {
            let size = (need + need / 4).next_multiple_of(16);
            let usage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST;
            (buffer(&ctx.device, label, size, usage), true)
        }
    };
    ctx.queue.write_buffer(&b, 0, bytes);
    (b, fresh)
}

/// Copies `bytes` of `src` out through a fresh staging buffer.
pub(super) fn read_back<T: Pod>(
    ctx: &GpuContext,
    src: &wgpu::Buffer,
    bytes: u64,
) -> Result<Vec<T>> {
    let staging = buffer(
        &ctx.device,
        "staging",
        bytes,
        wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
    );
    read_back_via(ctx, src, &staging, bytes)
}

/// Copies `bytes` of `src` out through `staging` (a `MAP_READ` buffer).
pub(super) fn read_back_via<T: Pod>(
    ctx: &GpuContext,
    src: &wgpu::Buffer,
    staging: &wgpu::Buffer,
    bytes: u64,
) -> Result<Vec<T>> {
    let mut enc = ctx.device.create_command_encoder(&Default::default());
    enc.copy_buffer_to_buffer(src, 0, staging, 0, bytes);
    ctx.queue.submit([enc.finish()]);
    map_read(ctx, staging, bytes)
}

/// Maps `staging` (after the submission that fills it), waits and copies it out.
pub(super) fn map_read<T: Pod>(
    ctx: &GpuContext,
    staging: &wgpu::Buffer,
    bytes: u64,
) -> Result<Vec<T>> {
    let slice = staging.slice(0..bytes);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    ctx.device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| GpuError::Readback(e.to_string()))?;
    rx.recv()
        .map_err(|e| GpuError::Readback(e.to_string()))?
        .map_err(|e| GpuError::Readback(e.to_string()))?;
    let view = slice
        .get_mapped_range()
        .map_err(|e| GpuError::Readback(e.to_string()))?;
    let out = bytemuck::cast_slice::<u8, T>(&view).to_vec();
    drop(view);
    staging.unmap();
    Ok(out)
}
