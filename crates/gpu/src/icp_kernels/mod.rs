//! Dispatch of the WGSL kernels: the model cloud's grid and the data cloud stay on the GPU across
//! iterations (and across scans for the model), buffers are reused, and per iteration only the
//! 4x4 transform goes up and a few dozen floats come back.

mod buffers;
mod pipelines;
mod run;
mod sums;
#[cfg(test)]
mod tests;

pub use sums::{GpuKernel, P2pSums, PlaneSystem, StageTimes};

use crate::context::GpuContext;
use crate::error::{GpuError, Result};
use crate::grid::{HostGrid, NONE};
use buffers::{buffer, read_back, upload};
use glam::{Mat4, Vec3};

/// Invocations per workgroup of the search kernel.
const WG: u32 = 128;
/// Floats in one workgroup's partial sums (and in the totals read back).
const K: usize = 30;

/// The model cloud's buffers: reused (overwritten in place) by the next `set_target` while
/// they are large enough, so a growing map re-allocates only now and then.
struct TargetBuffers {
    grid: HostGrid,
    target: wgpu::Buffer,
    normals: wgpu::Buffer,
    keys: wgpu::Buffer,
    vals: wgpu::Buffer,
    starts: wgpu::Buffer,
    has_normals: bool,
}

struct SourceBuffers {
    len: u32,
    capacity: u32,
    source: wgpu::Buffer,
    corr: wgpu::Buffer,
    dist2: wgpu::Buffer,
    partials: wgpu::Buffer,
}

/// GPU ICP: holds the device, the pipelines and the clouds' buffers.
pub struct GpuIcp {
    ctx: GpuContext,
    layout: wgpu::BindGroupLayout,
    search: wgpu::ComputePipeline,
    sum: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    totals: wgpu::Buffer,
    readback: wgpu::Buffer,
    target: Option<TargetBuffers>,
    source: Option<SourceBuffers>,
    bind: Option<wgpu::BindGroup>,
    /// Separate submissions (and waits) per stage, to time them; else one per iteration.
    stage_timing: bool,
    /// The source's sensor (source frame) for the back-face test, if on.
    sensor: Option<Vec3>,
    /// The per-point correspondences (the next search's hints) belong to other clouds.
    hints_stale: bool,
}

impl GpuIcp {
    /// Compiles the kernels on `ctx`.
    pub fn new(ctx: GpuContext) -> Result<GpuIcp> {
        let parts = ctx.scoped("compiling the ICP kernels", || Ok(pipelines::compile(&ctx)))?;
        let (layout, search, sum, params, totals, readback) = parts;
        Ok(GpuIcp {
            ctx,
            layout,
            search,
            sum,
            params,
            totals,
            readback,
            target: None,
            source: None,
            bind: None,
            sensor: None,
            hints_stale: true,
            stage_timing: false,
        })
    }

    /// The context in use.
    pub fn context(&self) -> &GpuContext {
        &self.ctx
    }

    /// Builds the model cloud's bucket grid (CPU counting sort) and uploads it with optional
    /// normals. The previous target's buffers are overwritten in place where they are large
    /// enough (a new target costs an upload, rarely an allocation).
    pub fn set_target(
        &mut self,
        points: &[Vec3],
        normals: Option<&[Vec3]>,
        bucket_size_m: f32,
    ) -> Result<()> {
        if let Some(n) = normals {
            if n.len() != points.len() {
                return Err(GpuError::Invalid(format!(
                    "{} normals for {} target points",
                    n.len(),
                    points.len()
                )));
            }
        }
        let grid = HostGrid::build(points, normals, bucket_size_m)?;
        self.check_size(grid.sorted.len() * 16, "the target cloud")?;
        self.check_size(grid.start.len() * 4, "the target's bucket grid")?;
        let dummy = [[0.0f32; 4]];
        let normal_data: &[[f32; 4]] = grid.normals.as_deref().unwrap_or(&dummy);
        let old = self.target.take();
        let ctx = &self.ctx;
        let (buffers, reallocated) = ctx.scoped("uploading the target cloud", || {
            let mut realloc = false;
            let mut put = |old: Option<wgpu::Buffer>, label: &str, bytes: &[u8]| {
                let (b, r) = upload(ctx, old, label, bytes);
                realloc |= r;
                b
            };
            let (t, n, k, v, st) = match old {
                Some(o) => (
                    Some(o.target),
                    Some(o.normals),
                    Some(o.keys),
                    Some(o.vals),
                    Some(o.starts),
                ),
                None => (None, None, None, None, None),
            };
            let target = put(t, "target", bytemuck::cast_slice(&grid.sorted));
            let normals = put(n, "normals", bytemuck::cast_slice(normal_data));
            let keys = put(k, "keys", bytemuck::cast_slice(&grid.keys));
            let vals = put(v, "vals", bytemuck::cast_slice(&grid.vals));
            let starts = put(st, "starts", bytemuck::cast_slice(&grid.start));
            Ok(((target, normals, keys, vals, starts), realloc))
        })?;
        let (target, normals, keys, vals, starts) = buffers;
        self.target = Some(TargetBuffers {
            target,
            normals,
            keys,
            vals,
            starts,
            has_normals: grid.normals.is_some(),
            grid,
        });
        if reallocated {
            self.bind = None;
        }
        self.hints_stale = true;
        self.sensor = None;
        Ok(())
    }

