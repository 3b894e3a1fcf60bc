//! The simulation thread: it owns the session, steps it in real time (times the speed
//! factor) at the scenario's fixed step, applies the driver's commands between steps, and
//! publishes states at the state rate, events as they happen, the rules when they change and
//! the verdict when the run ends or is saved. A run that has ended is saved at once.

use crate::error::{ConsoleError, Result};
use crate::hub::{Hub, Keep};
use crate::protocol::{ClientMessage, ServerMessage};
use crate::session::{Session, SessionSetup};
use sim::LiveRule;
use std::path::PathBuf;
use std::sync::mpsc::{Receiver, RecvTimeoutError};
use std::sync::Arc;
use std::time::{Duration, Instant};
use tokio::sync::oneshot;

/// What the thread is told.
pub(crate) enum Control {
    /// A checked command of the driving connection; the reply is `Err(message)` when it
    /// cannot be carried out now.
    Command {
        command: ClientMessage,
        reply: oneshot::Sender<Result<(), String>>,
    },
    /// The driving connection left: an operator-driven robot stops.
    DriverLeft,
    /// Save the session (if it stepped since its last save) and end; the reply lists every
    /// run folder saved.
    Shutdown {
        reply: oneshot::Sender<Result<Vec<PathBuf>>>,
    },
}

/// Simulated time the thread may fall behind real time by before it stops catching up (s).
const MAX_LAG_S: f64 = 0.25;
/// The rules' reasons (not their states) are sent again at most this often.
const RULE_REASONS_EVERY: Duration = Duration::from_millis(500);

/// See the module docs.
pub(crate) struct Runner {
    setup: Arc<SessionSetup>,
    hub: Arc<Hub>,
    session: Session,
    paused: bool,
    speed: f64,
    /// Real time and step count that real-time pacing counts from.
    anchor: (Instant, u64),
    state_period: Duration,
    next_state: Instant,
    rules: Vec<LiveRule>,
    rules_sent: Instant,
    finish_reported: bool,
    saved: Vec<PathBuf>,
}

impl Runner {
    /// Starts session `number` (errors: the scenario does not fit the world).
    pub(crate) fn new(
        setup: Arc<SessionSetup>,
        hub: Arc<Hub>,
        number: u32,
        state_rate_hz: f64,
    ) -> Result<Runner> {
        let session = Session::new(&setup, number)?;
        let now = Instant::now();
        Ok(Runner {
            rules: session.sim().live_rules(),
            setup,
            hub,
            session,
            paused: false,
            speed: 1.0,
            anchor: (now, 0),
            state_period: Duration::from_secs_f64(1.0 / state_rate_hz),
            next_state: now,
            rules_sent: now,
            finish_reported: false,
            saved: vec![],
        })
    }

    /// The first session's live rules.
    pub(crate) fn rules(&self) -> Vec<LiveRule> {
        self.rules.clone()
    }

    /// The thread's loop; returns when told to shut down (or when every sender is gone).
    pub(crate) fn run(mut self, controls: Receiver<Control>) {
        loop {
            let timeout = self
                .next_deadline()
                .saturating_duration_since(Instant::now());
            match controls.recv_timeout(timeout) {
                Ok(Control::Shutdown { reply }) => {
                    let _ = reply.send(self.shut_down());
                    return;
                }
                Ok(c) => self.handle(c),
                Err(RecvTimeoutError::Timeout) => {}
                Err(RecvTimeoutError::Disconnected) => {
                    let _ = self.shut_down();
                    return;
                }
            }
            self.advance();
            self.report_finish();
            let now = Instant::now();
            if now >= self.next_state {
                self.publish_state();
                self.publish_rules(false);
                self.next_state += self.state_period;
                if self.next_state < now {
                    self.next_state = now + self.state_period;
                }
            }
        }
    }

    fn dt_secs(&self) -> f64 {
        self.session.sim().world().dt_secs()
    }

    fn running(&self) -> bool {
        !self.paused && !self.session.is_finished()
    }

    fn reanchor(&mut self) {
        self.anchor = (Instant::now(), self.session.sim().steps());
    }

