//! The simulation stage of the chain: a scenario (from a file, the built-in one, or planned
//! from the world when none is given) run in the world of a semantic map or of a building,
//! judged, and its files.

use crate::error::Result;
use scanner::Building;
use sim::{
    Outcome, PlanConfig, PlannedScenario, ReportConfig, RobotModel, Scenario, StartPose, WorldSpec,
};
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
    /// The plan, when the scenario was planned from the world (its tour and what it could
    /// not reach, for the report).
    pub planned: Option<PlannedScenario>,
}

/// Where a run's scenario comes from: given (a file, or the built-in default scenario the
/// demo uses), or planned from the world once the world is known.
#[derive(Debug, Clone)]
pub enum ScenarioChoice {
    /// A scenario given up front.
    Given(Box<ScenarioSource>),
    /// No scenario given: plan one in the world (see [`sim::plan_scenario`]).
    Planned {
        /// The planner's settings (`[plan]` of the configuration).
        cfg: PlanConfig,
        /// The robot `cfg.robot` names (resolved up front, so a bad robot fails before any work).
        robot: Box<RobotModel>,
    },
}

impl ScenarioChoice {
    /// The scenario file's, or, without one, a plan with `cfg` (its robot resolved from the
    /// current folder).
    pub fn from_file_or_plan(path: Option<&Path>, cfg: &PlanConfig) -> Result<ScenarioChoice> {
        Ok(match path {
            Some(p) => ScenarioChoice::Given(Box::new(ScenarioSource::load(Some(p))?)),
            None => {
                cfg.validate()?;
                ScenarioChoice::Planned {
                    cfg: cfg.clone(),
                    robot: Box::new(RobotModel::resolve(&cfg.robot, Path::new("."))?),
                }
            }
        })
    }

    /// The scenario to run in `world`: the given one, or one planned there from `start` (the
    /// nearest free cell to it; `None`: the middle of the largest free region).
    pub fn resolve(&self, world: &WorldSpec, start: Option<StartPose>) -> Result<ScenarioSource> {
        match self {
            ScenarioChoice::Given(s) => Ok(s.as_ref().clone()),
            ScenarioChoice::Planned { cfg, robot } => {
                ScenarioSource::plan(world, robot, start, cfg)
            }
        }
    }

    /// The scenario's name for progress lines (`a planned tour` before it is planned).
    pub fn title(&self) -> String {
        match self {
            ScenarioChoice::Given(s) => format!("\"{}\"", s.scenario.name),
            ScenarioChoice::Planned { .. } => "a planned tour".into(),
        }
    }
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
            planned: None,
        })
    }

    /// A scenario planned in `world` for `robot` (see [`sim::plan_scenario`]); its text is the
    /// planned scenario's TOML with a header saying so.
    pub fn plan(
        world: &WorldSpec,
        robot: &RobotModel,
        start: Option<StartPose>,
        cfg: &PlanConfig,
    ) -> Result<ScenarioSource> {
        let planned = sim::plan_scenario(world, robot, start, cfg)?;
        Ok(ScenarioSource {
            scenario: planned.scenario.clone(),
            text: planned.to_toml()?,
            base_dir: PathBuf::from("."),
            robot: robot.clone(),
            planned: Some(planned),
        })
    }

    /// The report of a run of this scenario: `report.md`'s text, with the section on what a
    /// planned tour could not reach.
    pub fn report(&self, outcome: &Outcome) -> String {
        let mut report = sim::report_markdown(outcome, &ReportConfig::default());
        if let Some(p) = &self.planned {
            report.push('\n');
            report.push_str(&p.report_section());
        }
        report
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

/// Writes `sim::write_outputs`' files (`events.jsonl`, `trajectory.csv`, `report.md`, ...)
/// and `scenario.toml` into `out` (which must exist); for a planned scenario `report.md` also
/// lists what the tour could not reach. Returns the report's text.
pub fn write_simulation(outcome: &Outcome, source: &ScenarioSource, out: &Path) -> Result<String> {
    sim::write_outputs(out, outcome, &ReportConfig::default())?;
    let report = source.report(outcome);
    if source.planned.is_some() {
        cloud::write_bytes_atomically(&out.join("report.md"), report.as_bytes())?;
    }
    cloud::write_bytes_atomically(&out.join("scenario.toml"), source.text.as_bytes())?;
    Ok(report)
}
