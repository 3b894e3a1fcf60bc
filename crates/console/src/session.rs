//! A console session: one run of the scenario that an operator may drive, its command log,
//! and its run folder (what `semsim simulate` writes, plus `commands.jsonl`). Sessions know
//! nothing of time or sockets: the runner steps them in real time.

use crate::cloud_layer::CloudLayer;
use crate::error::Result;
use crate::log::{CommandLog, RunEnd};
use crate::protocol::{ClientMessage, DriveCommand};
use crate::replay::apply_drive;
use crate::world::ConsoleWorld;
use sim::{Event, Outcome, ReportConfig, RobotModel, Scenario, Simulation};
use std::path::{Path, PathBuf};

/// What every session of a console runs, and where its runs are saved.
#[derive(Debug, Clone)]
pub struct SessionSetup {
    /// The world.
    pub world: ConsoleWorld,
    /// The scenario: robot, start, time limit, rules (its scripted commands drive until the
    /// operator's first `drive` or `stop`).
    pub scenario: Scenario,
    /// The scenario's TOML text, written as `scenario.toml` beside each run.
    pub scenario_toml: String,
    /// The robot.
    pub robot: RobotModel,
    /// The folder the sessions are saved in, each as `session-NNN/`.
    pub out_dir: PathBuf,
    /// The registered point cloud, shown as a layer (`--cloud`).
    pub cloud: Option<CloudLayer>,
}

/// The file names of a run folder (the first five as `semsim simulate` writes them).
pub const RUN_FILES: [&str; 6] = [
    "events.jsonl",
    "trajectory.csv",
    "doors.csv",
    "report.md",
    "scenario.toml",
    "commands.jsonl",
];

/// The folder name of session `number`.
pub fn session_dir_name(number: u32) -> String {
    format!("session-{number:03}")
}

/// The number after the highest `session-NNN` folder in `dir` (1 if none), so that a console
/// never replaces the runs of an earlier one.
pub fn first_free_session(dir: &Path) -> u32 {
    let highest = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .filter_map(|e| {
            let name = e.file_name();
            name.to_str()?.strip_prefix("session-")?.parse::<u32>().ok()
        })
        .max()
        .unwrap_or(0);
    highest.saturating_add(1)
}

/// One session.
pub struct Session {
    sim: Simulation,
    number: u32,
    log: Vec<(u64, ClientMessage)>,
    operator: Option<DriveCommand>,
    saved_at_step: Option<u64>,
}

impl Session {
    /// Starts session `number` (the scenario's entity references are checked here).
    pub fn new(setup: &SessionSetup, number: u32) -> Result<Session> {
        Ok(Session {
            sim: Simulation::new(&setup.world.spec, &setup.scenario, &setup.robot)?,
            number,
            log: vec![],
            operator: None,
            saved_at_step: None,
        })
    }

    /// Its number.
    pub fn number(&self) -> u32 {
        self.number
    }

    /// The simulation.
    pub fn sim(&self) -> &Simulation {
        &self.sim
    }

    /// The operator's command as applied, once the operator drives.
    pub fn operator(&self) -> Option<DriveCommand> {
        self.operator
    }

    /// Whether the run has ended.
    pub fn is_finished(&self) -> bool {
        self.sim.is_finished()
    }

    /// Logs a (checked) command at the current step and applies its effect on the robot
    /// (drive, stop; the runner handles the rest).
    pub fn apply(&mut self, command: &ClientMessage) {
        self.log.push((self.sim.steps(), command.clone()));
        if let Some(applied) = apply_drive(&mut self.sim, command) {
            self.operator = Some(applied);
        }
    }

    /// Advances one step (unless finished); returns the events it produced.
    pub fn step(&mut self) -> &[Event] {
        if self.sim.is_finished() {
            return &[];
        }
        let before = self.sim.events().len();
        self.sim.step();
        self.sim.events().get(before..).unwrap_or_default()
    }

    /// Whether it has stepped since it was last saved.
    pub fn needs_saving(&self) -> bool {
        self.sim.steps() > 0 && self.saved_at_step != Some(self.sim.steps())
    }

    /// The command log so far, ended at the current step.
    pub fn command_log(&self) -> CommandLog {
        let end = if self.sim.is_finished() {
            RunEnd::Finished
        } else {
            RunEnd::Interrupted
        };
        CommandLog {
            commands: self.log.clone(),
            end: Some((self.sim.steps(), end)),
        }
    }

    /// The outcome so far: the run's, or marked interrupted before its end.
    pub fn outcome(&mut self) -> Outcome {
        if !self.sim.is_finished() {
            self.sim.interrupt();
        }
        self.sim.outcome()
    }

    /// Writes the run folder `setup.out_dir/session-NNN/` (events, trajectory, report,
    /// scenario, command log; each file atomically) and returns it with the outcome. The
    /// session goes on.
    pub fn save(&mut self, setup: &SessionSetup) -> Result<(PathBuf, Outcome)> {
        let dir = setup.out_dir.join(session_dir_name(self.number));
        std::fs::create_dir_all(&dir).map_err(|e| cloud::CloudError::io(&dir, e))?;
        let outcome = self.outcome();
        sim::write_outputs(&dir, &outcome, &ReportConfig::default())?;
        cloud::write_bytes_atomically(&dir.join("scenario.toml"), setup.scenario_toml.as_bytes())?;
        self.command_log().write(&dir.join("commands.jsonl"))?;
        self.saved_at_step = Some(self.sim.steps());
        Ok((dir, outcome))
    }
}
