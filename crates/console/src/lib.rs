//! semsim's operator console: a local web server that shows the semantic world in 3D in a
//! browser, lets a person drive the robot live while the scenario's rules judge it, and saves
//! every session as a run (`semsim console`).
//!
//! * **Server** ([`Console`]): axum on tokio, bound to `127.0.0.1:8080` by default
//!   ([`ConsoleConfig`]). It serves the page (`/`, its script and the vendored three.js, all
//!   compiled into the binary), the world as glTF binary (`/world.glb`, interop's export with
//!   the robot at its start), its entities (`/api/world.json`: id, class, name, label,
//!   relations), the optional point-cloud layer ([`CloudLayer`]: `/api/cloud.json` and the
//!   binary `/api/cloud.bin`, at most [`MAX_CLOUD_POINTS`] points) and a WebSocket (`/ws`),
//!   with TCP_NODELAY on every connection. Nothing a client sends names a file. The page
//!   draws a minimap and a follow camera that keeps in front of walls.
//! * **Simulation**: a thread owns the session's [`sim::Simulation`] and steps it in real
//!   time at the scenario's fixed step, times a speed factor (x0.25 to x10), paused or
//!   stepped on request. The scenario's scripted commands drive the robot until the operator's
//!   first `drive` or `stop`; from then on the operator's command does (clamped to the robot's
//!   limits). States go out 30 times a second, events as they happen, the rules' live state
//!   when it changes, the verdict when the run ends.
//! * **Protocol** ([`protocol`]): typed JSON messages with a `type`; unknown types or
//!   fields, malformed JSON, messages over 64 KiB, out-of-range numbers and messages beyond
//!   100 a second get an `error` reply and change nothing else. WebSocket upgrades are refused
//!   (403) unless the `Origin` header is absent or the console's own (`http://HOST:PORT`, and
//!   `http://localhost:PORT` on loopback, or one of [`ConsoleConfig::allowed_origins`]).
//! * **Several tabs**: every connection sees the same session. The first connection drives;
//!   the others watch, and their commands get an `error` reply. When the driver leaves, the
//!   next connection (in the order they came) drives, and is told so by a `role` message; an
//!   operator-driven robot stops when its driver leaves.
//! * **Sessions are runs** ([`Session`]): when the run ends, on `save`, on `reset` (which then
//!   starts the next session) and when the console stops (Ctrl-C), the session is written to
//!   `OUT/session-NNN/` as `semsim simulate` writes a run (`events.jsonl`, `trajectory.csv`,
//!   `doors.csv`, `report.md`, `scenario.toml`; each file atomically) plus `commands.jsonl`, the operator's
//!   commands stamped with the step they were applied before ([`CommandLog`]). A session saved
//!   before its end has an interrupted verdict. [`replay`] runs the log again and gives the
//!   same events, bit for bit (`semsim simulate --replay`).
//! * **Reports** ([`report_html`]): a run folder ([`RecordedRun`]) as one self-contained HTML
//!   file (the world, the trajectory with its events marked, the verdict and rules, a time
//!   slider that moves the robot and swings the doors, optionally a small cloud) that opens from disk with no server (`semsim report RUN_DIR --html F`).
//! * **Replays** ([`RunConsole`]): the console serving a recorded run instead of a live
//!   session (`semsim console --run RUN_DIR`): the page gets it from `/api/run.json` and
//!   replays it with a time slider, play/pause and speed; every WebSocket message is refused.
//!   Both consoles run from a program without a runtime through [`serve_blocking`].
//! * **Inputs** ([`ConsoleInputs`]): which world and cloud a console or report shows, from what
//!   the user named (`--map` as a file or an output folder, `--building`, `--run`, `--cloud`)
//!   or, where nothing is named, from what lies beside the map or run folder ([`Located`],
//!   [`WorldFile`]).
//!
//! ```
//! use console::protocol::ClientMessage;
//!
//! let drive = ClientMessage::parse(r#"{"type":"drive","linear_m_s":0.4,"angular_rad_s":0.2}"#);
//! assert_eq!(drive, Ok(ClientMessage::Drive { linear_m_s: 0.4, angular_rad_s: 0.2 }));
//! // Unknown fields and out-of-range numbers are refused with a message for the reply.
//! assert!(ClientMessage::parse(r#"{"type":"stop","now":true}"#).is_err());
//! assert!(ClientMessage::parse(r#"{"type":"speed","factor":100}"#).is_err());
//! assert!(console::ConsoleConfig::default().listen.ip().is_loopback());
//! ```

