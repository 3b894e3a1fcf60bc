//! `semsim register`: ICP for a pair of scans, or a whole sequence against a growing map.

use crate::exit::bad_input;
use crate::scan_input::ScanReadArgs;
use clap::Args;
use glam::{DAffine3, DMat4};
use pipeline::Config;
use registration::{Device, IcpResult, Method, Registrar, RegistrationError};
use std::path::PathBuf;

/// Arguments of `semsim register`.
#[derive(Args)]
pub struct RegisterArgs {
    /// Pair mode: SOURCE TARGET. With --sequence: folders or files of scans, in order.
    #[arg(required = true, value_name = "SCANS")]
    inputs: Vec<PathBuf>,
    /// Register a whole sequence: scan k against the map of scans 0..k-1.
    #[arg(long)]
    sequence: bool,
    /// Initial target_from_source: a file of 16 numbers (row-major 4x4), or x,y,z,roll,pitch,yaw (metres, degrees).
    #[arg(long, value_name = "FILE|X,Y,Z,R,P,Y")]
    guess: Option<String>,
    /// ICP variant: p2p, p2plane or gicp (default from the configuration).
    #[arg(long, value_name = "METHOD")]
    method: Option<Method>,
    /// Where ICP runs: auto (a hardware GPU for p2p/p2plane if there is one, else the CPU),
    /// cpu, or gpu (any Vulkan adapter, software ones included; GICP is CPU-only). Default from
    /// the configuration ([registration.icp] device, itself auto by default).
    #[arg(long, value_name = "auto|cpu|gpu")]
    device: Option<Device>,
    /// Pair mode: print exactly one JSON object.
    #[arg(long)]
    json: bool,
    /// Draw RMSE per iteration into this .svg or .png.
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
    /// Sequence mode: odometry pose file (default: odometry.txt in the folder, or 3DTK .pose files beside the scans).
    #[arg(long, value_name = "FILE")]
    odometry: Option<PathBuf>,
    /// Sequence mode: ground-truth pose file to report errors against (default: poses.txt in the folder, if any).
    #[arg(long, value_name = "FILE")]
    truth: Option<PathBuf>,
    /// Sequence mode: output folder for poses.txt, map.pcd, registration.json and config.toml.
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    #[command(flatten)]
    read: ScanReadArgs,
}

/// Runs `semsim register`.
pub fn run(a: RegisterArgs, cfg: &Config, cfg_is_default: bool) -> anyhow::Result<()> {
    let mut cfg = cfg.clone();
    if let Some(m) = a.method {
        // Without a configuration file, `--method p2p` means the paper's setting (full resolution,
        // fixed 0.5 m gate); the other methods keep the defaults. A file's settings always win.
        if m == Method::PointToPoint && cfg_is_default {
            cfg.registration.icp = registration::IcpConfig::point_to_point();
        }
        cfg.registration.icp.method = m;
    }
    if let Some(d) = a.device {
        cfg.registration.icp.device = d;
    }
    if a.sequence {
        return run_sequence(&a, &cfg);
    }
    let [source_path, target_path] = a.inputs.as_slice() else {
        return Err(bad_input(format!(
            "pair mode takes exactly two scans (SOURCE TARGET), got {}; use --sequence for more",
            a.inputs.len()
        )));
    };
    let guess = match &a.guess {
        Some(g) => pipeline::parse_guess(g)?,
        None => DAffine3::IDENTITY,
    };
    let source = read_one(source_path, &a.read)?;
    let target = read_one(target_path, &a.read)?;
    let mut registrar = open_device(&cfg.registration.icp)?;
    let result = registrar.register(&source, &target, guess, &cfg.registration.icp);
    let result = match result {
        Ok(r) => r,
        Err(RegistrationError::NotConverged { result, reason }) => {
            if let Some(p) = &a.plot {
                pipeline::plot_rmse(p, &[("pair".into(), &result)])?;
            }
            anyhow::bail!(
                "ICP did not converge ({reason}) after {} iterations, RMSE {:.4} m, fitness {:.3}: no transform reported",
                result.iterations.len(),
                result.rmse_m,
                result.fitness
            );
        }
        Err(e) => {
            return Err(anyhow::Error::new(e).context(format!(
                "registering {} (source) onto {} (target)",
                source_path.display(),
                target_path.display()
            )))
        }
    };
    if let Some(p) = &a.plot {
        pipeline::plot_rmse(p, &[("pair".into(), &result)])?;
    }
    if a.json {
        let mut v = serde_json::to_value(pipeline::PairReport::of(&result))?;
        v["device"] = serde_json::Value::from(registrar.description());
        println!("{v}");
    } else {
        print_pair(&result);
    }
    Ok(())
}

