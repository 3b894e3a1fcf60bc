//! A scenario for any world: when no scenario is given, plan one from the world itself. A tour
//! from the start through every reachable door opening and up every staircase and ramp the
//! robot can climb, on a 2D free-space grid inflated by the robot's footprint ([`grid`]), found by
//! Dijkstra searches from where the robot stands, greedy nearest goal next ([`tour`]); the
//! rules follow from the tour (pass through each door on it, reach the top of each staircase
//! and ramp on it, no wall contact over 0.5 s, no tipping). What cannot be reached is listed with the
//! reason, never an error; a world with no free space for the robot is one.
//!
//! Door leaves do not block the grid: the robot may push a closed or ajar leaf (hinges turn
//! freely up to their limit, as the demo's robot pushes the stair room's door open). It
//! cannot pull one: from the side a leaf swings towards, an opening is passed only where the
//! leaf, as the map has it, already leaves the robot a way past its free edge (a leaf ajar
//! towards the robot is pushed shut by it, which is what happens on real scans, where most
//! leaves are seen ajar). Where both sides are reachable, the tour enters from the push side.
//! Staircases and ramps are climbed last (the tour ends on a landing or a ramp's upper end;
//! with several, the robot drives back down to each foot before the next). A ramp is climbed
//! only up to `max_ramp_pitch_deg`; its upper end is the robot's half length short of its
//! head. A tour with nothing to pass or climb sweeps the start's free region (its two farthest
//! points where the robot can turn in place), with a `reach` rule at the point farthest from
//! the start.
//!
//! The scenario names the world it was planned in (`building`: a semantic map's world is
//! named `semantic map`, or after its file), never the built-in building it was not.

mod config;
mod distance;
mod footprint;
mod goals;
mod grid;
mod ramp_leg;
mod search;
mod tour;

pub use config::PlanConfig;
pub use footprint::Footprint;

use crate::controller::Waypoint;
use crate::error::{Result, SimError};
use crate::model::{RobotModel, StartPose};
use crate::scenario::{ReachGoal, Rules, Scenario};
use crate::spec::WorldSpec;
use grid::FreeGrid;
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;

/// The radius of the `reach` rule at a sweep's end (m): about a robot's length (the
/// Pioneer 3-AT is 0.5 m long), over three times the controller's waypoint tolerance (0.15 m),
/// so a robot that drove there passes, one that stopped a body length short does not.
const REACH_RADIUS_M: f64 = 0.5;

/// A goal of the tour.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Goal {
    /// Pass through this opening (named by its door leaf, or its free space without a leaf).
    Door(String),
    /// Climb to the top of this staircase.
    Stairs(String),
    /// Drive up this ramp to its upper end.
    Ramp(String),
}

impl Goal {
    /// The entity's name.
    pub fn name(&self) -> &str {
        match self {
            Goal::Door(n) | Goal::Stairs(n) | Goal::Ramp(n) => n,
        }
    }
}

/// A goal the tour could not include, and why.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Unreachable {
    /// What was not reached.
    pub goal: Goal,
    /// Why, in one line.
    pub reason: String,
}

/// A planned scenario: the scenario, the goals in tour order and what is not reachable.
#[derive(Debug, Clone, PartialEq)]
pub struct PlannedScenario {
    /// The scenario (its rules: the tour's goals, `max_wall_contact_s = 0.5`, `no_tipping`).
    pub scenario: Scenario,
    /// The goals on the tour, in order.
    pub tour: Vec<Goal>,
    /// The tour's length (m).
    pub tour_length_m: f64,
    /// What the tour leaves out, and why.
    pub unreachable: Vec<Unreachable>,
    /// The grid cell size used (m; larger than asked for in very large worlds).
    pub cell_m: f64,
    /// The sweep's point farthest from the start, in a tour without doors or stairs (the
    /// `reach` rule's centre).
    pub sweep_end_m: Option<[f64; 2]>,
}

impl PlannedScenario {
    /// Doors on the tour.
    pub fn doors(&self) -> usize {
        self.tour
            .iter()
            .filter(|g| matches!(g, Goal::Door(_)))
            .count()
    }

    /// Staircases on the tour.
    pub fn stairs(&self) -> usize {
        self.tour
            .iter()
            .filter(|g| matches!(g, Goal::Stairs(_)))
            .count()
    }

    /// Ramps on the tour.
    pub fn ramps(&self) -> usize {
        self.tour
            .iter()
            .filter(|g| matches!(g, Goal::Ramp(_)))
            .count()
    }