    /// Turns the back-face test on (`Some(sensor)`, the source's sensor position in the source
    /// frame) or off (`None`, the default; a new target turns it off). With it on, a nearest
    /// model point whose normal points away from the sensor (moved into the model frame by
    /// each iteration's transform) is no pair: its surface is seen from behind. The model's
    /// normals must be oriented toward the sensors that saw them.
    pub fn set_back_face_test(&mut self, sensor_in_source: Option<Vec3>) -> Result<()> {
        if let Some(s) = sensor_in_source {
            if !s.is_finite() {
                return Err(GpuError::Invalid(format!(
                    "the sensor position {s} is not finite"
                )));
            }
            if !self.target_has_normals() {
                return Err(GpuError::Invalid(
                    "the back-face test needs a target with (oriented) normals".into(),
                ));
            }
        }
        self.sensor = sensor_in_source;
        Ok(())
    }

    /// Times the stages apart (`true`: the search, the final reduction and the copy back are
    /// submitted and waited for one by one, as `semsim bench icp` reports them) or not
    /// (`false`, the default and the ICP loop's way: one submission and one wait per iteration;
    /// [`StageTimes::search_ms`] then covers all the GPU work and the copy back).
    pub fn set_stage_timing(&mut self, on: bool) {
        self.stage_timing = on;
    }

    /// Whether a target with normals (as point-to-plane needs) is uploaded.
    pub fn target_has_normals(&self) -> bool {
        self.target.as_ref().is_some_and(|t| t.has_normals)
    }

    /// Uploads the data cloud, reusing the buffers when they are large enough.
    pub fn set_source(&mut self, points: &[Vec3]) -> Result<()> {
        self.set_weighted_source(points, &[])
    }

    /// [`GpuIcp::set_source`] with a prior weight per point (multiplying each pair's robust
    /// kernel weight; empty: all 1).
    pub fn set_weighted_source(&mut self, points: &[Vec3], weights: &[f32]) -> Result<()> {
        if !weights.is_empty() && weights.len() != points.len() {
            return Err(GpuError::Invalid(format!(
                "{} weights for {} source points",
                weights.len(),
                points.len()
            )));
        }
        if let Some(i) = weights.iter().position(|w| !(w.is_finite() && *w >= 0.0)) {
            return Err(GpuError::Invalid(format!(
                "source weight {i} is not a finite non-negative number"
            )));
        }
        if points.is_empty() {
            return Err(GpuError::Invalid("the source cloud is empty".into()));
        }
        if let Some(i) = points.iter().position(|p| !p.is_finite()) {
            return Err(GpuError::Invalid(format!("source point {i} is not finite")));
        }
        let n = points.len() as u32;
        if n.div_ceil(WG) > self.ctx.limits.max_compute_workgroups_per_dimension {
            return Err(GpuError::TooLarge(format!(
                "{n} source points exceed one dispatch"
            )));
        }
        self.check_size(points.len() * 16, "the source cloud")?;
        // The fourth component is the point's prior weight.
        let data: Vec<[f32; 4]> = points
            .iter()
            .enumerate()
            .map(|(i, p)| [p.x, p.y, p.z, weights.get(i).copied().unwrap_or(1.0)])
            .collect();
        let ctx = &self.ctx;
        let source = &mut self.source;
        let bind = &mut self.bind;
        ctx.scoped("uploading the source cloud", || {
            if source.as_ref().is_none_or(|s| s.capacity < n) {
                let d = &ctx.device;
                let rw = wgpu::BufferUsages::STORAGE
                    | wgpu::BufferUsages::COPY_SRC
                    | wgpu::BufferUsages::COPY_DST;
                *source = Some(SourceBuffers {
                    len: n,
                    capacity: n,
                    source: buffer(d, "source", n as u64 * 16, rw),
                    corr: buffer(d, "corr", n as u64 * 4, rw),
                    dist2: buffer(d, "dist2", n as u64 * 4, rw),
                    partials: buffer(d, "partials", n.div_ceil(WG) as u64 * K as u64 * 4, rw),
                });
                *bind = None;
            }
            if let Some(s) = source.as_mut() {
                s.len = n;
                ctx.queue
                    .write_buffer(&s.source, 0, bytemuck::cast_slice(&data));
            }
            Ok(())
        })?;
        self.hints_stale = true;
        Ok(())
    }

