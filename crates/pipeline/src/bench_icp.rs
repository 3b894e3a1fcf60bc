//! The ICP benchmark (`semsim bench icp`): ms per ICP iteration on the CPU and on the GPU for
//! two virtual scans of the default building, the GPU kernels' iteration as the loop submits
//! it (one submission and one wait), the same split into upload, search, reduction and
//! download, and the whole ICP loop on the GPU. Figures are compared within one run.

use crate::error::{PipelineError, Result};
use glam::{Mat4, Quat, Vec3};
use registration::{Device, IcpConfig, Method};
use scanner::{Building, BuildingGeometry, LaserConfig, ScanPose, VirtualLaser};
use serde::Serialize;
use std::time::Instant;

/// The gate of every benchmarked iteration (the paper's fixed 0.5 m).
const GATE_M: f32 = 0.5;

/// One benchmarked pair of scans.
#[derive(Debug, Clone, Serialize)]
pub struct IcpBenchRow {
    /// The case's name.
    pub case: String,
    /// Points of the source scan.
    pub source_points: usize,
    /// Points of the target scan.
    pub target_points: usize,
    /// CPU: mean ms per ICP iteration.
    pub cpu_ms_per_iteration: Option<f64>,
    /// GPU kernels: mean ms per iteration (one submission).
    pub gpu_ms_per_iteration: Option<f64>,
    /// The whole ICP loop on the GPU: mean ms per iteration.
    pub gpu_loop_ms_per_iteration: Option<f64>,
    /// GPU split: upload.
    pub gpu_upload_ms: Option<f64>,
    /// GPU split: search.
    pub gpu_search_ms: Option<f64>,
    /// GPU split: reduction.
    pub gpu_reduce_ms: Option<f64>,
    /// GPU split: download.
    pub gpu_download_ms: Option<f64>,
    /// CPU time over GPU kernel time.
    pub gpu_speedup: Option<f64>,
    /// The target grid built on the CPU and uploaded, once per target.
    pub gpu_target_grid_ms: Option<f64>,
}

/// The benchmark's cases: the default laser (162,841-point scans) and, unless `small_only`,
/// a dense one (1.6 M points).
pub fn icp_bench_cases(small_only: bool) -> Vec<(&'static str, LaserConfig)> {
    let mut cases = vec![("162,841-point scans", LaserConfig::default())];
    if !small_only {
        cases.push((
            "1.6 M-point scans",
            LaserConfig {
                beams: 1623,
                rotation_steps: 1003,
                ..Default::default()
            },
        ));
    }
    cases
}

/// Opens a GPU for the benchmark; "no adapter" is bad input (the user asked for a GPU).
pub fn open_bench_gpu(choice: gpu::AdapterChoice) -> Result<gpu::GpuIcp> {
    let ctx = gpu::GpuContext::new(choice).map_err(|e| PipelineError::bad_input(e.to_string()))?;
    Ok(gpu::GpuIcp::new(ctx)?)
}

/// Benchmarks one case: the CPU if `cpu`, the GPU if one is given, `iterations` each.
pub fn bench_icp_case(
    name: &str,
    laser: LaserConfig,
    cpu: bool,
    gpu: Option<&mut gpu::GpuIcp>,
    iterations: usize,
    bucket_m: f32,
) -> Result<IcpBenchRow> {
    let (target, source) = pair(laser)?;
    let cpu_ms = cpu
        .then(|| ms_per_iteration(&target, &source, iterations, Device::Cpu))
        .transpose()?;
    let (mut split, mut gpu_ms, mut loop_ms, mut grid_ms) = (None, None, None, None);
    if let Some(g) = gpu {
        // The split needs a wait after each stage; the total is measured as the loop runs
        // (one submission and one wait per iteration).
        g.set_stage_timing(true);
        let (s, t) = gpu_ms_per_iteration(g, &target, &source, iterations, bucket_m)?;
        g.set_stage_timing(false);
        let (fused, _) = gpu_ms_per_iteration(g, &target, &source, iterations, bucket_m)?;
        split = Some(s);
        grid_ms = Some(t);
        gpu_ms = Some(fused.upload_ms + fused.search_ms + fused.reduce_ms + fused.download_ms);
        loop_ms = Some(ms_per_iteration(&target, &source, iterations, Device::Gpu)?);
    }
    Ok(IcpBenchRow {
        case: name.to_string(),
        source_points: source.len(),
        target_points: target.len(),
        cpu_ms_per_iteration: cpu_ms,
        gpu_ms_per_iteration: gpu_ms,
        gpu_loop_ms_per_iteration: loop_ms,
        gpu_upload_ms: split.map(|s| s.upload_ms),
        gpu_search_ms: split.map(|s| s.search_ms),
        gpu_reduce_ms: split.map(|s| s.reduce_ms),
        gpu_download_ms: split.map(|s| s.download_ms),
        gpu_speedup: cpu_ms.zip(gpu_ms).map(|(c, g)| c / g),
        gpu_target_grid_ms: grid_ms,
    })
}