    /// One line: `planned tour: 3 doors, 1 stairs, 2 unreachable, 41.2 m` (`..., 0
    /// unreachable, 12.5 m sweep` for a tour without goals that sweeps its free region;
    /// `1 stairs, 1 ramps, ...` where ramps are on the tour or left out).
    pub fn summary(&self) -> String {
        let any_ramp = self.ramps() > 0
            || self
                .unreachable
                .iter()
                .any(|u| matches!(u.goal, Goal::Ramp(_)));
        let ramps = if any_ramp {
            format!(", {} ramps", self.ramps())
        } else {
            String::new()
        };
        format!(
            "planned tour: {} doors, {} stairs{ramps}, {} unreachable, {:.1} m{}",
            self.doors(),
            self.stairs(),
            self.unreachable.len(),
            self.tour_length_m,
            if self.sweep_end_m.is_some() {
                " sweep"
            } else {
                ""
            }
        )
    }

    /// The scenario as TOML, with a header saying it was planned and what it left out.
    pub fn to_toml(&self) -> Result<String> {
        let body = toml::to_string(&self.scenario).map_err(|e| SimError::Invalid {
            element: "planned scenario".into(),
            msg: format!("could not be written as TOML: {e}"),
        })?;
        let mut s = String::from(
            "# Planned by semsim from the world (no scenario was given): a tour through every\n\
             # reachable door opening and up every staircase and ramp the robot can climb.\n",
        );
        let _ = writeln!(
            s,
            "# Planned in: {} (`building` names it; run it again with that world, e.g.\n\
             # `semsim simulate --map map/semantic_map.json --scenario scenario.toml`).",
            self.scenario.building
        );
        let _ = writeln!(s, "# {}", self.summary());
        for u in &self.unreachable {
            let _ = writeln!(s, "# not reachable: {}: {}", u.goal.name(), u.reason);
        }
        s.push_str(&body);
        Ok(s)
    }

    /// The report's section on what the tour left out (Markdown), or on everything reached.
    pub fn report_section(&self) -> String {
        let mut s = String::from("## Not reachable\n\n");
        let stand = "the robot only had to stand without touching walls or tipping";
        let sweep = self.sweep_end_m.map(|e| {
            format!(
                "the robot sweeps its free region instead ({:.1} m, reaching ({:.2}, {:.2}) m)",
                self.tour_length_m, e[0], e[1]
            )
        });
        let intro = match (self.tour.is_empty(), self.unreachable.is_empty()) {
            (true, true) if sweep.is_some() => format!(
                "The scenario was planned from the world, which has no door opening, \
                 staircase or ramp: {}.",
                sweep.unwrap_or_default()
            ),
            (true, false) if sweep.is_some() => format!(
                "The scenario was planned from the world, and nothing was reachable: {}. \
                 Left out:",
                sweep.unwrap_or_default()
            ),
            (true, true) => format!(
                "The scenario was planned from the world, which has no door opening, \
                 staircase or ramp: {stand}."
            ),
            (true, false) => format!(
                "The scenario was planned from the world, and nothing was reachable: {stand}."
            ),
            (false, true) => {
                "Every door opening, staircase and ramp of the world is on the planned tour.".into()
            }
            (false, false) => "The planned tour leaves out:".into(),
        };
        let _ = writeln!(s, "{intro}\n");
        if self.unreachable.is_empty() {
            return s;
        }
        let _ = writeln!(s, "| entity | kind | why |\n|---|---|---|");
        for u in &self.unreachable {
            let kind = match u.goal {
                Goal::Door(_) => "door",
                Goal::Stairs(_) => "stairs",
                Goal::Ramp(_) => "ramp",
            };
            let _ = writeln!(
                s,
                "| `{}` | {kind} | {} |",
                u.goal.name(),
                u.reason.replace('|', "\\|")
            );
        }
        s.push('\n');
        s
    }
}

