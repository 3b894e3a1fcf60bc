//! `semsim register`: ICP for a pair of scans, or a whole sequence against a growing map.

use crate::config::SemsimConfig;
use crate::exit::bad_input;
use crate::plot::{line_chart, Series};
use anyhow::Context;
use clap::Args;
use cloud::{NamedPose, PointCloud};
use glam::{DAffine3, DMat4, DQuat, DVec3, EulerRot};
use indicatif::{ProgressBar, ProgressStyle};
use registration::{Device, IcpResult, Method, Registrar, RegistrationError, SequenceConfig};
use std::path::{Path, PathBuf};

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
}

/// Runs `semsim register`.
pub fn run(a: RegisterArgs, cfg: &SemsimConfig, cfg_is_default: bool) -> anyhow::Result<()> {
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
        Some(g) => parse_guess(g)?,
        None => DAffine3::IDENTITY,
    };
    let source = cloud::read_cloud(source_path)?;
    let target = cloud::read_cloud(target_path)?;
    let mut registrar = open_device(&cfg.registration.icp)?;
    let result = registrar.register(&source, &target, guess, &cfg.registration.icp);
    let result = match result {
        Ok(r) => r,
        Err(RegistrationError::NotConverged { result, reason }) => {
            if let Some(p) = &a.plot {
                plot_rmse(p, &[("pair".into(), &result)])?;
            }
            anyhow::bail!(
                "ICP did not converge ({reason}) after {} iterations, RMSE {:.4} m, fitness {:.3}: no transform reported",
                result.iterations.len(),
                result.rmse_m,
                result.fitness
            );
        }
        Err(e) => return Err(e.into()),
    };
    if let Some(p) = &a.plot {
        plot_rmse(p, &[("pair".into(), &result)])?;
    }
    if a.json {
        let mut v = pair_json(&result);
        v["device"] = serde_json::Value::from(registrar.description());
        println!("{v}");
    } else {
        print_pair(&result);
    }
    Ok(())
}

/// Opens the configured device and says on stderr which it is (for `auto`: the adapter chosen,
/// or why the CPU runs instead). `device = gpu` without an adapter is bad input (exit 2).
pub fn open_device(icp: &registration::IcpConfig) -> anyhow::Result<Registrar> {
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

fn pair_json(r: &IcpResult) -> serde_json::Value {
    let m = DMat4::from(r.target_from_source)
        .transpose()
        .to_cols_array();
    let n = r.iterations.len();
    serde_json::json!({
        "transform": m.to_vec(),
        "iterations": n,
        "rmse_m": r.rmse_m,
        "fitness": r.fitness,
        "ms_per_iteration": r.total_ms / n.max(1) as f64,
        "total_ms": r.total_ms,
        "converged": r.converged,
    })
}

/// Parses `--guess`: a 4x4 matrix file (16 numbers) or `x,y,z,roll,pitch,yaw` in metres and degrees.
pub fn parse_guess(g: &str) -> anyhow::Result<DAffine3> {
    let path = Path::new(g);
    if path.is_file() {
        let text = std::fs::read_to_string(path).map_err(|e| cloud::CloudError::io(path, e))?;
        let numbers: Vec<f64> = text
            .split_whitespace()
            .map(|f| {
                f.parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| bad_input(format!("{g}: '{f}' is not a finite number")))
            })
            .collect::<anyhow::Result<_>>()?;
        let arr: [f64; 16] = numbers.as_slice().try_into().map_err(|_| {
            bad_input(format!(
                "{g}: a guess file holds 16 numbers (a row-major 4x4 matrix), found {}",
                numbers.len()
            ))
        })?;
        return Ok(cloud::affine_from_mat4(
            DMat4::from_cols_array(&arr).transpose(),
            path,
            1,
        )?);
    }
    let v: Vec<f64> = g
        .split(',')
        .map(|f| f.trim().parse::<f64>().unwrap_or(f64::NAN))
        .collect();
    match v.as_slice() {
        [x, y, z, roll, pitch, yaw] if v.iter().all(|x| x.is_finite()) => Ok(DAffine3::from_rotation_translation(
            DQuat::from_euler(EulerRot::ZYX, yaw.to_radians(), pitch.to_radians(), roll.to_radians()),
            DVec3::new(*x, *y, *z),
        )),
        _ => Err(bad_input(format!(
            "--guess '{g}': neither a file nor six finite numbers x,y,z,roll,pitch,yaw (metres, degrees)"
        ))),
    }
}

