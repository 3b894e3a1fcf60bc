//! Semantic simulation for semsim: a rapier3d physics world built from a building's semantic
//! entities, robots driving in it, semantic events and a judge.
//!
//! * [`WorldSpec`] is the input: fixed boxes (floor, ceiling, walls, lintels, furniture), doors
//!   on hinges, door free-space sensors and staircases, each tagged with its entity (id, class,
//!   name). [`WorldSpec::from_building`] makes one from a ground-truth [`scanner::Building`],
//!   `WorldSpec::from_semantic_map` (feature `semantic`) from a semantic map built from scans.
//! * [`RobotModel`]s are data (TOML): chassis, wheels with skid-steering velocity motors, an
//!   optional arm with breakable joints. Built in: `pioneer3at` and `inspection` (climbs stairs).
//! * A [`Scenario`] (TOML) says which robot starts where, what it is told (timed velocities,
//!   waypoints), for how long, and the [`Rules`] it is judged by.
//! * [`Simulation`] runs it with a fixed step: controller, physics, breakable joints, then the
//!   event detectors ([`EventKind`]: movement, collision started/continued/stopped, wall touched,
//!   door free space entered/left, door opened/closed, stairs climbing, joint broken, tipped,
//!   stuck) and the judge, giving events, a trajectory and a [`Verdict`]. It is deterministic,
//!   and can be checkpointed and resumed with identical results.
//!   [`run_scenario_with`] reports progress and can be stopped (e.g. on Ctrl-C), giving the
//!   outcome so far with the verdict marked interrupted.
//! * Worlds are refused up front when too big to simulate ([`WorldSpec::check_limits`]); static
//!   boxes that overlap much (thousands at one place) become one compound collider, so memory
//!   stays linear, and contacts still name each box's entity.
//! * Errors name their file: [`Scenario::load`], [`RobotModel::load`],
//!   [`WorldSpec::from_building_file`], `WorldSpec::from_semantic_map_file` (see
//!   [`SimError::in_source`]).
//! * Where no scenario is given, [`plan_scenario`] plans one from the world: a tour through
//!   every reachable door opening and up every staircase the robot can climb, on a free-space
//!   grid inflated by the robot's footprint, with what is unreachable listed and why.
//! * A person can drive instead of the scenario ([`Simulation::set_operator_drive`]), and
//!   viewers read the live state ([`Simulation::live_state`], [`Simulation::live_rules`]).
//! * [`write_outputs`] writes `events.jsonl`, `trajectory.csv`, `doors.csv` and `report.md`.
//!
//! ```
//! use sim::{RobotModel, Scenario, Simulation, WorldSpec};
//!
//! let building = scanner::Building::from_toml_str(r#"
//!     [floor]
//!     min_m = [0.0, -2.0]
//!     max_m = [6.0, 2.0]
//!     [ceiling]
//!     height_m = 2.5
//!     [[walls]]
//!     start_m = [5.0, -2.0]
//!     end_m = [5.0, 2.0]
//!     thickness_m = 0.2
//! "#, std::path::Path::new("tiny.toml")).unwrap();
//! let spec = WorldSpec::from_building(&building).unwrap();
//! let scenario = Scenario::from_toml_str(r#"
//!     robot = "pioneer3at"
//!     time_limit_s = 8.0
//!     start = { x_m = 2.0, y_m = 0.0, yaw_deg = 0.0 }
//!     [[velocity]]
//!     from_s = 0.5
//!     to_s = 8.0
//!     linear_mps = 0.6
//!     [rules]
//!     max_wall_contact_s = 0.5
//! "#, "doctest").unwrap();
//! let model = RobotModel::builtin(&scenario.robot).unwrap();
//! let outcome = sim::run_scenario(&spec, &scenario, &model).unwrap();
//! assert!(outcome.events.iter().any(|e| e.kind == sim::EventKind::WallTouched));
//! assert!(!outcome.verdict.passed); // it pushed against the wall for seconds
//! ```

#![warn(missing_docs)]

mod checkpoint;
mod controller;
mod detect;
mod error;
mod events;
mod import;
mod judge;
mod live;
mod model;
mod operator;
mod plan;
mod ramps;
mod report;
mod resolve;
mod scenario;
mod simulation;
mod spec;
mod validate;
mod verdict;
mod world;

pub use cloud::EntityClass;
pub use controller::{Controller, ControllerConfig, VelocityCommand, Waypoint};
pub use error::{Result, SimError};
pub use events::{events_to_jsonl, EntityRef, Event, EventConfig, EventKind};
pub use import::ImportConfig;
pub use live::{LiveDoor, LiveRobot, LiveRule, LiveState, RuleState};
pub use model::{
    ArmAxis, ArmModel, ChassisModel, DriveModel, LinkModel, RobotModel, StartPose, WheelModel,
};
pub use plan::{plan_scenario, Footprint, Goal, PlanConfig, PlannedScenario, Unreachable};
pub use report::{
    doors_to_csv, report_markdown, trajectory_to_csv, write_doors_csv, write_events_jsonl,
    write_outputs, write_report_md, write_trajectory_csv, ReportConfig, DOORS_CSV,
};
pub use scenario::{ReachGoal, Rules, Scenario};
pub use simulation::{
    run_scenario, run_scenario_with, DoorSample, DoorTrack, Outcome, Simulation, TrajectoryPoint,
    PROGRESS_EVERY_STEPS,
};
pub use spec::{
    BoxSpec, DoorSpec, EntityInfo, FixedBox, FreeSpaceSpec, HingeEnd, OpeningSense, StairsSpec,
    StepSpec, WorldSpec,
};
pub use verdict::{RuleResult, Verdict};
pub use world::robot::RobotPose;
pub use world::{World, WorldConfig};