/// Opens the configured device and says on stderr which it is (for `auto`: the adapter chosen,
/// or why the CPU runs instead). `device = gpu` without an adapter is bad input (exit 2).
fn open_device(icp: &registration::IcpConfig) -> anyhow::Result<Registrar> {
    let registrar = Registrar::new(icp)?;
    eprintln!("device: {}", registrar.description());
    Ok(registrar)
}

fn print_pair(r: &IcpResult) {
    println!("target_from_source =");
    let m = DMat4::from(r.target_from_source);
    for row in 0..4 {
        let v = m.row(row);
        println!("  {:>12.6} {:>12.6} {:>12.6} {:>12.6}", v.x, v.y, v.z, v.w);
    }
    let n = r.iterations.len();
    println!(
        "iterations: {n}, RMSE {:.4} m, fitness {:.3}, {:.2} ms per iteration, {:.1} ms total",
        r.rmse_m,
        r.fitness,
        r.total_ms / n.max(1) as f64,
        r.total_ms
    );
}

fn run_sequence(a: &RegisterArgs, cfg: &Config) -> anyhow::Result<()> {
    let out = a
        .out
        .clone()
        .ok_or_else(|| bad_input("--sequence needs --out DIR"))?;
    pipeline::check_output_dir(&out)?;
    let input = pipeline::read_sequence(
        &a.inputs,
        a.odometry.as_deref(),
        a.truth.as_deref(),
        &a.read.options(),
    )?;
    let outputs = ["poses.txt", "map.pcd", "registration.json", "config.toml"].map(|f| out.join(f));
    pipeline::refuse_overwriting_inputs(&outputs, &input.read)?;
    let scans = pipeline::read_scans_with(&input.scans, None, &cfg.outliers, &cfg.mixed_pixels)?;
    std::fs::create_dir_all(&out).map_err(|e| cloud::CloudError::io(&out, e))?;
    let mut registrar = open_device(&cfg.registration.icp)?;
    let bar = crate::progress::scan_bar(scans.len(), "registering");
    let mut reg = pipeline::register_scans(
        &input,
        &scans,
        &cfg.registration,
        &mut registrar,
        &mut |done, _| bar.set_position(done as u64),
    )?;
    bar.finish_and_clear();
    pipeline::clear_transients_from_map(&mut reg, &input, scans, &cfg.transients)?;
    pipeline::write_registration(&reg, &out)?;
    crate::print::registration(&reg);
    crate::print::registration_written(&reg, &out);
    if let Some(p) = &a.plot {
        let runs: Vec<(String, &IcpResult)> = reg
            .rows
            .iter()
            .zip(&reg.sequence.results)
            .filter_map(|(row, r)| r.as_ref().map(|r| (row.scan.clone(), r)))
            .collect();
        pipeline::plot_rmse(p, &runs)?;
    }
    cfg.write_beside(&out)?;
    Ok(())
}

/// One cloud of a pair (a multi-scan file merged by its scans' poses).
fn read_one(path: &std::path::Path, read: &ScanReadArgs) -> anyhow::Result<cloud::PointCloud> {
    let (cloud, notes) = interop::read_cloud(path, &read.options())?;
    cloud::io::print_notes(&notes);
    Ok(cloud)
}
