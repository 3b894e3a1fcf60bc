//! A scenario's run: the world, one robot, its controller, the event detectors and the judge,
//! advanced one fixed step at a time. The whole state is serialisable (see checkpoint.rs).

use crate::controller::Controller;
use crate::detect::contacts::{self, ContactDetector};
use crate::detect::doors::{DoorDetector, FreeSpaceDetector};
use crate::detect::joints;
use crate::detect::motion::MotionDetector;
use crate::detect::ramps::RampDetector;
use crate::detect::stairs::StairsDetector;
use crate::error::Result;
use crate::events::{Emitter, Event};
use crate::judge::{Judge, Observation};
use crate::model::RobotModel;
use crate::scenario::Scenario;
use crate::spec::WorldSpec;
use crate::verdict::Verdict;
use crate::world::robot::{robot_pose, RobotPose};
use crate::world::World;
use serde::{Deserialize, Serialize};
use std::ops::ControlFlow;

/// One trajectory sample of the robot's chassis.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TrajectoryPoint {
    /// Simulated time (s).
    pub time_s: f64,
    /// Pose and speed.
    pub pose: RobotPose,
}

/// The doors' opening angles over time, sampled with the trajectory (one sample per
/// trajectory point, at the same times): what lets a replay swing the doors as they moved.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct DoorTrack {
    /// The doors' entity ids, in the world's order: the columns of each sample.
    pub doors: Vec<u32>,
    /// The samples, in time order.
    pub samples: Vec<DoorSample>,
}

/// The doors' angles at one moment.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DoorSample {
    /// Simulated time (s).
    pub time_s: f64,
    /// Each door's opening angle (degrees, 0 = closed), in [`DoorTrack::doors`]' order (a
    /// door whose hinge broke keeps its leaf's angle about the hinge's axis).
    pub angles_deg: Vec<f64>,
}

/// What a finished run produced.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Outcome {
    /// Every event, in time order.
    pub events: Vec<Event>,
    /// The robot's trajectory at the scenario's rate.
    pub trajectory: Vec<TrajectoryPoint>,
    /// The verdict.
    pub verdict: Verdict,
    /// The scenario's name.
    pub scenario_name: String,
    /// The robot model's name.
    pub robot_model: String,
    /// The doors' angles, sampled with the trajectory (empty in outcomes serialised before
    /// doors were recorded).
    #[serde(default)]
    pub doors: DoorTrack,
}

/// A running simulation of one scenario.
#[derive(Serialize, Deserialize)]
pub struct Simulation {
    pub(crate) world: World,
    pub(crate) scenario: Scenario,
    pub(crate) model_name: String,
    pub(crate) controller: Controller,
    pub(crate) contacts: ContactDetector,
    pub(crate) doors: DoorDetector,
    pub(crate) free_spaces: FreeSpaceDetector,
    pub(crate) stairs: StairsDetector,
    /// The ramps and their climbs (empty in checkpoints from before ramps were detected).
    #[serde(default)]
    pub(crate) ramps: RampDetector,
    pub(crate) motion: MotionDetector,
    pub(crate) judge: Judge,
    pub(crate) events: Vec<Event>,
    pub(crate) trajectory: Vec<TrajectoryPoint>,
    /// The doors' angles, sampled with the trajectory (empty in checkpoints from before doors
    /// were recorded: their replays show the doors where they stand from then on).
    #[serde(default)]
    pub(crate) door_track: DoorTrack,
    pub(crate) next_sample_s: f64,
    pub(crate) step_limit: u64,
    /// Set when [`Simulation::run_with`] was stopped before the end; cleared by the next step.
    #[serde(default)]
    pub(crate) interrupted_at_s: Option<f64>,
    /// The operator's (linear m/s, angular rad/s) command, overriding the scenario's
    /// commands while set (see operator.rs).
    #[serde(default)]
    pub(crate) operator: Option<(f64, f64)>,
}

impl Simulation {
    /// Builds the world of `spec`, puts the scenario's robot (`model`) at its start and resolves
    /// the rules (unknown entities are errors).
    pub fn new(spec: &WorldSpec, scenario: &Scenario, model: &RobotModel) -> Result<Simulation> {
        scenario.validate()?;
        let judge =
            Judge::new(&scenario.rules, spec).map_err(|e| e.in_source(scenario.source_name()))?;
        let mut world = World::new(spec, scenario.world.clone())?;
        world.add_robot(model, &scenario.start, &scenario.robot_name)?;
        let doors = DoorDetector::new(&world, &scenario.events);
        let step_limit = (scenario.time_limit_s / world.dt_secs()).round().max(1.0) as u64;
        let mut sim = Simulation {
            world,
            scenario: scenario.clone(),
            model_name: model.name.clone(),
            controller: Controller::default(),
            contacts: ContactDetector::default(),
            doors,
            free_spaces: FreeSpaceDetector::default(),
            stairs: StairsDetector::default(),
            ramps: RampDetector::new(spec),
            motion: MotionDetector::default(),
            judge,
            events: vec![],
            trajectory: vec![],
            door_track: DoorTrack::default(),
            next_sample_s: 0.0,
            step_limit,
            interrupted_at_s: None,
            operator: None,
        };
        sim.sample();
        Ok(sim)
    }

