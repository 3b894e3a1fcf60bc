//! `semsim bench icp`: ms per ICP iteration on the CPU and on the GPU for two 162,841-point
//! virtual scans and a 1.6 M-point pair: the GPU kernels' iteration as the loop submits it (one
//! submission and one wait), the same split into upload, search, reduction and download (a wait
//! after each stage), and the whole ICP loop on the GPU (`registration::register` with `device = gpu`:
//! the kernels' sums, the SVD on the CPU, the stop criteria) per iteration. Writes a JSON report;
//! figures are ratios against the CPU measured in the same run.

use crate::exit::bad_input;
use anyhow::Context;
use clap::{Args, Subcommand, ValueEnum};
use glam::{Mat4, Quat, Vec3};
use registration::{Device, IcpConfig, Method};
use scanner::{Building, BuildingGeometry, LaserConfig, ScanPose, VirtualLaser};
use std::path::PathBuf;
use std::time::Instant;

/// Benchmark subcommands.
#[derive(Subcommand)]
pub enum BenchCommand {
    /// ICP iterations on CPU and GPU.
    Icp(IcpBenchArgs),
}

/// Which devices to measure.
#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum BenchDevice {
    /// CPU only.
    Cpu,
    /// GPU only (error if none).
    Gpu,
    /// Both where a GPU exists.
    Auto,
}

/// Arguments of `semsim bench icp`.
#[derive(Args)]
pub struct IcpBenchArgs {
    /// Devices to measure.
    #[arg(long, value_enum, default_value = "auto")]
    device: BenchDevice,
    /// Iterations measured per case.
    #[arg(long, default_value_t = 10)]
    iterations: usize,
    /// GPU bucket edge in metres (the 27-bucket search is exact within one bucket edge; the gate is 0.5 m).
    #[arg(long, default_value_t = 0.5)]
    bucket: f32,
    /// Skip the 1.6 M-point pair.
    #[arg(long)]
    small_only: bool,
    /// Write the report here (JSON).
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
}