fn plot_rmse(path: &Path, runs: &[(String, &IcpResult)]) -> anyhow::Result<()> {
    let series: Vec<Series> = runs
        .iter()
        .map(|(name, r)| Series {
            name: name.clone(),
            points: r
                .iterations
                .iter()
                .map(|it| (it.iteration as f64, it.rmse_m))
                .collect(),
        })
        .collect();
    line_chart(path, "ICP convergence", "iteration", "RMSE (m)", &series)
}

/// The scans of a sequence, their odometry and (if known) their ground truth.
pub struct SequenceInput {
    /// Scan files in order.
    pub files: Vec<PathBuf>,
    /// Odometry `world_from_scan` per scan (empty if none).
    pub odometry: Vec<DAffine3>,
    /// Ground truth `world_from_scan` per scan (empty if none).
    pub truth: Vec<DAffine3>,
}

fn run_sequence(a: &RegisterArgs, cfg: &SemsimConfig) -> anyhow::Result<()> {
    let out = a
        .out
        .clone()
        .ok_or_else(|| bad_input("--sequence needs --out DIR"))?;
    let input = collect_sequence(&a.inputs, a.odometry.as_deref(), a.truth.as_deref())?;
    let scans = input
        .files
        .iter()
        .map(|f| cloud::read_cloud(f))
        .collect::<Result<Vec<PointCloud>, _>>()?;
    std::fs::create_dir_all(&out).map_err(|e| cloud::CloudError::io(&out, e))?;
    let report = register_and_write(&input, &scans, &cfg.registration, &out)?;
    if let Some(p) = &a.plot {
        let runs: Vec<(String, &IcpResult)> = report
            .iter()
            .flatten()
            .map(|(n, r)| (n.clone(), r))
            .collect();
        plot_rmse(p, &runs)?;
    }
    cfg.write_beside(&out)?;
    Ok(())
}

/// Registers the sequence, writes `poses.txt`, `map.pcd` and `registration.json`, prints a summary
/// (with errors against ground truth where known) and returns each scan's result.
pub fn register_and_write(
    input: &SequenceInput,
    scans: &[PointCloud],
    cfg: &SequenceConfig,
    out: &Path,
) -> anyhow::Result<Vec<Option<(String, IcpResult)>>> {
    let bar = ProgressBar::new(scans.len() as u64).with_style(
        ProgressStyle::with_template(
            "{msg:>10} [{bar:30}] {pos}/{len} scans, {elapsed} (eta {eta})",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar())
        .progress_chars("=> "),
    );
    let mut registrar = open_device(&cfg.icp)?;
    bar.set_message("registering");
    let seq = registration::register_sequence_with(
        &mut registrar,
        scans,
        &input.odometry,
        cfg,
        &mut |done, _| bar.set_position(done as u64),
    )
    .context("registering the sequence")?;
    bar.finish_and_clear();
    let names: Vec<String> = input
        .files
        .iter()
        .map(|f| {
            f.file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default()
        })
        .collect();
    let poses: Vec<NamedPose> = names
        .iter()
        .zip(&seq.world_from_scan)
        .map(|(name, p)| NamedPose {
            name: name.clone(),
            world_from_scan: *p,
        })
        .collect();
    cloud::write_poses(&out.join("poses.txt"), &poses)?;
    cloud::write_cloud_as(
        &out.join("map.pcd"),
        &seq.map,
        cloud::CloudFormat::Pcd(cloud::PcdEncoding::BinaryCompressed),
    )?;
    let mut rows = Vec::new();
    println!(
        "{:<10} {:>5} {:>10} {:>8} {:>9} {:>10} {:>10}",
        "scan", "iters", "RMSE m", "fitness", "ms", "err m", "err deg"
    );
    for (k, name) in names.iter().enumerate() {
        let r = seq.results.get(k).and_then(|r| r.as_ref());
        let err = input.truth.get(k).map(|t| {
            pose_error(
                &relative(&input.truth, k, t),
                &relative(&seq.world_from_scan, k, &seq.world_from_scan[k]),
            )
        });
        let (it, rmse, fit, ms) = r.map_or((0, 0.0, 1.0, 0.0), |r| {
            (r.iterations.len(), r.rmse_m, r.fitness, r.total_ms)
        });
        let (e_m, e_deg) = err.unwrap_or((f64::NAN, f64::NAN));
        println!("{name:<10} {it:>5} {rmse:>10.4} {fit:>8.3} {ms:>9.1} {e_m:>10.4} {e_deg:>10.3}");
        rows.push(serde_json::json!({
            "scan": name, "iterations": it, "rmse_m": rmse, "fitness": fit, "total_ms": ms,
            "error_m": err.map(|e| e.0), "error_deg": err.map(|e| e.1),
        }));
    }
    let json = serde_json::to_string_pretty(&rows).context("serialising the report")?;
    cloud::write_bytes_atomically(&out.join("registration.json"), json.as_bytes())?;
    println!(
        "wrote {}/poses.txt, map.pcd ({} points), registration.json",
        out.display(),
        seq.map.len()
    );
    Ok(seq
        .results
        .into_iter()
        .zip(names)
        .map(|(r, n)| r.map(|r| (n, r)))
        .collect())
}

