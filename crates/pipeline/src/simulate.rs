//! The simulation stage of the chain: a scenario (from a file, the built-in one, or planned
//! from the world when none is given) run in the world of a semantic map or of a building,
//! judged, and its files.

use crate::error::{PipelineError, Result};
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

    /// The scenario driving `robot` instead (a built-in name, a robot TOML or a URDF file,
    /// relative to the current folder), its text saying so: the text written beside a run
    /// (`scenario.toml`) names the robot, a file by its absolute path, so that a replay of the
    /// run drives the same robot from any folder.
    pub fn with_robot(mut self, robot: &str) -> Result<ScenarioSource> {
        let model = RobotModel::resolve(robot, Path::new("."))?;
        let name = if Path::new(robot).is_file() {
            std::fs::canonicalize(robot)
                .map_err(|e| cloud::CloudError::io(robot, e))?
                .display()
                .to_string()
        } else {
            robot.to_string()
        };
        let mut table: toml::Table = toml::from_str(&self.text)
            .map_err(|e| PipelineError::bad_input(format!("{}: {e}", self.scenario.name)))?;
        table.insert("robot".into(), toml::Value::String(name.clone()));
        let text = toml::to_string(&table).map_err(|e| PipelineError::Serialise {
            what: "the scenario with another robot",
            msg: e.to_string(),
        })?;
        self.text = format!("# semsim --robot {robot}: the scenario with this robot\n{text}");
        self.scenario.robot = name;
        self.robot = model;
        Ok(self)
    }

    /// The building the scenario names (`building`, relative to its folder; "default" or
    /// nothing for the built-in one), unless `explicit` is given.
    pub fn building(&self, explicit: Option<&Path>) -> Result<Building> {
        let file = explicit.map(Path::to_path_buf);
        Ok(
            match file.or_else(|| self.scenario.building_file(&self.base_dir)) {
                Some(p) => Building::load(&p)?,
                None => Building::default_building()?,
            },
        )
    }
}

/// The world and scenario of a simulation given as files (`semsim simulate`): with a semantic
/// map (`map`), its world (named by the file when the scenario is planned, so that "no free
/// space for the robot in `<map>`" names it) and the `scenario` file's scenario or, without one, a
/// scenario planned there with `plan` (its robot resolved from the current folder); without a
/// map, the `scenario` file's scenario in the `building` given or else the one the scenario
/// names; with a `building` and no scenario, a scenario planned in its world likewise (the
/// built-in scenario names places in the built-in building only); with neither, the built-in
/// scenario in the built-in building.
pub fn world_and_scenario(
    map: Option<&Path>,
    scenario: Option<&Path>,
    building: Option<&Path>,
    plan: &PlanConfig,
) -> Result<(WorldSpec, ScenarioSource)> {
    Ok(match (map, scenario, building) {
        (Some(m), None, _) => {
            let mut world = WorldSpec::from_semantic_map_file(m)?;
            world.name = m.display().to_string();
            let robot = RobotModel::resolve(&plan.robot, Path::new("."))?;
            let source = ScenarioSource::plan(&world, &robot, None, plan)?;
            (world, source)
        }
        (Some(m), Some(_), _) => (
            WorldSpec::from_semantic_map_file(m)?,
            ScenarioSource::load(scenario)?,
        ),
        (None, None, Some(file)) => {
            let mut world = WorldSpec::from_building(&Building::load(file)?)?;
            world.name = file.display().to_string();
            let robot = RobotModel::resolve(&plan.robot, Path::new("."))?;
            let source = ScenarioSource::plan(&world, &robot, None, plan)?;
            (world, source)
        }
        (None, _, _) => {
            let source = ScenarioSource::load(scenario)?;
            let world = WorldSpec::from_building(&source.building(building)?)?;
            (world, source)
        }
    })
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

#[cfg(test)]
mod tests {
    use super::*;
    use cloud::BadInput;

    #[test]
    fn another_robot_is_driven_and_named_in_the_scenario_text() {
        let source = ScenarioSource::load(None).expect("the default scenario");
        assert_ne!(source.scenario.robot, "pioneer3at");
        let other = source.with_robot("pioneer3at").expect("a built-in robot");
        assert_eq!(other.scenario.robot, "pioneer3at");
        assert_eq!(
            other.robot,
            RobotModel::builtin("pioneer3at").expect("built in")
        );
        // The text written beside the run reads back as the same scenario with that robot.
        let back = Scenario::from_toml_str(&other.text, "scenario.toml").expect("valid TOML");
        assert_eq!(back, other.scenario);
    }

    #[test]
    fn a_robot_file_is_named_by_its_absolute_path() {
        let dir = tempfile::tempdir().expect("tempdir");
        let file = dir.path().join("robot.toml");
        let text = include_str!("../../sim/data/pioneer3at.toml");
        std::fs::write(&file, text).expect("write");
        let relative = pathdiff(&file);
        let other = ScenarioSource::load(None)
            .expect("default")
            .with_robot(&relative)
            .expect("a robot file");
        assert!(Path::new(&other.scenario.robot).is_absolute());
        assert_eq!(
            Path::new(&other.scenario.robot),
            file.canonicalize().expect("exists")
        );
        let back = Scenario::from_toml_str(&other.text, "scenario.toml").expect("valid TOML");
        assert_eq!(back.robot, other.scenario.robot);
    }

    /// `path` relative to the current folder where it can be (else as it is).
    fn pathdiff(path: &Path) -> String {
        let here = std::env::current_dir().expect("cwd");
        path.strip_prefix(&here)
            .unwrap_or(path)
            .display()
            .to_string()
    }

    #[test]
    fn an_unknown_robot_is_bad_input() {
        let e = ScenarioSource::load(None)
            .expect("default")
            .with_robot("no-such-robot")
            .expect_err("unknown");
        assert!(e.is_bad_input(), "{e}");
        assert!(e.to_string().contains("no-such-robot"), "{e}");
    }

    #[test]
    fn a_map_without_a_scenario_gets_a_planned_one_named_after_the_map() {
        let dir = tempfile::tempdir().expect("tempdir");
        let map = dir.path().join("semantic_map.json");
        let json = fixtures::door_wall_map_json("left", 0.0, fixtures::DOOR_RELATIONS);
        std::fs::write(&map, json).expect("write");
        let (world, source) =
            world_and_scenario(Some(&map), None, None, &PlanConfig::default()).expect("planned");
        assert_eq!(world.name, map.display().to_string());
        assert!(source.planned.is_some());
        let (_, given) = world_and_scenario(None, None, None, &PlanConfig::default())
            .expect("the default scenario in its building");
        assert!(given.planned.is_none());
        assert_eq!(
            given.scenario,
            Scenario::default_scenario().expect("built in")
        );
    }
}
