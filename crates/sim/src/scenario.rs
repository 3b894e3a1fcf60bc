//! The scenario file (TOML): which robot, where it starts, what it is told to do, for how long,
//! how events are reported, and the rules it is judged by. See `crates/sim/README.md` for the
//! format; `data/default_scenario.toml` is the demo's.

use crate::controller::{validate_commands, ControllerConfig, VelocityCommand, Waypoint};
use crate::error::{check_finite, check_range, read_text, Result, SimError};
use crate::events::EventConfig;
use crate::model::{RobotModel, StartPose};
use crate::world::WorldConfig;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// A scenario: robot, start, commands, time limit, event settings and rules.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scenario {
    /// A name for people.
    #[serde(default)]
    pub name: String,
    /// A line or two for people.
    #[serde(default)]
    pub description: String,
    /// The building, for tools that load it: `default` (the built-in one) or a file path.
    /// The library itself takes the world from its caller.
    #[serde(default = "default_building")]
    pub building: String,
    /// A built-in robot model (`pioneer3at`, `inspection`) or a model file path.
    #[serde(default = "default_robot")]
    pub robot: String,
    /// The robot's name in events.
    #[serde(default = "default_robot_name")]
    pub robot_name: String,
    /// The start pose.
    pub start: StartPose,
    /// Simulated seconds to run (> 0).
    pub time_limit_s: f64,
    /// Stop as soon as every goal rule has passed.
    #[serde(default)]
    pub stop_when_goals_met: bool,
    /// Trajectory samples per second (0 = every step).
    #[serde(default = "default_trajectory_rate")]
    pub trajectory_rate_hz: f64,
    /// Timed velocity commands (they override the waypoint follower while active).
    #[serde(default)]
    pub velocity: Vec<VelocityCommand>,
    /// Waypoints, followed in order.
    #[serde(default)]
    pub waypoints: Vec<Waypoint>,
    /// The rules the run is judged by.
    #[serde(default)]
    pub rules: Rules,
    /// Event rates and thresholds.
    #[serde(default)]
    pub events: EventConfig,
    /// Physics settings.
    #[serde(default)]
    pub world: WorldConfig,
    /// Waypoint follower gains.
    #[serde(default)]
    pub controller: ControllerConfig,
    /// Where it came from (its file, `<built-in default scenario>`, or the `source` given to
    /// [`Scenario::from_toml_str`]): errors about it name this. Not part of its value.
    #[serde(skip)]
    source: SourceName,
}

/// A scenario's source, for error messages; it never makes two scenarios differ.
#[derive(Debug, Clone, Default)]
struct SourceName(String);

impl PartialEq for SourceName {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

fn default_building() -> String {
    "default".into()
}
fn default_robot() -> String {
    "pioneer3at".into()
}
fn default_robot_name() -> String {
    "robot".into()
}
fn default_trajectory_rate() -> f64 {
    10.0
}

/// A circle to reach.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReachGoal {
    /// Centre x (m).
    pub x_m: f64,
    /// Centre y (m).
    pub y_m: f64,
    /// Radius (m).
    pub radius_m: f64,
}

/// The rules; entities are named by id, machine name (`walls[4].doors[2]`) or unique label.
/// Goals (`pass_through_door`, `pass_through_doors`, `reach_top_of_stairs`,
/// `reach_top_of_stairs_all`, `reach_top_of_ramps`, `open_door`, `reach`) pass when achieved and fail at the end
/// otherwise; constraints (`max_wall_contact_s`, `no_broken_joint`,
/// `no_tipping`, `no_stuck`) fail when violated and pass at the end otherwise.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Rules {
    /// The robot's chassis passes through this door's opening (enters its free space on one
    /// side and leaves on the other).
    pub pass_through_door: Option<String>,
    /// More doors to pass through, each judged like `pass_through_door` (a planned scenario
    /// lists its tour's doors here). Not written when empty.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub pass_through_doors: Vec<String>,
    /// The robot finishes climbing this staircase.
    pub reach_top_of_stairs: Option<String>,
    /// More staircases to climb, each judged like `reach_top_of_stairs`. Not written when
    /// empty.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub reach_top_of_stairs_all: Vec<String>,
    /// Ramps to drive up, each to its upper end (a "ramp climbing finished" event: every
    /// touching wheel on the ramp, the robot's centre within `events.ramp_top_within_m` of its
    /// head). Not written when empty.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub reach_top_of_ramps: Vec<String>,
    /// The robot opens this door: a "door opened" event, or the door opened at least
    /// `open_door_by_deg` wider than it started.
    pub open_door: Option<String>,
    /// How much wider than at the start counts as opening an already open door (degrees).
    pub open_door_by_deg: f64,
    /// The robot's chassis centre comes within the circle.
    pub reach: Option<ReachGoal>,
    /// Total time touching walls at most this (s).
    pub max_wall_contact_s: Option<f64>,
    /// No door hinge or arm joint breaks.
    pub no_broken_joint: bool,
    /// The robot never tips over.
    pub no_tipping: bool,
    /// The robot never gets stuck.
    pub no_stuck: bool,
}

