//! The demo: the whole chain on the built-in default building, scored against its ground
//! truth at every stage. [`prepare_demo`] makes the scans, [`crate::scans_to_verdict`] runs the
//! chain on them, [`score_demo`] scores the result.

use crate::chain::{create_dir, ChainOutcome};
use crate::config::Config;
use crate::error::Result;
use crate::scan_folder::{read_sequence, write_scan_folder, ScanFolderSummary, SequenceInput};
use crate::scans::read_scans;
use crate::truth::worst_pose_error;
use cloud::PointCloud;
use glam::DAffine3;
use scanner::Building;
use std::path::{Path, PathBuf};

/// The demo's input: the building, its scans and the sequence read back from them.
#[derive(Debug)]
pub struct DemoScans {
    /// The built-in default building.
    pub building: Building,
    /// Where its description was written (`building.toml`).
    pub building_file: PathBuf,
    /// What scanning wrote.
    pub scanned: ScanFolderSummary,
    /// The sequence: scan files, odometry, ground truth.
    pub input: SequenceInput,
    /// The scans, read (missing returns dropped).
    pub scans: Vec<PointCloud>,
}

/// The demo's scores against ground truth.
#[derive(Debug, Clone)]
pub struct DemoScore {
    /// Worst pose error of the odometry (metres, degrees).
    pub odometry_error: (f64, f64),
    /// Worst pose error of the registration (metres, degrees).
    pub registered_error: (f64, f64),
    /// The semantic map against the building.
    pub map: evaluate::Evaluation,
}

/// Writes the default building into `out` and scans it from its survey poses (a scan folder);
/// `progress(done, total)` after each scan.
pub fn prepare_demo(
    out: &Path,
    cfg: &Config,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<DemoScans> {
    // 1. The building, written beside its scans.
    let building = Building::default_building()?;
    create_dir(out)?;
    let building_file = out.join("building.toml");
    building.save(&building_file)?;
    // 2. Virtual scans from the surveyor's poses, with ground truth and noisy odometry.
    let scanned = write_scan_folder(
        &building,
        &Building::default_survey_poses(),
        cfg,
        out,
        progress,
    )?;
    // 3. The scan folder read back as any user's sequence would be.
    let input = read_sequence(&[out.to_path_buf()], None, None, &Default::default())?;
    let scans = read_scans(&input.scans, None)?;
    Ok(DemoScans {
        building,
        building_file,
        scanned,
        input,
        scans,
    })
}

/// Scores the chain's registration and semantic map against the demo building's truth.
pub fn score_demo(demo: &DemoScans, chain: &ChainOutcome) -> DemoScore {
    let registered: Vec<DAffine3> = chain
        .registration
        .poses
        .iter()
        .map(|p| p.world_from_scan)
        .collect();
    DemoScore {
        odometry_error: worst_pose_error(&demo.input.truth, &demo.input.odometry),
        registered_error: worst_pose_error(&demo.input.truth, &registered),
        map: evaluate::evaluate(&chain.map.map, &demo.building, Some(&chain.cloud)),
    }
}
