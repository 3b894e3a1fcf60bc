//! Replaying a session: the scenario run again with the operator's drive commands applied
//! before the same steps as in the session, so that its events, trajectory and verdict are the
//! session's, bit for bit (`semsim simulate --replay commands.jsonl`).

use crate::error::Result;
use crate::log::{CommandLog, RunEnd};
use crate::protocol::{ClientMessage, DriveCommand};
use sim::{Outcome, RobotModel, Scenario, Simulation, WorldSpec};

/// Applies a command's effect on the robot (drive, stop; the others do not touch the
/// simulation): the operator drives from the next step on, clamped to the robot's limits.
/// Returns the command as applied.
pub(crate) fn apply_drive(sim: &mut Simulation, command: &ClientMessage) -> Option<DriveCommand> {
    let (v, w) = match *command {
        ClientMessage::Drive {
            linear_m_s,
            angular_rad_s,
        } => (linear_m_s, angular_rad_s),
        ClientMessage::Stop {} => (0.0, 0.0),
        _ => return None,
    };
    let (max_v, max_w) = sim.drive_limits();
    let finite = |x: f64| if x.is_finite() { x } else { 0.0 };
    let applied = DriveCommand {
        linear_m_s: finite(v).clamp(-max_v, max_v),
        angular_rad_s: finite(w).clamp(-max_w, max_w),
    };
    sim.set_operator_drive(Some((applied.linear_m_s, applied.angular_rad_s)));
    Some(applied)
}

/// Runs `scenario` in `spec` with `robot`, applying the log's drive commands before the steps
/// they are stamped with, until the log's end (or the scenario's, for a log without one); a
/// log that ended interrupted gives an interrupted verdict, as the session's was.
pub fn replay(
    spec: &WorldSpec,
    scenario: &Scenario,
    robot: &RobotModel,
    log: &CommandLog,
) -> Result<Outcome> {
    let mut sim = Simulation::new(spec, scenario, robot)?;
    let mut next = 0;
    loop {
        while let Some((step, command)) = log.commands.get(next) {
            if *step > sim.steps() {
                break;
            }
            apply_drive(&mut sim, command);
            next += 1;
        }
        let at_end = log.end.is_some_and(|(step, _)| sim.steps() >= step);
        if sim.is_finished() || at_end {
            break;
        }
        sim.step();
    }
    if matches!(log.end, Some((_, RunEnd::Interrupted))) {
        sim.interrupt();
    }
    Ok(sim.outcome())
}
