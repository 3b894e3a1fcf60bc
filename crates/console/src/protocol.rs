//! The WebSocket protocol: typed JSON messages, one per WebSocket text message, each an object
//! whose `type` names it. Unknown types and unknown fields are refused, numbers are checked.
//!
//! Client to server ([`ClientMessage`]): `drive {linear_m_s, angular_rad_s}`, `stop`, `pause`,
//! `resume`, `step`, `speed {factor}`, `reset`, `save`.
//!
//! Server to client ([`ServerMessage`]): `hello` (protocol version, the connection's id and
//! role, the world, the scenario and its rules, the limits), `state` (30 times a second),
//! `event` (each semantic event as it happens), `rules` (the rules' live state, when it
//! changes), `verdict` (when a run ends or is saved), `role` (this connection's role changed),
//! `error {message}` (a message was refused; nothing else happens).

use serde::{Deserialize, Serialize};
use sim::{Event, LiveRule, LiveState, Verdict};

/// The protocol's version, in `hello`.
pub const PROTOCOL_VERSION: u32 = 1;
/// The largest `|linear_m_s|` a `drive` may ask (m/s); the robot's own limit clamps it further.
pub const MAX_LINEAR_M_S: f64 = 10.0;
/// The largest `|angular_rad_s|` a `drive` may ask (rad/s); the robot's own limit clamps it.
pub const MAX_ANGULAR_RAD_S: f64 = 10.0;
/// The slowest real-time factor (`speed`).
pub const MIN_SPEED_FACTOR: f64 = 0.25;
/// The fastest real-time factor (`speed`).
pub const MAX_SPEED_FACTOR: f64 = 10.0;

/// A message from a client (the page). The variants without fields are empty structs so that
/// fields beside their `type` are refused too (serde ignores them for unit variants).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum ClientMessage {
    /// Drive at this speed and yaw rate until told otherwise (the operator takes over from
    /// the scenario's scripted commands; clamped to the robot's limits).
    Drive {
        /// Forward speed (m/s, negative backwards), at most [`MAX_LINEAR_M_S`] either way.
        linear_m_s: f64,
        /// Yaw rate (rad/s, counter-clockwise positive), at most [`MAX_ANGULAR_RAD_S`] either way.
        angular_rad_s: f64,
    },
    /// Stop the robot (a `drive` at zero).
    Stop {},
    /// Pause the simulation.
    Pause {},
    /// Resume in real time (times the speed factor).
    Resume {},
    /// Advance one fixed step and pause.
    Step {},
    /// Run at `factor` times real time.
    Speed {
        /// From [`MIN_SPEED_FACTOR`] to [`MAX_SPEED_FACTOR`].
        factor: f64,
    },
    /// End this session (it is saved as a run if it took a step) and start a new one.
    Reset {},
    /// Save the session so far as a run folder (the session goes on).
    Save {},
}

impl ClientMessage {
    /// Parses and checks one message; the error is the reply's text.
    pub fn parse(text: &str) -> Result<ClientMessage, String> {
        let m: ClientMessage = serde_json::from_str(text).map_err(|e| {
            let mut msg = format!("malformed message: {e}");
            truncate(&mut msg, 300);
            msg
        })?;
        m.check()?;
        Ok(m)
    }

    /// Checks the numbers.
    pub fn check(&self) -> Result<(), String> {
        let within = |x: f64, max: f64| x.is_finite() && x.abs() <= max;
        match *self {
            ClientMessage::Drive { linear_m_s, .. } if !within(linear_m_s, MAX_LINEAR_M_S) => {
                Err(format!(
                    "drive: linear_m_s = {linear_m_s} is out of range (-{MAX_LINEAR_M_S} to {MAX_LINEAR_M_S} m/s)"
                ))
            }
            ClientMessage::Drive { angular_rad_s, .. }
                if !within(angular_rad_s, MAX_ANGULAR_RAD_S) =>
            {
                Err(format!(
                    "drive: angular_rad_s = {angular_rad_s} is out of range (-{MAX_ANGULAR_RAD_S} to {MAX_ANGULAR_RAD_S} rad/s)"
                ))
            }
            ClientMessage::Speed { factor }
                if !(MIN_SPEED_FACTOR..=MAX_SPEED_FACTOR).contains(&factor) =>
            {
                Err(format!(
                    "speed: factor = {factor} is out of range ({MIN_SPEED_FACTOR} to {MAX_SPEED_FACTOR})"
                ))
            }
            _ => Ok(()),
        }
    }

    /// Whether the message moves the robot (what a replay applies).
    pub fn drives(&self) -> bool {
        matches!(self, ClientMessage::Drive { .. } | ClientMessage::Stop {})
    }
}

/// Cuts `s` to at most `max` bytes (at a character boundary), marking the cut.
fn truncate(s: &mut String, max: usize) {
    if s.len() > max {
        let mut cut = max;
        while !s.is_char_boundary(cut) {
            cut -= 1;
        }
        s.truncate(cut);
        s.push_str("...");
    }
}

/// A connection's role: the first connection drives, the others watch.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Role {
    /// Its commands are applied.
    Driver,
    /// It sees everything; its commands get error replies.
    Watcher,
}

/// The robot as `hello` describes it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RobotSummary {
    /// Its entity id (in states and events).
    pub entity: u32,
    /// Its name in events.
    pub name: String,
    /// The robot model's name.
    pub model: String,
    /// Top speed (m/s): drive commands are clamped to it.
    pub max_speed_mps: f64,
    /// Top yaw rate (rad/s).
    pub max_yaw_rate_radps: f64,
}