#![warn(missing_docs)]

mod app;
mod assets;
mod blocking;
mod cloud_layer;
mod config;
mod error;
mod http;
mod hub;
mod inputs;
mod log;
pub mod protocol;
mod rate;
mod replay;
mod report;
mod run;
mod run_server;
mod runner;
mod server;
mod session;
mod socket;
mod world;

pub use blocking::{serve_blocking, Serve};
pub use cloud_layer::{CloudInfo, CloudLayer, MAX_CLOUD_POINTS};
pub use config::ConsoleConfig;
pub use error::{ConsoleError, Result};
pub use inputs::{ConsoleInputs, Located, WorldFile};
pub use log::{CommandLog, RunEnd};
pub use replay::replay;
pub use report::{base64, report_html, write_report, REPORT_CLOUD_POINTS};
pub use run::{
    doors_from_text, events_from_text, parse_doors, parse_events, parse_trajectory,
    report_from_text, trajectory_from_text, RecordedRun, ReportSummary, RuleRow, TrackPoint,
    TRAJECTORY_HEADER,
};
pub use run_server::{RunConsole, RunSetup, REPLAY_REFUSAL};
pub use server::Console;
pub use session::{first_free_session, session_dir_name, Session, SessionSetup, RUN_FILES};
pub use world::ConsoleWorld;

/// Byte-slice entry points of the console's readers for the fuzz targets (`fuzz/formats/`):
/// what the path readers run after reading the file. Bytes that are not UTF-8 are refused as
/// the path readers refuse them.
#[doc(hidden)]
pub mod fuzzing {
    use crate::error::{ConsoleError, Result};
    use crate::{CommandLog, ReportSummary, TrackPoint};
    use serde_json::{Map, Value};
    use sim::DoorTrack;
    use std::path::Path;

    fn text<'a>(path: &Path, bytes: &'a [u8]) -> Result<&'a str> {
        std::str::from_utf8(bytes).map_err(|e| ConsoleError::RunFolder {
            path: path.to_path_buf(),
            line: None,
            msg: e.to_string(),
        })
    }

    /// A run folder's `doors.csv`.
    pub fn read_doors_bytes(path: &Path, bytes: &[u8]) -> Result<DoorTrack> {
        crate::doors_from_text(path, text(path, bytes)?)
    }

    /// A run folder's `trajectory.csv`.
    pub fn read_trajectory_bytes(path: &Path, bytes: &[u8]) -> Result<Vec<TrackPoint>> {
        crate::trajectory_from_text(path, text(path, bytes)?)
    }

    /// A run folder's `events.jsonl`.
    pub fn read_events_bytes(path: &Path, bytes: &[u8]) -> Result<Vec<Map<String, Value>>> {
        crate::events_from_text(path, text(path, bytes)?)
    }

    /// A run folder's `report.md`.
    pub fn read_report_bytes(path: &Path, bytes: &[u8]) -> Result<ReportSummary> {
        crate::report_from_text(path, text(path, bytes)?)
    }

    /// A session's `commands.jsonl`.
    pub fn read_command_log_bytes(path: &Path, bytes: &[u8]) -> Result<CommandLog> {
        CommandLog::parse(text(path, bytes)?, path)
    }
}