    /// Advances one fixed step: controller, physics, broken joints, event detectors, judge.
    pub fn step(&mut self) {
        self.interrupted_at_s = None;
        let t = self.world.time_s();
        let pose = self.robot_pose();
        let s = &self.scenario;
        let (v, w) = match self.operator {
            Some(command) => command,
            None => self
                .controller
                .command(t, &pose, &s.velocity, &s.waypoints, &s.controller),
        };
        let world = &mut self.world;
        if let Some(robot) = world.robots.first_mut() {
            robot.drive(&mut world.physics, v, w);
        }
        world.step_physics();
        let mut new_events = vec![];
        let mut out = Emitter {
            time_s: world.time_s(),
            log: &mut new_events,
        };
        joints::break_overloaded(world, &mut out);
        let cfg = &self.scenario.events;
        let scan = contacts::scan(world);
        self.contacts.update(world, &scan, cfg, &mut out);
        self.doors.update(world, cfg, &mut out);
        self.free_spaces.update(world, &mut out);
        self.stairs.update(world, &scan, cfg, &mut out);
        self.ramps.update(world, &scan, cfg, &mut out);
        self.motion.update(world, cfg, &mut out);
        let door_angles: Vec<(u32, f64)> = world
            .doors
            .iter()
            .filter(|d| d.joint.is_some())
            .map(|d| (d.entity, d.angle_deg(&world.physics)))
            .collect();
        let obs = Observation {
            time_s: world.time_s(),
            events: &new_events,
            robot_entity: world.robots.first().map(|r| r.entity).unwrap_or(0),
            pose: self.robot_pose(),
            wall_contact_s: self.wall_contact_s(),
            door_angles: &door_angles,
        };
        self.judge.observe(&obs);
        self.events.append(&mut new_events);
        self.sample();
    }

    fn sample(&mut self) {
        let t = self.world.time_s();
        if t + 1e-9 >= self.next_sample_s {
            let rate = self.scenario.trajectory_rate_hz;
            self.next_sample_s = if rate > 0.0 { t + 1.0 / rate } else { t };
            let pose = self.robot_pose();
            self.trajectory.push(TrajectoryPoint { time_s: t, pose });
            self.sample_doors(t);
        }
    }

    /// Records the doors' angles at `t` (a simulation resumed from a checkpoint written
    /// before doors were recorded starts its door track now).
    fn sample_doors(&mut self, t: f64) {
        let doors = &self.world.doors;
        let track = &mut self.door_track;
        if track.samples.is_empty() {
            track.doors = doors.iter().map(|d| d.entity).collect();
        }
        if track.doors.len() == doors.len() {
            let physics = &self.world.physics;
            let angles_deg = doors.iter().map(|d| d.angle_deg(physics)).collect();
            track.samples.push(DoorSample {
                time_s: t,
                angles_deg,
            });
        }
    }

    /// Steps until the simulated time reaches `t_s` (or the time limit).
    pub fn run_until(&mut self, t_s: f64) {
        let target = ((t_s / self.world.dt_secs()).round().max(0.0) as u64).min(self.step_limit);
        while self.world.steps < target {
            self.step();
        }
    }

    /// Runs to the time limit, or until every goal has passed when the scenario says
    /// `stop_when_goals_met`; returns the verdict.
    pub fn run(&mut self) -> Verdict {
        while !self.is_finished() {
            self.step();
        }
        self.verdict()
    }

    /// Like [`Simulation::run`], but calls `progress` with the simulated time every
    /// `every_steps` steps (at least 1); when it answers [`ControlFlow::Break`] the run stops
    /// there, interrupted: the verdict (and [`Simulation::outcome`]) then says so (see
    /// [`Verdict::interrupted_at_s`]) until the simulation is stepped again.
    pub fn run_with(
        &mut self,
        every_steps: u64,
        progress: &mut dyn FnMut(f64) -> ControlFlow<()>,
    ) -> Verdict {
        let every = every_steps.max(1);
        while !self.is_finished() {
            self.step();
            if self.world.steps.is_multiple_of(every)
                && !self.is_finished()
                && progress(self.time_s()).is_break()
            {
                self.interrupted_at_s = Some(self.time_s());
                break;
            }
        }
        self.verdict()
    }

    /// When the run was interrupted (s), if [`Simulation::run_with`] was stopped before the
    /// end and the simulation has not been stepped since.
    pub fn interrupted_at_s(&self) -> Option<f64> {
        self.interrupted_at_s
    }

