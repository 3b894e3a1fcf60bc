//! The operator's command log, `commands.jsonl`: one JSON object a line, each command as the
//! client sent it (see [`ClientMessage`]) stamped with the simulation step it was applied
//! before (`{"step":120,"command":{"type":"drive","linear_m_s":0.5,"angular_rad_s":0.0}}`),
//! and a last line saying where the run ended and how (`{"step":900,"end":"interrupted"}`,
//! or `"finished"` at the scenario's end). Applying the drive commands at the same steps
//! replays the run bit for bit ([`crate::replay`]).

use crate::error::{ConsoleError, Result};
use crate::protocol::ClientMessage;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// How a logged run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RunEnd {
    /// At the scenario's end (time limit, or goals met with `stop_when_goals_met`).
    Finished,
    /// Saved before its end (Ctrl-C, `save`, `reset`).
    Interrupted,
}

/// A session's commands.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CommandLog {
    /// (step, command), in the order applied; steps never decrease.
    pub commands: Vec<(u64, ClientMessage)>,
    /// The step the run ended at and how, once it ended.
    pub end: Option<(u64, RunEnd)>,
}

/// One line of the file.
#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Line {
    step: u64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    command: Option<ClientMessage>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    end: Option<RunEnd>,
}

impl CommandLog {
    /// The log as JSON lines.
    pub fn to_jsonl(&self) -> String {
        let mut out = String::new();
        let lines = self
            .commands
            .iter()
            .map(|(step, c)| Line {
                step: *step,
                command: Some(c.clone()),
                end: None,
            })
            .chain(self.end.map(|(step, end)| Line {
                step,
                command: None,
                end: Some(end),
            }));
        for line in lines {
            if let Ok(text) = serde_json::to_string(&line) {
                out.push_str(&text);
                out.push('\n');
            }
        }
        out
    }

    /// Parses a log; `path` names it in errors.
    pub fn parse(text: &str, path: &Path) -> Result<CommandLog> {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let bad = |line: usize, msg: String| ConsoleError::CommandLog {
            path: path.to_path_buf(),
            line,
            msg,
        };
        let mut log = CommandLog::default();
        let mut last_step = 0;
        for (i, raw) in text.lines().enumerate() {
            let n = i + 1;
            if raw.trim().is_empty() {
                continue;
            }
            if log.end.is_some() {
                return Err(bad(n, "a line after the end line".into()));
            }
            let line: Line = serde_json::from_str(raw).map_err(|e| bad(n, e.to_string()))?;
            if line.step < last_step {
                return Err(bad(
                    n,
                    format!("step {} comes after step {last_step}", line.step),
                ));
            }
            last_step = line.step;
            match (line.command, line.end) {
                (Some(ClientMessage::Reset {}), None) => {
                    return Err(bad(n, "reset starts a new session: not in a log".into()))
                }
                (Some(c), None) => {
                    c.check().map_err(|e| bad(n, e))?;
                    log.commands.push((line.step, c));
                }
                (None, Some(end)) => log.end = Some((line.step, end)),
                _ => {
                    return Err(bad(
                        n,
                        "expected either \"command\" or \"end\" beside \"step\"".into(),
                    ))
                }
            }
        }
        Ok(log)
    }

    /// Reads a log file.
    pub fn load(path: &Path) -> Result<CommandLog> {
        let text = std::fs::read_to_string(path).map_err(|e| cloud::CloudError::io(path, e))?;
        CommandLog::parse(&text, path)
    }

    /// Writes the log atomically.
    pub fn write(&self, path: &Path) -> Result<()> {
        cloud::write_bytes_atomically(path, self.to_jsonl().as_bytes())?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_log_round_trips() {
        let log = CommandLog {
            commands: vec![
                (
                    3,
                    ClientMessage::Drive {
                        linear_m_s: 0.5,
                        angular_rad_s: -0.25,
                    },
                ),
                (3, ClientMessage::Pause {}),
                (40, ClientMessage::Stop {}),
            ],
            end: Some((41, RunEnd::Interrupted)),
        };
        let text = log.to_jsonl();
        assert!(text.starts_with(r#"{"step":3,"command":{"type":"drive","linear_m_s":0.5"#));
        assert!(
            text.ends_with("{\"step\":41,\"end\":\"interrupted\"}\n"),
            "{text}"
        );
        assert_eq!(
            CommandLog::parse(&text, Path::new("c.jsonl")).expect("parses"),
            log
        );
    }

    #[test]
    fn bad_logs_name_the_line() {
        let p = Path::new("c.jsonl");
        for (text, line) in [
            ("{\"step\":5,\"command\":{\"type\":\"stop\"}}\n{\"step\":4,\"command\":{\"type\":\"stop\"}}", 2),
            ("{\"step\":5,\"command\":{\"type\":\"reset\"}}", 1),
            ("{\"step\":5}", 1),
            ("{\"step\":5,\"end\":\"finished\"}\n{\"step\":6,\"command\":{\"type\":\"stop\"}}", 2),
            ("\n{\"step\":1,\"command\":{\"type\":\"drive\",\"linear_m_s\":99,\"angular_rad_s\":0}}", 2),
            ("{\"step\":1,\"command\":{\"type\":\"stop\"},\"x\":1}", 1),
        ] {
            match CommandLog::parse(text, p) {
                Err(ConsoleError::CommandLog { line: l, .. }) => assert_eq!(l, line, "{text}"),
                other => panic!("{text}: {other:?}"),
            }
        }
    }
}