/// Two scans of the default building 0.8 m and 5 degrees apart (target, source), missing returns dropped.
fn pair(laser: LaserConfig) -> Result<(Vec<Vec3>, Vec<Vec3>)> {
    let b = Building::default_building()?;
    let g = BuildingGeometry::new(&b);
    let l = VirtualLaser::new(laser)?;
    let at = |x_m, y_m, yaw_deg, k| {
        l.scan(&g, &ScanPose { x_m, y_m, yaw_deg }, k)
            .without_invalid()
            .points
    };
    Ok((at(6.5, 0.0, 0.0, 0), at(7.3, 0.6, 5.0, 1)))
}

/// The truth of `pair` perturbed by 0.3 m / 5 degrees, as the starting transform.
fn start() -> Mat4 {
    let truth = Mat4::from_rotation_translation(
        Quat::from_rotation_z(5f32.to_radians()),
        Vec3::new(0.8, 0.6, 0.0),
    );
    truth
        * Mat4::from_rotation_translation(
            Quat::from_rotation_z(5f32.to_radians()),
            Vec3::new(0.25, 0.15, 0.05),
        )
}

/// Mean iteration time of `registration::register` (point-to-point, full resolution, 0.5 m
/// gate) on `device`.
fn ms_per_iteration(
    target: &[Vec3],
    source: &[Vec3],
    iterations: usize,
    device: Device,
) -> Result<f64> {
    let config = IcpConfig {
        method: Method::PointToPoint,
        device,
        max_iterations: iterations,
        translation_epsilon_m: 0.0,
        rotation_epsilon_deg: 0.0,
        rmse_relative_epsilon: 0.0,
        min_fitness: 0.0,
        ..IcpConfig::point_to_point()
    };
    let t = cloud::PointCloud::from_points(target.to_vec());
    let s = cloud::PointCloud::from_points(source.to_vec());
    let guess = glam::DAffine3::from_mat4(start().as_dmat4());
    let result = match registration::register(&s, &t, guess, &config) {
        Ok(r) => r,
        Err(registration::RegistrationError::NotConverged { result, .. }) => *result,
        Err(e) => return Err(e.into()),
    };
    let its = &result.iterations;
    Ok(its.iter().map(|i| i.time_ms).sum::<f64>() / its.len().max(1) as f64)
}

/// Mean time of the GPU kernels' iterations (`p2p_sums`, 0.5 m gate), split into stages, and
/// the time to build and upload the target grid.
fn gpu_ms_per_iteration(
    g: &mut gpu::GpuIcp,
    target: &[Vec3],
    source: &[Vec3],
    iterations: usize,
    bucket_m: f32,
) -> Result<(gpu::StageTimes, f64)> {
    let t0 = Instant::now();
    g.set_target(target, None, bucket_m)?;
    let target_ms = t0.elapsed().as_secs_f64() * 1e3;
    let t0 = Instant::now();
    g.set_source(source)?;
    let source_upload_ms = t0.elapsed().as_secs_f64() * 1e3;
    let mut sum = gpu::StageTimes::default();
    let reference = target.iter().copied().sum::<Vec3>() / target.len() as f32;
    // Alternate between the start and a transform 2 cm / 0.2 degrees away, as consecutive ICP
    // iterations move: each search starts from the previous iteration's pairs (its hints) but
    // never from the answer itself.
    let nudge = Mat4::from_rotation_translation(
        Quat::from_rotation_z(0.2f32.to_radians()),
        Vec3::new(0.02, -0.01, 0.005),
    );
    for i in 0..iterations {
        let t = if i % 2 == 0 { start() } else { start() * nudge };
        let (_, t) = g.p2p_sums(t, GATE_M, reference)?;
        sum.upload_ms += t.upload_ms;
        sum.search_ms += t.search_ms;
        sum.reduce_ms += t.reduce_ms;
        sum.download_ms += t.download_ms;
    }
    let n = iterations as f64;
    let times = gpu::StageTimes {
        upload_ms: sum.upload_ms / n + source_upload_ms / n,
        search_ms: sum.search_ms / n,
        reduce_ms: sum.reduce_ms / n,
        download_ms: sum.download_ms / n,
    };
    Ok((times, target_ms))
}