    /// Whether the run is over (time limit, or goals met with `stop_when_goals_met`).
    pub fn is_finished(&self) -> bool {
        self.world.steps >= self.step_limit
            || (self.scenario.stop_when_goals_met && self.judge.goals_met())
    }

    /// Simulated time (s).
    pub fn time_s(&self) -> f64 {
        self.world.time_s()
    }

    /// Steps taken.
    pub fn steps(&self) -> u64 {
        self.world.steps
    }

    /// Every event so far.
    pub fn events(&self) -> &[Event] {
        &self.events
    }

    /// The trajectory so far.
    pub fn trajectory(&self) -> &[TrajectoryPoint] {
        &self.trajectory
    }

    /// The robot's current pose.
    pub fn robot_pose(&self) -> RobotPose {
        self.world
            .robots
            .first()
            .map(|r| robot_pose(&self.world.physics, r))
            .unwrap_or_default()
    }

    /// Total time the robot has touched walls (s).
    pub fn wall_contact_s(&self) -> f64 {
        self.contacts.wall_contact_s.get(&0).copied().unwrap_or(0.0)
    }

    /// The highest stair tread the robot has reached on a staircase (-1: none).
    pub fn highest_step(&self, stairs_entity: u32) -> i32 {
        self.stairs.highest(0, stairs_entity)
    }

    /// The widest angle a door has reached (degrees).
    pub fn widest_door_angle_deg(&self, door_entity: u32) -> Option<f64> {
        self.doors.widest_deg.get(&door_entity).copied()
    }

    /// The verdict now (undecided goals count as failed; after an interrupted
    /// [`Simulation::run_with`], undecided rules are failed as not decided).
    pub fn verdict(&self) -> Verdict {
        self.judge.verdict(
            self.time_s(),
            self.wall_contact_s(),
            self.interrupted_at_s.is_some(),
        )
    }

    /// The world.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// The scenario.
    pub fn scenario(&self) -> &Scenario {
        &self.scenario
    }

    /// The events, trajectory and verdict.
    pub fn outcome(&self) -> Outcome {
        Outcome {
            events: self.events.clone(),
            trajectory: self.trajectory.clone(),
            verdict: self.verdict(),
            scenario_name: self.scenario.name.clone(),
            robot_model: self.model_name.clone(),
            doors: self.door_track.clone(),
        }
    }
}

/// Runs a scenario headless in a world and returns what it produced.
pub fn run_scenario(spec: &WorldSpec, scenario: &Scenario, model: &RobotModel) -> Result<Outcome> {
    let mut sim = Simulation::new(spec, scenario, model)?;
    sim.run();
    Ok(sim.outcome())
}

/// How often [`run_scenario_with`] calls its `progress` (steps; 10 steps are 1/6 s of
/// simulated time with the default step).
pub const PROGRESS_EVERY_STEPS: u64 = 10;

/// Like [`run_scenario`], but calls `progress` with the simulated time (s) every
/// [`PROGRESS_EVERY_STEPS`] steps, to show progress (the run ends at
/// `scenario.time_limit_s`, or earlier with `stop_when_goals_met`) and to stop it: when
/// `progress` answers [`ControlFlow::Break`] (e.g. on Ctrl-C) the run stops there and the
/// outcome holds the events and trajectory so far, with the verdict failed and marked
/// interrupted ([`Verdict::interrupted_at_s`]; rules not decided by then say so, and so does
/// `report.md`). A run that is not stopped gives exactly [`run_scenario`]'s outcome.
///
/// ```no_run
/// # fn demo(spec: &sim::WorldSpec, scenario: &sim::Scenario, model: &sim::RobotModel) -> sim::Result<()> {
/// use std::ops::ControlFlow;
/// use std::sync::atomic::{AtomicBool, Ordering};
/// static STOP: AtomicBool = AtomicBool::new(false); // set by a Ctrl-C handler
/// let outcome = sim::run_scenario_with(spec, scenario, model, &mut |t_s| {
///     eprint!("\rsimulated {t_s:.1} of {} s", scenario.time_limit_s);
///     if STOP.load(Ordering::Relaxed) { ControlFlow::Break(()) } else { ControlFlow::Continue(()) }
/// })?;
/// if let Some(t) = outcome.verdict.interrupted_at_s {
///     eprintln!("interrupted at {t} s");
/// }
/// # Ok(()) }
/// ```
pub fn run_scenario_with(
    spec: &WorldSpec,
    scenario: &Scenario,
    model: &RobotModel,
    progress: &mut dyn FnMut(f64) -> ControlFlow<()>,
) -> Result<Outcome> {
    let mut sim = Simulation::new(spec, scenario, model)?;
    sim.run_with(PROGRESS_EVERY_STEPS, progress);
    Ok(sim.outcome())
}