    /// One point-to-point iteration's sums for `target_from_source` with the correspondence gate.
    pub fn p2p_sums(
        &mut self,
        target_from_source: Mat4,
        max_distance_m: f32,
        reference: Vec3,
    ) -> Result<(P2pSums, StageTimes)> {
        self.p2p_sums_weighted(
            target_from_source,
            max_distance_m,
            reference,
            GpuKernel::None,
        )
    }

    /// [`GpuIcp::p2p_sums`] with each pair weighted by `kernel` of its point distance.
    pub fn p2p_sums_weighted(
        &mut self,
        target_from_source: Mat4,
        max_distance_m: f32,
        reference: Vec3,
        kernel: GpuKernel,
    ) -> Result<(P2pSums, StageTimes)> {
        let (v, t) = self.run(target_from_source, max_distance_m, reference, 0, kernel)?;
        let f = |i: usize| v.get(i).copied().unwrap_or(f32::NAN) as f64;
        let sums = P2pSums {
            count: f(0),
            sum_p: [f(1), f(2), f(3)],
            sum_q: [f(4), f(5), f(6)],
            sum_pq: std::array::from_fn(|i| f(7 + i)),
            sum_d2: f(16),
            weight: f(17),
        };
        Ok((sums, t))
    }

    /// One point-to-plane iteration's normal equations (needs target normals).
    pub fn p2plane_system(
        &mut self,
        target_from_source: Mat4,
        max_distance_m: f32,
        reference: Vec3,
        kernel: GpuKernel,
    ) -> Result<(PlaneSystem, StageTimes)> {
        if !self.target.as_ref().is_some_and(|t| t.has_normals) {
            return Err(GpuError::Invalid(
                "point-to-plane needs target normals".into(),
            ));
        }
        let (v, t) = self.run(target_from_source, max_distance_m, reference, 1, kernel)?;
        let f = |i: usize| v.get(i).copied().unwrap_or(f32::NAN) as f64;
        let sys = PlaneSystem {
            count: f(0),
            jtj_upper: std::array::from_fn(|i| f(1 + i)),
            jtr: std::array::from_fn(|i| f(22 + i)),
            sum_wr2: f(28),
            sum_d2: f(29),
        };
        Ok((sys, t))
    }

    /// The correspondences themselves (input index into the target, squared distance), for
    /// checking against the CPU search; downloads one entry per source point.
    pub fn correspondences(
        &mut self,
        target_from_source: Mat4,
        max_distance_m: f32,
    ) -> Result<Vec<Option<(u32, f32)>>> {
        self.run(
            target_from_source,
            max_distance_m,
            Vec3::ZERO,
            0,
            GpuKernel::None,
        )?;
        let (Some(s), Some(t)) = (&self.source, &self.target) else {
            return Err(GpuError::Invalid("no clouds uploaded".into()));
        };
        let (idx, d2): (Vec<u32>, Vec<f32>) =
            self.ctx.scoped("reading the correspondences back", || {
                Ok((
                    read_back(&self.ctx, &s.corr, s.len as u64 * 4)?,
                    read_back(&self.ctx, &s.dist2, s.len as u64 * 4)?,
                ))
            })?;
        Ok(idx
            .iter()
            .zip(&d2)
            .map(|(&i, &d)| {
                (i != NONE && d >= 0.0)
                    .then(|| (t.grid.original.get(i as usize).copied().unwrap_or(NONE), d))
            })
            .collect())
    }

    fn check_size(&self, bytes: usize, what: &str) -> Result<()> {
        let max = self.ctx.limits.max_storage_buffer_binding_size as usize;
        if bytes > max {
            return Err(GpuError::TooLarge(format!(
                "{what} needs {bytes} bytes, the device binds at most {max}"
            )));
        }
        Ok(())
    }
}