/// Pose relative to the first of its sequence (registration fixes scan 0 to its odometry, truth may differ).
fn relative(all: &[DAffine3], _k: usize, p: &DAffine3) -> DAffine3 {
    all.first().map_or(*p, |first| first.inverse() * *p)
}

/// Translation (m) and rotation (deg) difference between two poses.
pub fn pose_error(a: &DAffine3, b: &DAffine3) -> (f64, f64) {
    let d = a.inverse() * *b;
    let angle = DQuat::from_mat3(&d.matrix3)
        .angle_between(DQuat::IDENTITY)
        .to_degrees();
    (d.translation.length(), angle)
}

/// Expands folders into scan files and finds odometry and ground truth.
pub fn collect_sequence(
    inputs: &[PathBuf],
    odometry: Option<&Path>,
    truth: Option<&Path>,
) -> anyhow::Result<SequenceInput> {
    let mut files = Vec::new();
    let mut folder = None;
    for i in inputs {
        if i.is_dir() {
            folder.get_or_insert(i.clone());
            let mut in_dir: Vec<PathBuf> = std::fs::read_dir(i)
                .map_err(|e| cloud::CloudError::io(i, e))?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| is_scan_file(p))
                .collect();
            in_dir.sort();
            files.extend(in_dir);
        } else if i.is_file() {
            files.push(i.clone());
        } else {
            return Err(cloud::CloudError::io(
                i,
                std::io::Error::new(std::io::ErrorKind::NotFound, "no such file or folder"),
            )
            .into());
        }
    }
    if files.len() < 2 {
        return Err(bad_input(format!(
            "a sequence needs at least two scans, found {}",
            files.len()
        )));
    }
    let odometry = match (odometry, &folder) {
        (Some(p), _) => poses_for(&files, &cloud::read_poses(p)?, p)?,
        (None, Some(dir)) if dir.join("odometry.txt").is_file() => {
            let p = dir.join("odometry.txt");
            poses_for(&files, &cloud::read_poses(&p)?, &p)?
        }
        _ if files.iter().all(|f| f.with_extension("pose").is_file()) => files
            .iter()
            .map(|f| cloud::io::threedtk::read_pose_3dtk(&f.with_extension("pose")))
            .collect::<Result<_, _>>()?,
        _ => Vec::new(),
    };
    let truth = match (truth, &folder) {
        (Some(p), _) => poses_for(&files, &cloud::read_poses(p)?, p)?,
        (None, Some(dir)) if dir.join("poses.txt").is_file() => {
            let p = dir.join("poses.txt");
            poses_for(&files, &cloud::read_poses(&p)?, &p)?
        }
        _ => Vec::new(),
    };
    Ok(SequenceInput {
        files,
        odometry,
        truth,
    })
}

fn is_scan_file(p: &Path) -> bool {
    let ext = p
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    let stem = p
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    matches!(ext.as_str(), "pcd" | "ply" | "3d" | "xyz") && stem != "map" && stem != "labels"
}

/// Picks the pose of each scan by name from a pose file.
fn poses_for(files: &[PathBuf], poses: &[NamedPose], path: &Path) -> anyhow::Result<Vec<DAffine3>> {
    files
        .iter()
        .map(|f| {
            let stem = f
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default();
            poses
                .iter()
                .find(|p| p.name == stem)
                .map(|p| p.world_from_scan)
                .ok_or_else(|| bad_input(format!("{}: no pose for scan '{stem}'", path.display())))
        })
        .collect()
}
