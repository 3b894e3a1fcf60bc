//! `semsim bench icp`: ms per ICP iteration on the CPU and on the GPU (`pipeline::bench_icp_case`
//! measures; this prints the table and writes the JSON report). Figures are ratios against the
//! CPU measured in the same run.

use crate::exit::bad_input;
use anyhow::Context;
use clap::{Args, Subcommand, ValueEnum};
use pipeline::{bench_icp_case, icp_bench_cases, open_bench_gpu};
use std::path::PathBuf;

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
    let mut gpu = match a.device {
        BenchDevice::Cpu => None,
        BenchDevice::Gpu => Some(open_bench_gpu(gpu::AdapterChoice::Any)?),
        BenchDevice::Auto => open_bench_gpu(gpu::AdapterChoice::Any).ok(),
    };
    let cpu = matches!(a.device, BenchDevice::Cpu | BenchDevice::Auto);
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
    let mut rows = Vec::new();
    for (name, laser) in icp_bench_cases(a.small_only) {
        let r = bench_icp_case(name, laser, cpu, gpu.as_mut(), a.iterations, a.bucket)?;
        let f = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.3}"));
        let z = |v: Option<f64>| v.unwrap_or(0.0);
        println!(
            "{name:<22} {:>8} {:>10} {:>10} {:>10} {:>9.3} {:>9.3} {:>9.3} {:>9.3} {:>8}",
            r.source_points,
            f(r.cpu_ms_per_iteration),
            f(r.gpu_ms_per_iteration),
            f(r.gpu_loop_ms_per_iteration),
            z(r.gpu_upload_ms),
            z(r.gpu_search_ms),
            z(r.gpu_reduce_ms),
            z(r.gpu_download_ms),
            r.gpu_speedup.map_or("-".into(), |x| format!("{x:.1}x"))
        );
        rows.push(r);
    }
    let adapter = gpu.as_ref().map(|g| g.context().adapter_name());
    println!("GPU adapter: {}", adapter.as_deref().unwrap_or("none"));
    for r in &rows {
        if let Some(ms) = r.gpu_target_grid_ms {
            println!(
                "{}: target grid built on the CPU and uploaded in {ms:.1} ms (once per target)",
                r.case
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