    /// When the next step is due while running, or the next state.
    fn next_deadline(&self) -> Instant {
        if !self.running() {
            return self.next_state;
        }
        let step_secs = self.dt_secs() / self.speed;
        next_step_due(self.anchor, self.session.sim().steps(), step_secs).min(self.next_state)
    }

    /// Takes the steps real time asks for.
    fn advance(&mut self) {
        if !self.running() {
            return;
        }
        let elapsed_s = self.anchor.0.elapsed().as_secs_f64();
        let due = self.anchor.1 + (elapsed_s * self.speed / self.dt_secs()) as u64;
        let max_batch = ((MAX_LAG_S * self.speed / self.dt_secs()) as u64).max(1);
        let steps = self.session.sim().steps();
        let mut n = due.saturating_sub(steps);
        if n > max_batch {
            // Too slow for real time at this speed: drop the lag instead of racing after it.
            n = max_batch;
            self.anchor = (Instant::now(), steps + n);
        }
        // Steps in slices of at most a state period, so that states and commands are not
        // held up by a long batch; the rest is due at once in the next turn of the loop.
        let started = Instant::now();
        for _ in 0..n {
            if self.session.is_finished() || started.elapsed() >= self.state_period {
                break;
            }
            self.step_once();
        }
    }

    fn step_once(&mut self) {
        let number = self.session.number();
        let events = self.session.step().to_vec();
        for event in events {
            let m = ServerMessage::Event {
                session: number,
                event,
            };
            self.hub.publish(&m, Keep::Backlog);
        }
    }

    /// Once the run has ended: rules, saved run, verdict.
    fn report_finish(&mut self) {
        if self.finish_reported || !self.session.is_finished() {
            return;
        }
        self.finish_reported = true;
        self.publish_state();
        self.publish_rules(true);
        if let Err(e) = self.save() {
            self.hub.publish(
                &ServerMessage::error(format!("saving the run: {e}")),
                Keep::Nothing,
            );
        }
    }

    /// Saves the session and publishes its verdict.
    fn save(&mut self) -> Result<PathBuf> {
        let (dir, outcome) = self.session.save(&self.setup)?;
        if !self.saved.contains(&dir) {
            self.saved.push(dir.clone());
        }
        let m = ServerMessage::Verdict {
            session: self.session.number(),
            verdict: outcome.verdict,
            saved_as: dir.file_name().map(|n| n.to_string_lossy().into_owned()),
        };
        self.hub.publish(&m, Keep::Backlog);
        Ok(dir)
    }

    fn publish_state(&self) {
        let m = ServerMessage::State {
            session: self.session.number(),
            paused: self.paused,
            speed: self.speed,
            finished: self.session.is_finished(),
            operator: self.session.operator(),
            live: self.session.sim().live_state(),
        };
        self.hub.publish(&m, Keep::State);
    }

    /// Publishes the rules if their states changed (or, at most every
    /// [`RULE_REASONS_EVERY`], their reasons; or always when `force`).
    fn publish_rules(&mut self, force: bool) {
        let now_rules = self.session.sim().live_rules();
        let states_changed = now_rules.len() != self.rules.len()
            || now_rules
                .iter()
                .zip(&self.rules)
                .any(|(a, b)| a.state != b.state);
        let reasons_changed = now_rules != self.rules;
        if force
            || states_changed
            || (reasons_changed && self.rules_sent.elapsed() >= RULE_REASONS_EVERY)
        {
            self.rules = now_rules.clone();
            self.rules_sent = Instant::now();
            let m = ServerMessage::Rules {
                session: self.session.number(),
                rules: now_rules,
            };
            self.hub.publish(&m, Keep::Nothing);
        }
    }

    fn handle(&mut self, control: Control) {
        match control {
            Control::Command { command, reply } => {
                let _ = reply.send(self.command(command));
            }
            Control::DriverLeft => {
                let driving = self
                    .session
                    .operator()
                    .is_some_and(|c| c.linear_m_s != 0.0 || c.angular_rad_s != 0.0);
                if driving && !self.session.is_finished() {
                    self.session.apply(&ClientMessage::Stop {});
                }
            }
            Control::Shutdown { .. } => {}
        }
    }

