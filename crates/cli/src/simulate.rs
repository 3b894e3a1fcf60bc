//! `semsim simulate`: a scenario run headless in a rapier3d world, judged and reported.
//! Today the world comes from a building description (ground truth); building it from a
//! semantic map arrives with the semantic-map stage.

use crate::exit::bad_input;
use clap::Args;
use scanner::Building;
use sim::{ReportConfig, Scenario, WorldSpec};
use std::path::{Path, PathBuf};

/// Arguments of `semsim simulate`.
#[derive(Args)]
pub struct SimulateArgs {
    /// The scenario (TOML); default: the built-in default scenario.
    #[arg(long, value_name = "FILE")]
    scenario: Option<PathBuf>,
    /// The building to simulate (TOML/JSON); default: the scenario's `building` ("default" = built-in).
    #[arg(long, value_name = "FILE")]
    building: Option<PathBuf>,
    /// A semantic map (semantic_map.json): not supported yet in this build.
    #[arg(long, value_name = "FILE")]
    map: Option<PathBuf>,
    /// Output folder for events.jsonl, trajectory.csv, report.md and scenario.toml.
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
}

/// Runs `semsim simulate`; exit 0 on a passed verdict, 1 on a failed one.
pub fn run(a: SimulateArgs) -> anyhow::Result<()> {
    if let Some(m) = &a.map {
        return Err(bad_input(format!(
            "{}: simulating from a semantic map is not available yet; use --building",
            m.display()
        )));
    }
    let (scenario, text, base) = match &a.scenario {
        Some(p) => {
            let text = std::fs::read_to_string(p).map_err(|e| cloud::CloudError::io(p, e))?;
            (
                Scenario::load(p)?,
                text,
                p.parent().map(Path::to_path_buf).unwrap_or_default(),
            )
        }
        None => (
            Scenario::default_scenario()?,
            Scenario::default_scenario_toml().to_string(),
            PathBuf::from("."),
        ),
    };
    let building = match (&a.building, scenario.building.as_str()) {
        (Some(p), _) => Building::load(p)?,
        (None, "default" | "") => Building::default_building()?,
        (None, other) => Building::load(&base.join(other))?,
    };
    let passed = simulate(&building, &scenario, &text, &base, &a.out)?;
    if !passed {
        anyhow::bail!(
            "verdict: FAILED (see {})",
            a.out.join("report.md").display()
        );
    }
    Ok(())
}

/// Simulates, writes the outputs and the scenario beside them, prints the timeline and verdict.
pub fn simulate(
    building: &Building,
    scenario: &Scenario,
    scenario_text: &str,
    base: &Path,
    out: &Path,
) -> anyhow::Result<bool> {
    let spec = WorldSpec::from_building(building)?;
    let model = scenario.robot_model(base)?;
    std::fs::create_dir_all(out).map_err(|e| cloud::CloudError::io(out, e))?;
    let outcome = sim::run_scenario(&spec, scenario, &model)?;
    sim::write_outputs(out, &outcome, &ReportConfig::default())?;
    cloud::write_bytes_atomically(&out.join("scenario.toml"), scenario_text.as_bytes())?;
    let report = sim::report_markdown(&outcome, &ReportConfig::default());
    println!("{report}");
    println!(
        "wrote {}/events.jsonl, trajectory.csv, report.md, scenario.toml",
        out.display()
    );
    Ok(outcome.verdict.passed)
}
