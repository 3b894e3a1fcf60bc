//! Dispatch of the WGSL kernels: the model cloud's grid and the data cloud stay on the GPU across
//! iterations (and across scans for the model), buffers are reused, and per iteration only the
//! 4x4 transform goes up and a few dozen floats come back.

use crate::context::GpuContext;
use crate::error::{GpuError, Result};
use crate::grid::{HostGrid, NONE};
use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec3};
use std::time::Instant;

const WG: u32 = 128;
const K: usize = 30;

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct Params {
    transform: [f32; 16],
    origin: [f32; 4],
    reference: [f32; 4],
    dims: [u32; 4],
    counts: [u32; 4],
    kernel: [f32; 4],
    sensor: [f32; 4],
}

/// Robust kernel for point-to-plane (IRLS weight computed on the GPU).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GpuKernel {
    /// Plain least squares.
    None,
    /// Huber with width `k` metres.
    Huber(f32),
    /// Cauchy with width `k` metres.
    Cauchy(f32),
}

/// Wall-clock split of one GPU iteration, in milliseconds. Without stage timing (see
/// [`GpuIcp::set_stage_timing`]) everything after the upload counts as `search_ms`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StageTimes {
    /// Writing the parameters (and, on the first iteration, the data points).
    pub upload_ms: f64,
    /// The nearest-neighbour search with the per-workgroup reduction.
    pub search_ms: f64,
    /// The final reduction of the workgroup partials.
    pub reduce_ms: f64,
    /// Copying the sums back and mapping them.
    pub download_ms: f64,
}

/// Point-to-point sums over the accepted pairs (transformed data point p, model point q),
/// both centred on the `reference` point given, each pair weighted by the robust kernel `w` of
/// its distance (1 without a kernel): count, sum w p, sum w q, sum w p q^T, sum |p - q|^2, sum w.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct P2pSums {
    /// Pairs.
    pub count: f64,
    /// Sum of w (p - reference).
    pub sum_p: [f64; 3],
    /// Sum of w (q - reference).
    pub sum_q: [f64; 3],
    /// Sum of w (p - reference)(q - reference)^T, row-major.
    pub sum_pq: [f64; 9],
    /// Sum of squared distances (unweighted).
    pub sum_d2: f64,
    /// Sum of the weights (equals `count` without a kernel).
    pub weight: f64,
}