/// Plans a scenario in `world` for `robot` (whose name or file the scenario records as
/// `cfg.robot`): from `start` (moved to the nearest free cell), or else from the free cell
/// nearest the centre of the largest free region. Errors: bad settings, and a world with no
/// free space for the robot ([`SimError::Invalid`] naming the world).
pub fn plan_scenario(
    world: &WorldSpec,
    robot: &RobotModel,
    start: Option<StartPose>,
    cfg: &PlanConfig,
) -> Result<PlannedScenario> {
    cfg.validate()?;
    // 1. The robot's footprint, height and the step rise it climbs.
    let fp = Footprint::of(robot);
    // 2. The free-space grid: boxes in the robot's height band, inflated by its half width.
    let grid = FreeGrid::build(world, &fp, cfg)?;
    // 3. The start: the hint's nearest free cell, else the largest free region's centre.
    let start_cell = match start {
        Some(p) => grid.nearest_free([p.x_m, p.y_m]),
        None => grid.centre_of_largest_region(),
    }
    .ok_or_else(|| no_free_space(world))?;
    // 4. The tour and what it leaves out.
    let t = tour::plan_tour(
        world,
        &grid,
        &fp,
        &robot.name,
        robot.drive.max_speed_mps,
        start_cell,
        cfg,
    );
    // 5. The scenario: waypoints, a time limit from the tour, the rules.
    let first = t.waypoints.first().map(|w| [w.x_m, w.y_m]);
    let s = grid.centre(start_cell);
    let yaw_deg = first.map_or(start.map_or(0.0, |p| p.yaw_deg), |f| {
        (f[1] - s[1]).atan2(f[0] - s[0]).to_degrees()
    });
    let start = StartPose {
        x_m: s[0],
        y_m: s[1],
        yaw_deg,
        z_m: grid.floor_z_m(),
    };
    let scenario = scenario_of(world, robot, &t, start, cfg)?;
    Ok(PlannedScenario {
        scenario,
        tour: t.goals,
        tour_length_m: t.length_m,
        unreachable: t.unreachable,
        cell_m: grid.cell_m(),
        sweep_end_m: t.sweep_end,
    })
}

fn no_free_space(world: &WorldSpec) -> SimError {
    let name = if world.name.is_empty() {
        "the world".to_string()
    } else {
        world.name.clone()
    };
    SimError::Invalid {
        element: "plan".into(),
        msg: format!("no free space for the robot in {name}"),
    }
}

/// The scenario of a tour: its waypoints, a time limit from its length, and its rules.
fn scenario_of(
    world: &WorldSpec,
    robot: &RobotModel,
    t: &tour::Tour,
    start: StartPose,
    cfg: &PlanConfig,
) -> Result<Scenario> {
    let doors: Vec<String> = t
        .goals
        .iter()
        .filter_map(|g| match g {
            Goal::Door(n) => Some(n.clone()),
            Goal::Stairs(_) | Goal::Ramp(_) => None,
        })
        .collect();
    let stairs: Vec<String> = t
        .goals
        .iter()
        .filter_map(|g| match g {
            Goal::Stairs(n) => Some(n.clone()),
            Goal::Door(_) | Goal::Ramp(_) => None,
        })
        .collect();
    let ramps: Vec<String> = t
        .goals
        .iter()
        .filter_map(|g| match g {
            Goal::Ramp(n) => Some(n.clone()),
            Goal::Door(_) | Goal::Stairs(_) => None,
        })
        .collect();
    // A sweep's end is a goal: the robot must get there (within a robot's length).
    let reach = t.sweep_end.map(|e| ReachGoal {
        x_m: e[0],
        y_m: e[1],
        radius_m: REACH_RADIUS_M,
    });
    let rules = Rules {
        pass_through_doors: doors,
        reach_top_of_stairs_all: stairs,
        reach_top_of_ramps: ramps,
        reach,
        // The constraints: at most half a second against walls, never tipped.
        max_wall_contact_s: Some(0.5),
        no_tipping: true,
        ..Rules::default()
    };
    let name = if world.name.is_empty() {
        "planned tour".to_string()
    } else {
        format!("planned tour of {}", world.name)
    };
    let waypoints: Vec<Waypoint> = t.waypoints.clone();
    let time_limit_s = (t.drive_time_s * cfg.time_slack + cfg.time_extra_s).min(1.0e5);
    // Parsed from a minimal text so that every other field takes the file format's default.
    let text = format!(
        "time_limit_s = {time_limit_s:?}\nstart = {{ x_m = {:?}, y_m = {:?} }}\n",
        start.x_m, start.y_m
    );
    let mut s = Scenario::from_toml_str(&text, "<planned scenario>")?;
    s.name = name;
    s.robot = cfg.robot.clone();
    s.description = format!(
        "Planned from the world for {}: {} doors, {} stairs, {} ramps on the tour",
        robot.name,
        rules.pass_through_doors.len(),
        rules.reach_top_of_stairs_all.len(),
        rules.reach_top_of_ramps.len()
    );
    s.start = start;
    s.waypoints = waypoints;
    s.rules = rules;
    s.building = if world.name.is_empty() {
        "planned world".into()
    } else {
        world.name.clone()
    };
    // A sweep runs to its time limit: reaching its far point is the goal, the way back is
    // driven (and judged for wall contact and tipping) too.
    s.stop_when_goals_met = !t.goals.is_empty();
    s.validate()?;
    Ok(s)
}
