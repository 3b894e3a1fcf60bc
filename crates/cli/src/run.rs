//! `semsim run`: one command from scans to a verdict: registration, the semantic map, and a
//! judged simulation in the map's world.

use crate::scan_input::ScanReadArgs;
use clap::Args;
use pipeline::{read_scan_set, scans_to_verdict, Config, ScenarioChoice};
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `semsim run`.
#[derive(Args)]
pub struct RunArgs {
    /// The scans, in order (files, or a folder of them; one .e57 or .mcap holding several). One
    /// scan, or one cloud registered already, is mapped as it stands.
    #[arg(required = true, value_name = "SCANS")]
    inputs: Vec<PathBuf>,
    /// Odometry pose file (default: odometry.txt in the folder, or 3DTK .pose files).
    #[arg(long, value_name = "FILE")]
    odometry: Option<PathBuf>,
    /// The scenario (TOML). Its coordinates are in the registered world (scan 0's frame,
    /// levelled). Without one, a scenario is planned in the map's world from where scan 0's
    /// sensor stood: a tour through every reachable door opening and up every staircase and
    /// ramp the robot (`[plan] robot` of --config, default pioneer3at) can climb, with no wall contact
    /// over 0.5 s and no tipping; it is written as simulation/scenario.toml, and what the
    /// tour cannot reach is listed in report.md.
    #[arg(long, value_name = "FILE")]
    scenario: Option<PathBuf>,
    /// Drop points farther than this from their scan's sensor before registering.
    #[arg(long, value_name = "M")]
    max_range_m: Option<f64>,
    /// Output folder: registration/, map/, simulation/.
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    #[command(flatten)]
    read: ScanReadArgs,
}

/// Runs `semsim run`; exit 0 on a passed verdict, 1 on a failed one.
pub fn run(a: RunArgs, cfg: &Config) -> anyhow::Result<()> {
    let t0 = Instant::now();
    // The scenario and the output folder first: they should fail before minutes of work.
    pipeline::check_output_dir(&a.out)?;
    let scenario = ScenarioChoice::from_file_or_plan(a.scenario.as_deref(), &cfg.plan)?;
    let input = read_scan_set(&a.inputs, a.odometry.as_deref(), None, &a.read.options())?;
    let scans = pipeline::read_scans_with(
        &input.scans,
        a.max_range_m,
        &cfg.outliers,
        &cfg.mixed_pixels,
    )?;
    crate::interrupt::install();
    let mut printer = crate::print::Printer::default();
    let outcome = scans_to_verdict(&input, scans, &scenario, cfg, &a.out, &mut printer)?;
    if let Some(p) = &outcome.scenario.planned {
        println!("{}", p.summary());
    }
    println!("scans to verdict in {:.1} s", t0.elapsed().as_secs_f64());
    crate::print::verdict(&outcome.simulation, &a.out.join("simulation"))
}
