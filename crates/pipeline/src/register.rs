//! The registration stage of the chain: a sequence of scans registered one after another
//! against the growing map, each scan scored against ground truth where it is known.

use crate::error::{to_json, Result};
use crate::scan_folder::{ScanSource, SequenceInput};
use crate::scans::{place_scans, report_transients};
use crate::truth::relative_pose_errors;
use cloud::{NamedPose, PointCloud};
use glam::Vec3;
use registration::TransientConfig;
use registration::{
    CheckedEnd, CorrectionCheck, IcpResult, Registrar, SequenceConfig, SequenceResult,
};
use serde::Serialize;
use std::collections::HashSet;
use std::path::Path;

/// A registered sequence: the result and one row per scan.
#[derive(Debug, Clone)]
pub struct Registration {
    /// Each scan's registered pose, by name (`poses.txt`).
    pub poses: Vec<NamedPose>,
    /// The registration itself (the merged map, each scan's ICP result).
    pub sequence: SequenceResult,
    /// One row per scan (`registration.json`).
    pub rows: Vec<ScanRow>,
    /// The device ICP ran on, in words.
    pub device: String,
}

/// One scan's registration, scored against the truth where it is known.
#[derive(Debug, Clone, Serialize)]
pub struct ScanRow {
    /// The scan's name.
    pub scan: String,
    /// ICP iterations (0 for scan 0, which defines the world).
    pub iterations: usize,
    /// Final RMSE of the pairs.
    pub rmse_m: f64,
    /// Fraction of the source paired.
    pub fitness: f64,
    /// Time spent on the scan.
    pub total_ms: f64,
    /// Translation error against the truth (relative to scan 0).
    pub error_m: Option<f64>,
    /// Rotation error against the truth (relative to scan 0).
    pub error_deg: Option<f64>,
    /// The check of a long correction from the odometry (only where one ran).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub correction_check: Option<CorrectionCheck>,
}

/// Opens the configured device (for `auto`: a hardware GPU if there is one, else the CPU).
pub fn open_registrar(cfg: &SequenceConfig) -> Result<Registrar> {
    Ok(Registrar::new(&cfg.icp)?)
}

