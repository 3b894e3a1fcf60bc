//! `semsim simulate`: a scenario run headless in a rapier3d world, judged and reported. The
//! world comes from a semantic map (`--map`, the map made from scans) or from a building
//! description (ground truth).

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
    /// A semantic map (semantic_map.json, from `semsim map`): the world is built from its
    /// entities (overrides --building and the scenario's `building`).
    #[arg(long, value_name = "FILE", conflicts_with = "building")]
    map: Option<PathBuf>,
    /// Output folder for events.jsonl, trajectory.csv, report.md and scenario.toml.
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
}

/// Runs `semsim simulate`; exit 0 on a passed verdict, 1 on a failed one.
pub fn run(a: SimulateArgs) -> anyhow::Result<()> {
    let (scenario, text, base) = load_scenario(a.scenario.as_deref())?;
    let spec = match &a.map {
        Some(m) => WorldSpec::from_semantic_map(&semantic::SemanticMap::load(m)?)?,
        None => {
            let building = match (&a.building, scenario.building.as_str()) {
                (Some(p), _) => Building::load(p)?,
                (None, "default" | "") => Building::default_building()?,
                (None, other) => Building::load(&base.join(other))?,
            };
            WorldSpec::from_building(&building)?
        }
    };
    let passed = simulate(&spec, &scenario, &text, &base, &a.out)?;
    verdict(passed, &a.out)
}

/// `Ok` for a passed verdict; an error (exit 1) naming the report for a failed one.
pub fn verdict(passed: bool, out: &Path) -> anyhow::Result<()> {
    if !passed {
        anyhow::bail!("verdict: FAILED (see {})", out.join("report.md").display());
    }
    println!("verdict: PASSED");
    Ok(())
}

/// The scenario (default: the built-in one), its text and the folder its paths are relative to.
pub fn load_scenario(path: Option<&Path>) -> anyhow::Result<(Scenario, String, PathBuf)> {
    Ok(match path {
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
    })
}

/// Simulates, writes the outputs and the scenario beside them, prints the timeline and verdict.
pub fn simulate(
    spec: &WorldSpec,
    scenario: &Scenario,
    scenario_text: &str,
    base: &Path,
    out: &Path,
) -> anyhow::Result<bool> {
    let model = scenario.robot_model(base)?;
    std::fs::create_dir_all(out).map_err(|e| cloud::CloudError::io(out, e))?;
    let outcome = sim::run_scenario(spec, scenario, &model)?;
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
