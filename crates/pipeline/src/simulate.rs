//! The simulation stage of the chain: a scenario (from a file or the built-in one) run in
//! the world of a semantic map or of a building, judged, and its files.

use crate::error::Result;
use scanner::Building;
use sim::{Outcome, ReportConfig, RobotModel, Scenario, WorldSpec};
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};

/// A scenario with its text (written beside the outputs) and the folder its relative paths
/// (robot files, buildings) are read from.
#[derive(Debug, Clone)]
pub struct ScenarioSource {
    /// The scenario.
    pub scenario: Scenario,
    /// Its TOML text, as given.
    pub text: String,
    /// The folder its relative paths start from.
    pub base_dir: PathBuf,
    /// The robot it drives (loaded with the scenario, so a bad robot file fails before any work).
    pub robot: RobotModel,
}

impl ScenarioSource {
    /// The scenario of a file, or the built-in default scenario for `None`.
    pub fn load(path: Option<&Path>) -> Result<ScenarioSource> {
        let (scenario, text, base_dir) = match path {
            Some(p) => (
                Scenario::load(p)?,
                std::fs::read_to_string(p).map_err(|e| cloud::CloudError::io(p, e))?,
                p.parent().map(Path::to_path_buf).unwrap_or_default(),
            ),
            None => (
                Scenario::default_scenario()?,
                Scenario::default_scenario_toml().to_string(),
                PathBuf::from("."),
            ),
        };
        let robot = scenario.robot_model(&base_dir)?;
        Ok(ScenarioSource {
            scenario,
            text,
            base_dir,
            robot,
        })
    }

    /// The building the scenario names (`building`, relative to its folder; "default" or
    /// nothing for the built-in one), unless `explicit` is given.
    pub fn building(&self, explicit: Option<&Path>) -> Result<Building> {
        Ok(match (explicit, self.scenario.building.as_str()) {
            (Some(p), _) => Building::load(p)?,
            (None, "default" | "") => Building::default_building()?,
            (None, other) => Building::load(&self.base_dir.join(other))?,
        })
    }
}

/// Runs the scenario in `world` and judges it. `progress(sim_time_s)` is called every few
/// steps; returning `ControlFlow::Break` stops the run cleanly (Ctrl-C): the outcome keeps the
/// events so far and its verdict says it was interrupted.
pub fn simulate(
    world: &WorldSpec,
    source: &ScenarioSource,
    progress: &mut dyn FnMut(f64) -> ControlFlow<()>,
) -> Result<Outcome> {
    Ok(sim::run_scenario_with(
        world,
        &source.scenario,
        &source.robot,
        progress,
    )?)
}

/// Writes `events.jsonl`, `trajectory.csv`, `report.md` and `scenario.toml` into `out`
/// (which must exist); returns the report's text.
pub fn write_simulation(outcome: &Outcome, source: &ScenarioSource, out: &Path) -> Result<String> {
    sim::write_outputs(out, outcome, &ReportConfig::default())?;
    cloud::write_bytes_atomically(&out.join("scenario.toml"), source.text.as_bytes())?;
    Ok(sim::report_markdown(outcome, &ReportConfig::default()))
}