/// Registers the scans of `input` (already read) from its odometry; `progress(done, total)`
/// after each scan.
pub fn register_scans(
    input: &SequenceInput,
    scans: &[PointCloud],
    cfg: &SequenceConfig,
    registrar: &mut Registrar,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Registration> {
    // 1. Each scan against the map of the scans before it, from the odometry.
    let sequence =
        registration::register_sequence_with(registrar, scans, &input.odometry, cfg, progress)?;
    // 2. Name the poses after the scans.
    let names = input.names();
    let poses: Vec<NamedPose> = names
        .iter()
        .zip(&sequence.world_from_scan)
        .map(|(name, p)| NamedPose {
            name: name.clone(),
            world_from_scan: *p,
        })
        .collect();
    // 3. Score each scan against the truth, where it is known.
    let errors = relative_pose_errors(&input.truth, &sequence.world_from_scan);
    let rows = names
        .iter()
        .enumerate()
        .map(|(k, name)| {
            let check = sequence.corrections_checked.get(k).and_then(Clone::clone);
            scan_row(
                name,
                sequence.results.get(k).and_then(|r| r.as_ref()),
                errors.get(k),
                check,
            )
        })
        .collect();
    report_checks(&input.scans, &sequence.corrections_checked);
    Ok(Registration {
        poses,
        sequence,
        rows,
        device: registrar.description().to_string(),
    })
}

/// Says on stderr where a long correction's check kept another end than the ICP's.
fn report_checks(sources: &[ScanSource], checks: &[Option<CorrectionCheck>]) {
    for (f, c) in sources.iter().zip(checks) {
        let Some(c) = c.as_ref() else {
            continue;
        };
        let (how, moved_m) = match c.kept {
            CheckedEnd::Icp => continue,
            CheckedEnd::Narrow => ("registered again with a narrow gate", c.narrow_correction_m),
            CheckedEnd::Searched => (
                "registered again from a search of every yaw and position",
                c.searched_correction_m,
            ),
        };
        eprintln!(
            "note: {} ({}): ICP from the odometry moved the scan {:.2} m; {how} it ended {:.2} m from the odometry, which what both sides saw supports better: kept",
            f.file.display(),
            f.name,
            c.correction_m,
            moved_m.unwrap_or(f64::NAN)
        );
    }
}

fn scan_row(
    name: &str,
    r: Option<&IcpResult>,
    err: Option<&(f64, f64)>,
    correction_check: Option<CorrectionCheck>,
) -> ScanRow {
    let (iterations, rmse_m, fitness, total_ms) = r.map_or((0, 0.0, 1.0, 0.0), |r| {
        (r.iterations.len(), r.rmse_m, r.fitness, r.total_ms)
    });
    ScanRow {
        scan: name.to_string(),
        iterations,
        rmse_m,
        fitness,
        total_ms,
        error_m: err.map(|e| e.0),
        error_deg: err.map(|e| e.1),
        correction_check,
    }
}

/// Takes out of the registration's map (the growing map the scans were registered against)
/// what moved between the scans: the scans placed at their registered poses vote
/// ([`crate::find_transients`]), and a map point goes where its 10 cm cell
/// holds transient points and no other (the map keeps its density elsewhere). This is the
/// map `register` writes.
pub fn clear_transients_from_map(
    reg: &mut Registration,
    input: &SequenceInput,
    scans: Vec<PointCloud>,
    transients: &TransientConfig,
) -> Result<()> {
    let keep_all = TransientConfig {
        enabled: false,
        ..transients.clone()
    };
    let placed = place_scans(&input.scans, scans, Some(&reg.poses), &keep_all)?;
    let found = crate::find_transients(&placed, transients);
    let counts: Vec<usize> = found.iter().map(Vec::len).collect();
    report_transients(&input.scans, &counts);
    if counts.iter().all(|&n| n == 0) {
        return Ok(());
    }
    let cell = |p: Vec3| (p / TRANSIENT_CELL_M).floor().as_ivec3();
    let mut moved = HashSet::new();
    for (scan, gone) in placed.iter().zip(&found) {
        moved.extend(gone.iter().map(|&i| cell(scan.points[i])));
    }
    for (scan, gone) in placed.iter().zip(&found) {
        let mut gone = gone.iter().peekable();
        for (i, p) in scan.points.iter().enumerate() {
            if gone.peek() == Some(&&i) {
                gone.next();
            } else if p.is_finite() {
                moved.remove(&cell(*p));
            }
        }
    }
    let keep: Vec<usize> = (0..reg.sequence.map.len())
        .filter(|&i| !moved.contains(&cell(reg.sequence.map.points[i])))
        .collect();
    reg.sequence.map = reg.sequence.map.select(&keep);
    Ok(())
}

/// The cells in which [`clear_transients_from_map`] compares transient and other points:
/// twice the map's default voxel, so that a map point (a voxel's centroid) lies in the cell
/// of the points it stands for.
const TRANSIENT_CELL_M: f32 = 0.1;

/// Writes `poses.txt`, `map.pcd` and `registration.json` into `out` (which must exist).
pub fn write_registration(reg: &Registration, out: &Path) -> Result<()> {
    cloud::write_poses(&out.join("poses.txt"), &reg.poses)?;
    cloud::write_cloud_as(
        &out.join("map.pcd"),
        &reg.sequence.map,
        cloud::CloudFormat::Pcd(cloud::PcdEncoding::BinaryCompressed),
    )?;
    let json = to_json("the registration report", &reg.rows)?;
    cloud::write_bytes_atomically(&out.join("registration.json"), json.as_bytes())?;
    Ok(())
}

/// A pair registration as `semsim register --json` prints it: the row-major 4x4
/// `target_from_source` as 16 numbers and the run's figures.
#[derive(Debug, Clone, Serialize)]
pub struct PairReport {
    /// `target_from_source`, row-major.
    pub transform: Vec<f64>,
    /// ICP iterations.
    pub iterations: usize,
    /// Final RMSE of the pairs.
    pub rmse_m: f64,
    /// Fraction of the source paired.
    pub fitness: f64,
    /// Mean time per iteration.
    pub ms_per_iteration: f64,
    /// Time in all.
    pub total_ms: f64,
    /// Whether the stop criteria were met.
    pub converged: bool,
}

impl PairReport {
    /// The report of a result.
    pub fn of(r: &IcpResult) -> PairReport {
        let n = r.iterations.len();
        PairReport {
            transform: glam::DMat4::from(r.target_from_source)
                .transpose()
                .to_cols_array()
                .to_vec(),
            iterations: n,
            rmse_m: r.rmse_m,
            fitness: r.fitness,
            ms_per_iteration: r.total_ms / n.max(1) as f64,
            total_ms: r.total_ms,
            converged: r.converged,
        }
    }
}
