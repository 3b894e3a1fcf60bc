//! What the HTTP handlers and the WebSocket connections share: the configuration, the hub,
//! the way to the simulation thread, and what `hello` and the world's routes serve.

use crate::config::ConsoleConfig;
use crate::hub::Hub;
use crate::protocol::{Limits, ScenarioSummary, WorldSummary};
use crate::runner::Control;
use std::sync::{mpsc, Arc};
use tokio::sync::watch;

/// What the handlers share.
pub(crate) struct App {
    pub config: ConsoleConfig,
    pub origins: Vec<String>,
    pub hub: Arc<Hub>,
    pub controls: mpsc::Sender<Control>,
    pub world: WorldSummary,
    pub scenario: ScenarioSummary,
    pub limits: Limits,
    pub stop: watch::Receiver<bool>,
}

impl App {
    /// Sends a control to the simulation thread (false if it is gone).
    pub(crate) fn control(&self, c: Control) -> bool {
        self.controls.send(c).is_ok()
    }
}