/// Point-to-plane normal equations over the accepted pairs, linearised about `reference`:
/// upper triangle of J^T W J (21, row-major), J^T W r (6), sum of w r^2, pair count, sum of
/// squared point distances.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneSystem {
    /// Pairs.
    pub count: f64,
    /// Upper triangle of J^T W J, row by row.
    pub jtj_upper: [f64; 21],
    /// J^T W r.
    pub jtr: [f64; 6],
    /// Sum of w r^2.
    pub sum_wr2: f64,
    /// Sum of the squared point (not plane) distances of the pairs.
    pub sum_d2: f64,
}

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
        let parts = ctx.scoped("compiling the ICP kernels", || Ok(Self::build(&ctx)))?;
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

    #[allow(clippy::type_complexity)]
    fn build(
        ctx: &GpuContext,
    ) -> (
        wgpu::BindGroupLayout,
        wgpu::ComputePipeline,
        wgpu::ComputePipeline,
        wgpu::Buffer,
        wgpu::Buffer,
        wgpu::Buffer,
    ) {
        let d = &ctx.device;
        let module = d.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("icp.wgsl"),
            source: wgpu::ShaderSource::Wgsl(include_str!("icp.wgsl").into()),
        });
        let entry = |binding: u32, ty: wgpu::BufferBindingType| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let ro = wgpu::BufferBindingType::Storage { read_only: true };
        let rw = wgpu::BufferBindingType::Storage { read_only: false };
        let mut entries = vec![entry(0, wgpu::BufferBindingType::Uniform)];
        entries.extend((1..=6).map(|b| entry(b, ro)));
        entries.extend((7..=10).map(|b| entry(b, rw)));
        let layout = d.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("icp"),
            entries: &entries,
        });
        let pl = d.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("icp"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = |name: &str| {
            d.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(name),
                layout: Some(&pl),
                module: &module,
                entry_point: Some(name),
                compilation_options: Default::default(),
                cache: None,
            })
        };
        let search = pipeline("search_reduce");
        let sum = pipeline("sum_partials");
        let params = buffer(
            d,
            "params",
            std::mem::size_of::<Params>() as u64,
            wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        );
        let totals = buffer(
            d,
            "totals",
            (K * 4) as u64,
            wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        );
        let readback = buffer(
            d,
            "readback",
            (K * 4) as u64,
            wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        );
        (layout, search, sum, params, totals, readback)
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
        let data: Vec<[f32; 4]> = points.iter().map(|p| [p.x, p.y, p.z, 1.0]).collect();
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

    fn run(
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

    fn dispatch(
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
    fn encode(
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

    fn bind_group(&self) -> wgpu::BindGroup {
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

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

fn buffer(d: &wgpu::Device, label: &str, size: u64, usage: wgpu::BufferUsages) -> wgpu::Buffer {
    d.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size.max(16),
        usage,
        mapped_at_creation: false,
    })
}

/// Writes `bytes` into `old` if it is large enough, else into a new buffer with 25% headroom;
/// returns the buffer and whether it is new.
fn upload(
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

fn read_back<T: Pod>(ctx: &GpuContext, src: &wgpu::Buffer, bytes: u64) -> Result<Vec<T>> {
    let staging = buffer(
        &ctx.device,
        "staging",
        bytes,
        wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
    );
    read_back_via(ctx, src, &staging, bytes)
}

fn read_back_via<T: Pod>(
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
fn map_read<T: Pod>(ctx: &GpuContext, staging: &wgpu::Buffer, bytes: u64) -> Result<Vec<T>> {
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

#[cfg(test)]
mod tests {
    //! wgpu's validation errors, forced on purpose, come back as typed errors naming what was
    //! being done (not as wgpu's default panic), and the device stays usable afterwards.
    use super::*;
    use crate::context::AdapterChoice;

    fn open(test: &str) -> Option<GpuIcp> {
        match GpuContext::new(AdapterChoice::Any) {
            Ok(ctx) => Some(GpuIcp::new(ctx).expect("kernels compile")),
            Err(GpuError::NoAdapter(why)) => {
                eprintln!("{test}: SKIPPED: no GPU adapter at all ({why})");
                None
            }
            Err(e) => panic!("{test}: opening the GPU failed: {e}"),
        }
    }

    fn line(n: usize) -> Vec<Vec3> {
        (0..n)
            .map(|i| Vec3::new(i as f32 * 0.01, 0.0, 0.0))
            .collect()
    }

    #[test]
    fn a_validation_error_inside_a_scope_is_a_typed_error_and_the_device_recovers() {
        let Some(mut icp) = open("validation_error") else {
            return;
        };
        let points = line(500);
        icp.set_target(&points, None, 0.2).expect("target");
        icp.set_source(&points).expect("source");
        let (before, _) = icp.p2p_sums(Mat4::IDENTITY, 0.5, Vec3::ZERO).expect("sums");
        assert_eq!(before.count as usize, 500);
        // Submitted stage by stage (to time them) or at once, the sums are the same.
        icp.set_stage_timing(true);
        let (split, times) = icp.p2p_sums(Mat4::IDENTITY, 0.5, Vec3::ZERO).expect("sums");
        assert_eq!(split, before);
        assert!(
            times.reduce_ms > 0.0 && times.download_ms > 0.0,
            "{times:?}"
        );
        icp.set_stage_timing(false);
        // More workgroups than one dispatch may have: wgpu rejects the dispatch.
        let too_many = icp.ctx.limits.max_compute_workgroups_per_dimension + 1;
        let bind = icp.bind.clone().expect("bound");
        let err = icp
            .ctx
            .scoped("dispatching too many workgroups", || {
                icp.dispatch(&bind, &icp.search, too_many)
            })
            .expect_err("wgpu must reject the dispatch");
        match &err {
            GpuError::Validation { during, msg } => {
                assert_eq!(during, "dispatching too many workgroups");
                assert!(!msg.is_empty());
            }
            other => panic!("expected a validation error, got {other:?}"),
        }
        assert!(
            !err.is_bad_input(),
            "a kernel misuse is not the user's input"
        );
        // Nothing is lost: the next iteration runs and gives the same sums.
        let (after, _) = icp.p2p_sums(Mat4::IDENTITY, 0.5, Vec3::ZERO).expect("sums");
        assert_eq!(after, before);
    }

    #[test]
    fn an_error_outside_every_scope_is_reported_by_the_next_operation() {
        let Some(mut icp) = open("uncaptured_error") else {
            return;
        };
        // A buffer larger than the device allows, created outside any error scope: wgpu hands
        // the error to the uncaptured-error handler (whose default would panic).
        let too_big = icp.ctx.limits.max_buffer_size.saturating_add(16);
        let _ = icp.ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("too big"),
            size: too_big,
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });
        let points = line(100);
        let err = icp
            .set_target(&points, None, 0.2)
            .expect_err("the recorded error comes back");
        assert!(
            matches!(&err, GpuError::Validation { msg, .. } if !msg.is_empty()),
            "{err:?}"
        );
        // Reported once: the retry succeeds.
        icp.set_target(&points, None, 0.2).expect("target");
        icp.set_source(&points).expect("source");
        let (sums, _) = icp.p2p_sums(Mat4::IDENTITY, 0.5, Vec3::ZERO).expect("sums");
        assert_eq!(sums.count as usize, 100);
    }
}