/// Runs a benchmark.
pub fn run(c: BenchCommand) -> anyhow::Result<()> {
    let BenchCommand::Icp(a) = c;
    if a.iterations == 0 || a.iterations > 1000 {
        return Err(bad_input("--iterations must be within 1..1000"));
    }
    let gpu = match a.device {
        BenchDevice::Cpu => None,
        BenchDevice::Gpu => Some(open_gpu(gpu::AdapterChoice::Any)?),
        BenchDevice::Auto => open_gpu(gpu::AdapterChoice::Any).ok(),
    };
    let mut cases = vec![("162,841-point scans", LaserConfig::default())];
    if !a.small_only {
        cases.push((
            "1.6 M-point scans",
            LaserConfig {
                beams: 1623,
                rotation_steps: 1003,
                ..Default::default()
            },
        ));
    }
    let mut gpu = gpu;
    let mut rows = Vec::new();
    println!(
        "{:<22} {:>8} {:>10} {:>10} {:>10} {:>9} {:>9} {:>9} {:>9} {:>8}",
        "case",
        "points",
        "cpu ms/it",
        "gpu ms/it",
        "loop ms/it",
        "upload",
        "search",
        "reduce",
        "download",
        "speedup"
    );
    for (name, laser) in cases {
        let (target, source) = pair(laser)?;
        let cpu_ms = matches!(a.device, BenchDevice::Cpu | BenchDevice::Auto)
            .then(|| ms_per_iteration(&target, &source, a.iterations, Device::Cpu))
            .transpose()?;
        let mut on_gpu = |stage_timing| {
            gpu.as_mut()
                .map(|g| {
                    g.set_stage_timing(stage_timing);
                    gpu_ms_per_iteration(g, &target, &source, a.iterations, a.bucket)
                })
                .transpose()
        };
        // The split needs a wait after each stage; the total is measured as the loop runs
        // (one submission and one wait per iteration).
        let (gpu_split, target_ms) = on_gpu(true)?.unzip();
        let gpu_ms =
            on_gpu(false)?.map(|(s, _)| s.upload_ms + s.search_ms + s.reduce_ms + s.download_ms);
        let loop_ms = gpu
            .is_some()
            .then(|| ms_per_iteration(&target, &source, a.iterations, Device::Gpu))
            .transpose()?;
        let speedup = cpu_ms.zip(gpu_ms).map(|(c, g)| c / g);
        let f = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.3}"));
        let s = gpu_split.unwrap_or_default();
        println!(
            "{name:<22} {:>8} {:>10} {:>10} {:>10} {:>9.3} {:>9.3} {:>9.3} {:>9.3} {:>8}",
            source.len(),
            f(cpu_ms),
            f(gpu_ms),
            f(loop_ms),
            s.upload_ms,
            s.search_ms,
            s.reduce_ms,
            s.download_ms,
            speedup.map_or("-".into(), |x| format!("{x:.1}x"))
        );
        rows.push(serde_json::json!({
            "case": name, "source_points": source.len(), "target_points": target.len(),
            "cpu_ms_per_iteration": cpu_ms, "gpu_ms_per_iteration": gpu_ms,
            "gpu_loop_ms_per_iteration": loop_ms,
            "gpu_upload_ms": gpu_split.map(|s| s.upload_ms), "gpu_search_ms": gpu_split.map(|s| s.search_ms),
            "gpu_reduce_ms": gpu_split.map(|s| s.reduce_ms), "gpu_download_ms": gpu_split.map(|s| s.download_ms),
            "gpu_speedup": speedup, "gpu_target_grid_ms": target_ms,
        }));
    }
    let adapter = gpu.as_ref().map(|g| g.context().adapter_name());
    println!("GPU adapter: {}", adapter.as_deref().unwrap_or("none"));
    for row in &rows {
        if let Some(ms) = row["gpu_target_grid_ms"].as_f64() {
            println!(
                "{}: target grid built on the CPU and uploaded in {ms:.1} ms (once per target)",
                row["case"].as_str().unwrap_or("?")
            );
        }
    }
    println!("CPU threads: {}", rayon::current_num_threads());
    if let Some(path) = &a.json {
        let report = serde_json::json!({ "adapter": adapter, "cpu_threads": rayon::current_num_threads(), "iterations": a.iterations, "cases": rows });
        let text = serde_json::to_string_pretty(&report).context("serialising the report")?;
        cloud::write_bytes_atomically(path, text.as_bytes())?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// Opens a GPU; "no adapter" is bad input (exit 2) for `--device gpu`.
pub fn open_gpu(choice: gpu::AdapterChoice) -> anyhow::Result<gpu::GpuIcp> {
    let ctx = gpu::GpuContext::new(choice).map_err(|e| bad_input(e.to_string()))?;
    Ok(gpu::GpuIcp::new(ctx)?)
}

/// Two scans of the default building 0.8 m and 5 degrees apart (target, source), missing returns dropped.
fn pair(laser: LaserConfig) -> anyhow::Result<(Vec<Vec3>, Vec<Vec3>)> {
    let b = Building::default_building()?;
    let g = BuildingGeometry::new(&b);
    let l = VirtualLaser::new(laser)?;
    let t = l
        .scan(
            &g,
            &ScanPose {
                x_m: 6.5,
                y_m: 0.0,
                yaw_deg: 0.0,
            },
            0,
        )
        .without_invalid();
    let s = l
        .scan(
            &g,
            &ScanPose {
                x_m: 7.3,
                y_m: 0.6,
                yaw_deg: 5.0,
            },
            1,
        )
        .without_invalid();
    Ok((t.points, s.points))
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
) -> anyhow::Result<f64> {
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

/// Mean time of the GPU kernels' iterations (`p2p_sums`, 0.5 m gate), split into stages.
fn gpu_ms_per_iteration(
    g: &mut gpu::GpuIcp,
    target: &[Vec3],
    source: &[Vec3],
    iterations: usize,
    bucket_m: f32,
) -> anyhow::Result<(gpu::StageTimes, f64)> {
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
        let (_, t) = g.p2p_sums(t, 0.5, reference)?;
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
