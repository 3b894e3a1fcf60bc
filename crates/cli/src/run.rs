//! `semsim run`: one command from scans to a verdict: registration, the semantic map, and a
//! judged simulation in the map's world.

use crate::config::SemsimConfig;
use clap::Args;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `semsim run`.
#[derive(Args)]
pub struct RunArgs {
    /// The scans, in order (files, or a folder of them).
    #[arg(required = true, value_name = "SCANS")]
    inputs: Vec<PathBuf>,
    /// Odometry pose file (default: odometry.txt in the folder, or 3DTK .pose files).
    #[arg(long, value_name = "FILE")]
    odometry: Option<PathBuf>,
    /// The scenario (TOML); default: the built-in default scenario. Its coordinates are in
    /// the registered world (scan 0's frame, levelled).
    #[arg(long, value_name = "FILE")]
    scenario: Option<PathBuf>,
    /// Drop points farther than this from their scan's sensor before registering.
    #[arg(long, value_name = "M")]
    max_range_m: Option<f64>,
    /// Output folder: registration/, map/, simulation/.
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
}

/// Runs `semsim run`; exit 0 on a passed verdict, 1 on a failed one.
pub fn run(a: RunArgs, cfg: &SemsimConfig) -> anyhow::Result<()> {
    if let Some(r) = a.max_range_m {
        if !(r.is_finite() && r > 0.0) {
            return Err(crate::exit::bad_input(format!(
                "--max-range-m {r}: must be a positive length"
            )));
        }
    }
    // Load the scenario first: a bad scenario should fail before minutes of work.
    let (scenario, text, base) = crate::simulate::load_scenario(a.scenario.as_deref())?;
    let input = crate::register::collect_sequence(&a.inputs, a.odometry.as_deref(), None)?;
    let scans = crate::map::read_scans(&input.files, a.max_range_m)?;
    let outcome = scans_to_verdict(&input, scans, (&scenario, &text, &base), cfg, &a.out)?;
    crate::simulate::verdict(outcome.passed, &a.out.join("simulation"))
}

/// What [`scans_to_verdict`] made.
pub struct Outcome {
    /// Whether the scenario's verdict passed.
    pub passed: bool,
    /// The semantic map.
    pub map: semantic::SemanticMap,
    /// The registered scans, merged (the map's input).
    pub cloud: cloud::PointCloud,
}

/// Registration into `out/registration`, the semantic map into `out/map`, and the scenario
/// judged in the map's world into `out/simulation`.
pub fn scans_to_verdict(
    input: &crate::register::SequenceInput,
    scans: Vec<cloud::PointCloud>,
    (scenario, text, base): (&sim::Scenario, &str, &Path),
    cfg: &SemsimConfig,
    out: &Path,
) -> anyhow::Result<Outcome> {
    let t0 = Instant::now();
    let reg_dir = out.join("registration");
    std::fs::create_dir_all(&reg_dir).map_err(|e| cloud::CloudError::io(&reg_dir, e))?;
    println!(
        "1/3 registration ({}) of {} scans:",
        cfg.registration.icp.method.short_name(),
        scans.len()
    );
    crate::register::register_and_write(input, &scans, &cfg.registration, &reg_dir)?;
    cfg.write_beside(&reg_dir)?;
    let poses = cloud::read_poses(&reg_dir.join("poses.txt"))?;
    println!("2/3 semantic map of the registered scans:");
    let merged = crate::map::place_and_merge(&input.files, scans, Some(&poses))?;
    let map = crate::map::map_and_write(&merged, cfg, &out.join("map"))?;
    println!("{}", crate::map::summary(&map));
    println!(
        "3/3 simulation of \"{}\" in the map's world:",
        scenario.name
    );
    let spec = sim::WorldSpec::from_semantic_map(&map)?;
    let passed = crate::simulate::simulate(&spec, scenario, text, base, &out.join("simulation"))?;
    println!("scans to verdict in {:.1} s", t0.elapsed().as_secs_f64());
    Ok(Outcome {
        passed,
        map,
        cloud: merged,
    })
}
