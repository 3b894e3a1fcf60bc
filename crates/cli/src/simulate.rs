//! `semsim simulate`: a scenario run headless in a rapier3d world, judged and reported. The
//! world comes from a semantic map (`--map`, the map made from scans) or from a building
//! description (ground truth). With `--replay commands.jsonl` an operator's console session
//! is run again from its command log.

use clap::Args;
use pipeline::{simulate, write_simulation, Observer, ScenarioSource};
use sim::WorldSpec;
use std::path::PathBuf;

/// Arguments of `semsim simulate`.
#[derive(Args)]
pub struct SimulateArgs {
    /// The scenario (TOML); default: the built-in default scenario.
    #[arg(long, value_name = "FILE")]
    scenario: Option<PathBuf>,
    /// The building to simulate (TOML/JSON); default: the scenario's `building` ("default" = built-in).
    #[arg(long, value_name = "FILE")]
    building: Option<PathBuf>,
    /// A semantic map (semantic_map.json, from `semsim map`): the world is built from its
    /// entities (overrides --building and the scenario's `building`).
    #[arg(long, value_name = "FILE", conflicts_with = "building")]
    map: Option<PathBuf>,
    /// Replay an operator's session: apply its command log (commands.jsonl, from a
    /// `semsim console` run folder) at the same steps; with the session's scenario and world
    /// the events are the session's, bit for bit.
    #[arg(long, value_name = "FILE")]
    replay: Option<PathBuf>,
    /// Output folder for events.jsonl, trajectory.csv, report.md and scenario.toml.
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
}

/// Runs `semsim simulate`; exit 0 on a passed verdict, 1 on a failed one.
pub fn run(a: SimulateArgs) -> anyhow::Result<()> {
    pipeline::check_output_dir(&a.out)?;
    let source = ScenarioSource::load(a.scenario.as_deref())?;
    let world = match &a.map {
        Some(m) => WorldSpec::from_semantic_map_file(m)?,
        None => WorldSpec::from_building(&source.building(a.building.as_deref())?)?,
    };
    let log = match &a.replay {
        Some(path) => Some(console::CommandLog::load(path)?),
        None => None,
    };
    let outcome = match &log {
        Some(log) => console::replay(&world, &source.scenario, &source.robot, log)?,
        None => {
            crate::interrupt::install();
            let mut printer = crate::print::Printer::default();
            let limit_s = source.scenario.time_limit_s;
            let outcome = simulate(&world, &source, &mut |t| printer.simulating(t, limit_s))?;
            printer.clear();
            outcome
        }
    };
    std::fs::create_dir_all(&a.out).map_err(|e| cloud::CloudError::io(&a.out, e))?;
    let report = write_simulation(&outcome, &source, &a.out)?;
    println!("{report}");
    crate::print::simulation_written(&a.out);
    crate::print::verdict(&outcome, &a.out)
}