    fn command(&mut self, command: ClientMessage) -> std::result::Result<(), String> {
        let ended = "the run has ended: reset to start a new one";
        match command {
            ClientMessage::Drive { .. } | ClientMessage::Stop {} => {
                if self.session.is_finished() {
                    return Err(ended.into());
                }
                self.session.apply(&command);
            }
            ClientMessage::Pause {} => {
                self.session.apply(&command);
                self.paused = true;
            }
            ClientMessage::Resume {} => {
                self.session.apply(&command);
                self.paused = false;
                self.reanchor();
            }
            ClientMessage::Speed { factor } => {
                self.session.apply(&command);
                self.speed = factor;
                self.reanchor();
            }
            ClientMessage::Step {} => {
                if self.session.is_finished() {
                    return Err(ended.into());
                }
                self.session.apply(&command);
                self.paused = true;
                self.step_once();
                self.publish_state();
            }
            ClientMessage::Save {} => {
                self.session.apply(&command);
                self.save().map_err(|e| format!("saving the run: {e}"))?;
            }
            ClientMessage::Reset {} => self.reset().map_err(|e| format!("reset: {e}"))?,
        }
        Ok(())
    }

    /// Ends the session (saved if it stepped since its last save) and starts the next.
    fn reset(&mut self) -> Result<()> {
        if self.session.needs_saving() {
            self.save()?;
        }
        let next = Session::new(&self.setup, self.session.number() + 1)?;
        self.session = next;
        self.finish_reported = false;
        self.paused = false;
        self.reanchor();
        self.rules = self.session.sim().live_rules();
        self.hub
            .new_session(self.session.number(), self.rules.clone());
        self.publish_state();
        self.publish_rules(true);
        Ok(())
    }

    fn shut_down(&mut self) -> Result<Vec<PathBuf>> {
        if self.session.needs_saving() {
            self.save()?;
        }
        Ok(std::mem::take(&mut self.saved))
    }
}

/// When the step after `steps` is due, real-time pacing counting from `anchor` (a real instant
/// and the step count then) at `step_secs` real seconds a step. A thread that dropped its lag
/// re-anchors ahead of the steps it has taken (the rest are due at once): then the next step is
/// due at the anchor, not before it (a subtraction that overflowed there stopped the thread).
fn next_step_due(anchor: (Instant, u64), steps: u64, step_secs: f64) -> Instant {
    let ahead = (steps + 1).saturating_sub(anchor.1);
    anchor.0 + Duration::from_secs_f64(ahead as f64 * step_secs)
}

/// Spawns the thread.
pub(crate) fn spawn(
    runner: Runner,
    controls: Receiver<Control>,
) -> Result<std::thread::JoinHandle<()>> {
    let hub = Arc::clone(&runner.hub);
    std::thread::Builder::new()
        .name("semsim-console-sim".into())
        .spawn(move || {
            // A bug that stops the thread is said to every page (and on stderr, by the panic
            // hook), not left as a world frozen without a word.
            let run =
                std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| runner.run(controls)));
            if run.is_err() {
                let m = "the simulation stopped (a bug in semsim, its message is on the console's \
                         stderr); the world shown is its last state";
                hub.publish(&ServerMessage::error(m), Keep::Backlog);
            }
        })
        .map_err(|_| ConsoleError::SimulationThread)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_thread_behind_its_anchor_takes_its_next_step_at_once() {
        let now = Instant::now();
        // Re-anchored at step 40 after taking 12 of the steps due: step 13 is due now.
        assert_eq!(next_step_due((now, 40), 12, 0.01), now);
        // On time: step 41 after 40 taken, one step period after the anchor.
        assert_eq!(
            next_step_due((now, 40), 40, 0.01),
            now + Duration::from_secs_f64(0.01)
        );
        assert_eq!(
            next_step_due((now, 40), 49, 0.01),
            now + Duration::from_secs_f64(0.1)
        );
    }
}
