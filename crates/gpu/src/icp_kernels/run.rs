//! One GPU iteration: the parameters go up, the search and the reduction kernels run (in one
//! submission, or one per stage to time them), and the totals come back.

use super::buffers::{map_read, ms, read_back_via};
use super::{GpuIcp, GpuKernel, StageTimes, K, WG};
use crate::error::{GpuError, Result};
use crate::grid::NONE;
use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec3};
use std::time::Instant;

/// The kernels' uniform parameters (see the WGSL `Params`).
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
pub(super) struct Params {
    transform: [f32; 16],
    origin: [f32; 4],
    reference: [f32; 4],
    dims: [u32; 4],
    counts: [u32; 4],
    kernel: [f32; 4],
    sensor: [f32; 4],
}

impl GpuIcp {
    pub(super) fn run(
        &mut self,
        transform: Mat4,
        max_distance_m: f32,
        reference: Vec3,
        mode: u32,
        kernel: GpuKernel,
    ) -> Result<(Vec<f32>, StageTimes)> {
        if !(max_distance_m.is_finite() && max_distance_m > 0.0) {
            return Err(GpuError::Invalid(format!(
                "max_distance_m = {max_distance_m} must be positive"
            )));
        }
        let (Some(s), Some(t)) = (&self.source, &self.target) else {
            return Err(GpuError::Invalid(
                "upload a target and a source first".into(),
            ));
        };
        if let GpuKernel::Huber(k) | GpuKernel::Cauchy(k) = kernel {
            if !(k.is_finite() && k > 0.0) {
                return Err(GpuError::Invalid(format!(
                    "robust kernel width {k} must be positive"
                )));
            }
        }
        let groups = s.len.div_ceil(WG);
        let (kind, k) = match kernel {
            GpuKernel::None => (0, 1.0),
            GpuKernel::Huber(k) => (1, k),
            GpuKernel::Cauchy(k) => (2, k),
        };
        let g = &t.grid;
        let p = Params {
            transform: transform.to_cols_array(),
            origin: [g.origin.x, g.origin.y, g.origin.z, 1.0 / g.bucket_size_m],
            reference: [
                reference.x,
                reference.y,
                reference.z,
                max_distance_m * max_distance_m,
            ],
            dims: [g.dims[0], g.dims[1], g.dims[2], g.keys.len() as u32 - 1],
            counts: [s.len, mode, kind, groups],
            kernel: [k, 0.0, g.sub as f32, 0.0],
            sensor: match self.sensor {
                Some(v) => [v.x, v.y, v.z, 1.0],
                None => [0.0; 4],
            },
        };
        let mut times = StageTimes::default();
        let t0 = Instant::now();
        if self.bind.is_none() {
            let bind = self
                .ctx
                .scoped("binding the buffers", || Ok(self.bind_group()))?;
            self.bind = Some(bind);
        }
        let Some(bind) = &self.bind else {
            return Err(GpuError::Invalid("no bind group".into()));
        };
        let ctx = &self.ctx;
        let stale = self.hints_stale;
        let out = ctx.scoped("running the ICP kernels", || {
            if stale {
                // No hints yet: every search starts from the gate.
                let none = vec![NONE; s.len as usize];
                ctx.queue
                    .write_buffer(&s.corr, 0, bytemuck::cast_slice(&none));
            }
            ctx.queue
                .write_buffer(&self.params, 0, bytemuck::bytes_of(&p));
            times.upload_ms = ms(t0);
            let bytes = (K * 4) as u64;
            if !self.stage_timing {
                // One submission and one wait per iteration: both kernels and the copy back.
                let t1 = Instant::now();
                let mut enc = self.encode(bind, &[(&self.search, groups), (&self.sum, 1)]);
                enc.copy_buffer_to_buffer(&self.totals, 0, &self.readback, 0, bytes);
                ctx.queue.submit([enc.finish()]);
                let v: Vec<f32> = map_read(ctx, &self.readback, bytes)?;
                times.search_ms = ms(t1);
                return Ok((v, times));
            }
            let t1 = Instant::now();
            self.dispatch(bind, &self.search, groups)?;
            times.search_ms = ms(t1);
            let t2 = Instant::now();
            self.dispatch(bind, &self.sum, 1)?;
            times.reduce_ms = ms(t2);
            let t3 = Instant::now();
            let v: Vec<f32> = read_back_via(ctx, &self.totals, &self.readback, bytes)?;
            times.download_ms = ms(t3);
            Ok((v, times))
        });
        if out.is_ok() {
            self.hints_stale = false;
        }
        out
    }

    pub(super) fn dispatch(
        &self,
        bind: &wgpu::BindGroup,
        pipeline: &wgpu::ComputePipeline,
        groups: u32,
    ) -> Result<()> {
        let enc = self.encode(bind, &[(pipeline, groups)]);
        self.ctx.queue.submit([enc.finish()]);
        self.ctx
            .device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| GpuError::Internal {
                during: "waiting for the ICP kernels".into(),
                msg: e.to_string(),
            })?;
        Ok(())
    }

    /// A command encoder with one compute pass running `stages` (pipeline, workgroups) in order.
    pub(super) fn encode(
        &self,
        bind: &wgpu::BindGroup,
        stages: &[(&wgpu::ComputePipeline, u32)],
    ) -> wgpu::CommandEncoder {
        let mut enc = self.ctx.device.create_command_encoder(&Default::default());
        {
            let mut pass = enc.begin_compute_pass(&Default::default());
            pass.set_bind_group(0, bind, &[]);
            for (pipeline, groups) in stages {
                pass.set_pipeline(pipeline);
                pass.dispatch_workgroups(*groups, 1, 1);
            }
        }
        enc
    }

    pub(super) fn bind_group(&self) -> wgpu::BindGroup {
        let (s, t) = (self.source.as_ref(), self.target.as_ref());
        let bufs: Vec<&wgpu::Buffer> = match (s, t) {
            (Some(s), Some(t)) => vec![
                &self.params,
                &s.source,
                &t.target,
                &t.normals,
                &t.keys,
                &t.vals,
                &t.starts,
                &s.corr,
                &s.dist2,
                &s.partials,
                &self.totals,
            ],
            _ => Vec::new(),
        };
        let entries: Vec<wgpu::BindGroupEntry> = bufs
            .iter()
            .enumerate()
            .map(|(i, b)| wgpu::BindGroupEntry {
                binding: i as u32,
                resource: b.as_entire_binding(),
            })
            .collect();
        self.ctx
            .device
            .create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("icp"),
                layout: &self.layout,
                entries: &entries,
            })
    }
}