/// The world as `hello` describes it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WorldSummary {
    /// Its name.
    pub name: String,
    /// Entities (robot excluded).
    pub entities: usize,
    /// Fixed boxes.
    pub fixed_boxes: usize,
    /// Hinged doors.
    pub doors: usize,
    /// Door free spaces.
    pub free_spaces: usize,
    /// Staircases.
    pub stairs: usize,
    /// The robot.
    pub robot: RobotSummary,
}

/// The scenario as `hello` describes it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ScenarioSummary {
    /// Its name.
    pub name: String,
    /// Its description.
    pub description: String,
    /// When a run ends (simulated s).
    pub time_limit_s: f64,
    /// The fixed step (s).
    pub dt_secs: f64,
    /// The rules, live.
    pub rules: Vec<LiveRule>,
}

/// The limits a client must keep, as `hello` gives them.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Limits {
    /// The largest message answered (bytes).
    pub max_message_bytes: usize,
    /// Messages per second.
    pub max_messages_per_s: u32,
    /// See [`MAX_LINEAR_M_S`].
    pub max_linear_m_s: f64,
    /// See [`MAX_ANGULAR_RAD_S`].
    pub max_angular_rad_s: f64,
    /// See [`MIN_SPEED_FACTOR`].
    pub min_speed_factor: f64,
    /// See [`MAX_SPEED_FACTOR`].
    pub max_speed_factor: f64,
}

/// The operator's drive command in a state.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DriveCommand {
    /// Forward speed (m/s), as clamped.
    pub linear_m_s: f64,
    /// Yaw rate (rad/s), as clamped.
    pub angular_rad_s: f64,
}

/// A message to clients.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum ServerMessage {
    /// The first message of every connection.
    Hello {
        /// [`PROTOCOL_VERSION`].
        protocol: u32,
        /// This connection's id.
        connection: u64,
        /// This connection's role.
        role: Role,
        /// The session's number (1 for the first; `reset` starts the next).
        session: u32,
        /// The world.
        world: WorldSummary,
        /// The scenario.
        scenario: ScenarioSummary,
        /// The limits.
        limits: Limits,
    },
    /// The simulation now.
    State {
        /// The session's number.
        session: u32,
        /// Paused?
        paused: bool,
        /// The real-time factor.
        speed: f64,
        /// Whether the run has ended (time limit, or goals met).
        finished: bool,
        /// The operator's command, while the operator drives (else the scenario does).
        operator: Option<DriveCommand>,
        /// Time, robot, doors, contacts.
        #[serde(flatten)]
        live: LiveState,
    },
    /// A semantic event.
    Event {
        /// The session's number.
        session: u32,
        /// The event.
        event: Event,
    },
    /// The rules' live state.
    Rules {
        /// The session's number.
        session: u32,
        /// Each rule.
        rules: Vec<LiveRule>,
    },
    /// The verdict: when the run ends, or when it is saved before its end (then marked
    /// interrupted).
    Verdict {
        /// The session's number.
        session: u32,
        /// The verdict.
        verdict: Verdict,
        /// The run folder's name, if it was saved.
        saved_as: Option<String>,
    },
    /// This connection's role changed (the driver left).
    Role {
        /// The new role.
        role: Role,
    },
    /// A message was refused.
    Error {
        /// Why.
        message: String,
    },
}

impl ServerMessage {
    /// The message as JSON text.
    pub fn to_json(&self) -> String {
        // Serialising these types cannot fail (string keys, no maps with other keys); a
        // failure would still give a valid message.
        serde_json::to_string(self).unwrap_or_else(|e| {
            format!(
                r#"{{"type":"error","message":"cannot serialise a message: {}"}}"#,
                e.to_string().replace(['"', '\\'], "'")
            )
        })
    }

    /// An error reply.
    pub fn error(message: impl Into<String>) -> ServerMessage {
        ServerMessage::Error {
            message: message.into(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_parse_and_unknown_ones_are_refused() {
        assert_eq!(
            ClientMessage::parse(r#"{"type":"drive","linear_m_s":0.5,"angular_rad_s":-0.1}"#),
            Ok(ClientMessage::Drive {
                linear_m_s: 0.5,
                angular_rad_s: -0.1
            })
        );
        assert_eq!(
            ClientMessage::parse(r#"{"type":"stop"}"#),
            Ok(ClientMessage::Stop {})
        );
        for bad in [
            r#"{"type":"fly"}"#,
            r#"{"type":"stop","now":true}"#,
            r#"{"type":"drive","linear_m_s":0.5}"#,
            r#"{"type":"drive","linear_m_s":0.5,"angular_rad_s":0,"x":1}"#,
            r#"{"type":"drive","linear_m_s":50,"angular_rad_s":0}"#,
            r#"{"type":"speed","factor":0.1}"#,
            r#"{"type":"speed","factor":11}"#,
            r#"{"linear_m_s":0.5}"#,
            "not json",
            "[]",
        ] {
            assert!(ClientMessage::parse(bad).is_err(), "{bad} was accepted");
        }
    }

    #[test]
    fn long_errors_are_cut() {
        let text = format!(r#"{{"type":"{}"}}"#, "x".repeat(5000));
        let e = ClientMessage::parse(&text).expect_err("unknown type");
        assert!(e.len() < 400, "{}", e.len());
    }

    #[test]
    fn server_messages_carry_their_type() {
        let v: serde_json::Value =
            serde_json::from_str(&ServerMessage::error("nope").to_json()).expect("json");
        assert_eq!(v["type"], "error");
        assert_eq!(v["message"], "nope");
    }
}