impl Default for Rules {
    fn default() -> Self {
        Rules {
            pass_through_door: None,
            pass_through_doors: Vec::new(),
            reach_top_of_stairs: None,
            reach_top_of_stairs_all: Vec::new(),
            reach_top_of_ramps: Vec::new(),
            open_door: None,
            open_door_by_deg: 20.0,
            reach: None,
            max_wall_contact_s: None,
            no_broken_joint: false,
            no_tipping: false,
            no_stuck: false,
        }
    }
}

const DEFAULT_SCENARIO: &str = include_str!("../data/default_scenario.toml");

impl Scenario {
    /// The file of the building the scenario names, relative to `scenario_dir` (the folder of
    /// the scenario file); `None` for the built-in building (`building = "default"` or empty).
    pub fn building_file(&self, scenario_dir: &Path) -> Option<PathBuf> {
        match self.building.as_str() {
            "default" | "" => None,
            other => Some(scenario_dir.join(other)),
        }
    }

    /// The demo's scenario (`data/default_scenario.toml`): in the default building, drive down
    /// the corridor, push open the stair room's door, climb the stairs.
    pub fn default_scenario() -> Result<Scenario> {
        Scenario::from_toml_str(DEFAULT_SCENARIO, "<built-in default scenario>")
    }

    /// The demo scenario's TOML text.
    pub fn default_scenario_toml() -> &'static str {
        DEFAULT_SCENARIO
    }

    /// Loads and validates a scenario file.
    pub fn load(path: &Path) -> Result<Scenario> {
        Scenario::from_toml_str(&read_text(path)?, &path.display().to_string())
    }

    /// Parses and validates a scenario; `source` names it in errors.
    pub fn from_toml_str(text: &str, source: &str) -> Result<Scenario> {
        let mut s: Scenario = toml::from_str(text).map_err(|e| SimError::Syntax {
            source_name: source.to_string(),
            msg: e.to_string().trim_end().to_string(),
        })?;
        s.source = SourceName(source.to_string());
        s.validate()?;
        Ok(s)
    }

    /// Where the scenario came from (its file, `<built-in default scenario>`, or the source
    /// given to [`Scenario::from_toml_str`]; empty for one made otherwise). Errors about the
    /// scenario, from [`Scenario::validate`] and [`crate::Simulation::new`], name it.
    pub fn source_name(&self) -> &str {
        &self.source.0
    }

    /// Sets what [`Scenario::source_name`] answers.
    pub fn set_source_name(&mut self, source: &str) {
        self.source = SourceName(source.to_string());
    }

    /// Checks numbers and settings (entity references are checked against a world by
    /// [`crate::Simulation::new`]); errors name [`Scenario::source_name`].
    pub fn validate(&self) -> Result<()> {
        self.validate_fields()
            .map_err(|e| e.in_source(self.source_name()))
    }

    fn validate_fields(&self) -> Result<()> {
        let el = "scenario";
        check_range(
            el,
            "time_limit_s",
            self.time_limit_s,
            1.0e-3,
            1.0e6,
            "a time of 1 ms to 1e6 s",
        )?;
        check_range(
            el,
            "trajectory_rate_hz",
            self.trajectory_rate_hz,
            0.0,
            1000.0,
            "0 to 1000",
        )?;
        self.start.validate()?;
        validate_commands(&self.velocity, &self.waypoints)?;
        self.events.validate()?;
        self.world.validate()?;
        self.controller.validate()?;
        let r = &self.rules;
        check_range(
            "rules",
            "open_door_by_deg",
            r.open_door_by_deg,
            0.0,
            180.0,
            "0 to 180",
        )?;
        if let Some(m) = r.max_wall_contact_s {
            check_range("rules", "max_wall_contact_s", m, 0.0, 1.0e6, "0 to 1e6 s")?;
        }
        if let Some(g) = &r.reach {
            check_finite("rules.reach", "x_m, y_m", &[g.x_m, g.y_m])?;
            check_range(
                "rules.reach",
                "radius_m",
                g.radius_m,
                1.0e-3,
                1.0e4,
                "a radius of 1 mm to 10 km",
            )?;
        }
        Ok(())
    }

    /// The robot model: built-in by name, else a file relative to `base_dir`.
    pub fn robot_model(&self, base_dir: &Path) -> Result<RobotModel> {
        RobotModel::resolve(&self.robot, base_dir)
    }
}
