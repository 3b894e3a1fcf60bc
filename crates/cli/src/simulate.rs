//! `semsim simulate`: a scenario run headless in a rapier3d world, judged and reported. The
//! world comes from a semantic map (`--map`, the map made from scans) or from a building
//! description (ground truth). With `--replay commands.jsonl` an operator's console session
//! is run again from its command log.

use clap::Args;
use pipeline::{simulate, write_simulation, Config, Observer};
use std::path::PathBuf;

/// Arguments of `semsim simulate`.
#[derive(Args)]
pub struct SimulateArgs {
    /// The scenario (TOML). Without one: with --map, a scenario is planned in the map's world
    /// (a tour through every reachable door opening and up every staircase and ramp the
    /// robot, `[plan] robot` of --config, can climb; it starts at the free spot nearest the middle of the
    /// largest free region); likewise with --building; with neither, the built-in default
    /// scenario in the built-in building (it names that building's door and stairs).
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
    /// Output folder for events.jsonl, trajectory.csv, doors.csv, report.md and scenario.toml.
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
}

/// Runs `semsim simulate`; exit 0 on a passed verdict, 1 on a failed one.
pub fn run(a: SimulateArgs, cfg: &Config) -> anyhow::Result<()> {
    pipeline::check_output_dir(&a.out)?;
    let (world, source) = pipeline::world_and_scenario(
        a.map.as_deref(),
        a.scenario.as_deref(),
        a.building.as_deref(),
        &cfg.plan,
    )?;
    if let Some(p) = &source.planned {
        println!("{}", p.summary());
    }
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
