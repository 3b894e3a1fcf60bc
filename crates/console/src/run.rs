//! A recorded run folder, as `semsim simulate` and the console's sessions write it: the
//! trajectory (`trajectory.csv`), the doors' angles (`doors.csv`; optional: a folder written
//! before doors were recorded shows them at their initial angle), the events
//! (`events.jsonl`), the verdict and rules (`report.md`) and the scenario (`scenario.toml`). The static HTML report and the console's
//! replay mode (`--run`) show it. Errors name the file (and the line).

use crate::error::{ConsoleError, Result};
use serde::Serialize;
use serde_json::{Map, Value};
use sim::{DoorSample, DoorTrack};
use std::path::{Path, PathBuf};

/// The header `trajectory.csv` starts with.
pub const TRAJECTORY_HEADER: &str = "time_s,x_m,y_m,z_m,roll_deg,pitch_deg,yaw_deg,speed_mps";

/// One row of `trajectory.csv`: time, position, orientation and speed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TrackPoint {
    /// Simulated time (s).
    pub time_s: f64,
    /// Position (m).
    pub x_m: f64,
    /// Position (m).
    pub y_m: f64,
    /// Position (m).
    pub z_m: f64,
    /// Roll (degrees).
    pub roll_deg: f64,
    /// Pitch (degrees).
    pub pitch_deg: f64,
    /// Heading (degrees, 0 = +x, 90 = +y).
    pub yaw_deg: f64,
    /// Speed (m/s).
    pub speed_mps: f64,
}

/// One row of the report's rules table.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct RuleRow {
    /// The rule's name.
    pub rule: String,
    /// `passed`, `FAILED` or `not decided`.
    pub result: String,
    /// When it was decided (s), as the report writes it.
    pub decided_s: String,
    /// Why.
    pub reason: String,
}

/// A run folder, read.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RecordedRun {
    /// The report's title (`Simulation report: NAME`), or the folder's name.
    pub title: String,
    /// The verdict line (`PASSED`, `FAILED`, `FAILED (interrupted at 3 s)`).
    pub verdict: String,
    /// Whether the run passed.
    pub passed: bool,
    /// The rules and their results.
    pub rules: Vec<RuleRow>,
    /// The trajectory, in time order.
    pub trajectory: Vec<TrackPoint>,
    /// The doors' angles over time (empty for a folder without `doors.csv`).
    pub doors: DoorTrack,
    /// Every event, as `events.jsonl` has it (each with a `time_s` and a `kind`).
    pub events: Vec<Map<String, Value>>,
    /// The scenario's TOML text.
    pub scenario_toml: String,
}

fn bad(path: &Path, line: Option<usize>, msg: impl Into<String>) -> ConsoleError {
    ConsoleError::RunFolder {
        path: path.to_path_buf(),
        line,
        msg: msg.into(),
    }
}

fn read(path: &Path) -> Result<String> {
    std::fs::read_to_string(path).map_err(|e| bad(path, None, e.to_string()))
}

impl RecordedRun {
    /// Reads the run folder `dir`: `trajectory.csv`, `events.jsonl`, `report.md` and
    /// `scenario.toml` must be there and well formed.
    pub fn load(dir: &Path) -> Result<RecordedRun> {
        if !dir.is_dir() {
            return Err(bad(dir, None, "not a run folder (no such folder)"));
        }
        let file = |name: &str| -> PathBuf { dir.join(name) };
        let trajectory = parse_trajectory(&file("trajectory.csv"))?;
        let doors_path = file(sim::DOORS_CSV);
        let doors = if doors_path.exists() {
            parse_doors(&doors_path)?
        } else {
            DoorTrack::default()
        };
        let events = parse_events(&file("events.jsonl"))?;
        let report_path = file("report.md");
        let report = report_from_text(&report_path, &read(&report_path)?)?;
        let scenario_toml = read(&file("scenario.toml"))?;
        let title = report.title.unwrap_or_else(|| {
            dir.file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default()
        });
        Ok(RecordedRun {
            title,
            passed: report.verdict.starts_with("PASSED"),
            verdict: report.verdict,
            rules: report.rules,
            trajectory,
            doors,
            events,
            scenario_toml,
        })
    }

    /// The run as JSON for a page (`<` escaped, so it can sit inside a `<script>` element).
    pub fn to_json(&self) -> String {
        serde_json::to_string(self)
            .unwrap_or_else(|_| "{}".into())
            .replace('<', "\\u003c")
    }
}

/// Parses `trajectory.csv`: its header, then rows of 8 finite numbers in time order.
pub fn parse_trajectory(path: &Path) -> Result<Vec<TrackPoint>> {
    trajectory_from_text(path, &read(path)?)
}

/// [`parse_trajectory`] of a file's text; `path` names it in errors.
pub fn trajectory_from_text(path: &Path, text: &str) -> Result<Vec<TrackPoint>> {
    let mut lines = text.lines().enumerate();
    match lines.next() {
        Some((_, h)) if h.trim() == TRAJECTORY_HEADER => {}
        _ => {
            return Err(bad(
                path,
                Some(1),
                format!("expected `{TRAJECTORY_HEADER}`"),
            ))
        }
    }
    let mut out: Vec<TrackPoint> = Vec::new();
    for (i, line) in lines {
        if line.trim().is_empty() {
            continue;
        }
        let n = i + 1;
        let v: Vec<f64> = line
            .split(',')
            .map(|c| c.trim().parse::<f64>().ok().filter(|x| x.is_finite()))
            .collect::<Option<_>>()
            .ok_or_else(|| bad(path, Some(n), format!("not 8 numbers: `{line}`")))?;
        let [time_s, x_m, y_m, z_m, roll_deg, pitch_deg, yaw_deg, speed_mps] = v[..] else {
            return Err(bad(path, Some(n), format!("not 8 numbers: `{line}`")));
        };
        if out.last().is_some_and(|p| time_s < p.time_s) {
            return Err(bad(path, Some(n), "time goes backwards"));
        }
        out.push(TrackPoint {
            time_s,
            x_m,
            y_m,
            z_m,
            roll_deg,
            pitch_deg,
            yaw_deg,
            speed_mps,
        });
    }
    if out.is_empty() {
        return Err(bad(path, None, "no trajectory rows"));
    }
    Ok(out)
}

/// Parses `doors.csv`: `time_s` and columns `door_ID`, then rows of as many finite numbers
/// (degrees) in time order.
pub fn parse_doors(path: &Path) -> Result<DoorTrack> {
    doors_from_text(path, &read(path)?)
}

/// [`parse_doors`] of a file's text; `path` names it in errors.
pub fn doors_from_text(path: &Path, text: &str) -> Result<DoorTrack> {
    let mut lines = text.lines().enumerate();
    let header = lines.next().map(|(_, h)| h.trim()).unwrap_or("");
    let mut columns = header.split(',');
    if columns.next() != Some("time_s") {
        return Err(bad(path, Some(1), "expected `time_s,door_ID,...`"));
    }
    let doors: Vec<u32> = columns
        .map(|c| c.trim().strip_prefix("door_")?.parse::<u32>().ok())
        .collect::<Option<_>>()
        .ok_or_else(|| bad(path, Some(1), "expected `time_s,door_ID,...`"))?;
    let mut samples: Vec<DoorSample> = Vec::new();
    for (i, line) in lines {
        if line.trim().is_empty() {
            continue;
        }
        let n = i + 1;
        let v: Vec<f64> = line
            .split(',')
            .map(|c| c.trim().parse::<f64>().ok().filter(|x| x.is_finite()))
            .collect::<Option<_>>()
            .filter(|v: &Vec<f64>| v.len() == doors.len() + 1)
            .ok_or_else(|| {
                bad(
                    path,
                    Some(n),
                    format!("not {} numbers: `{line}`", doors.len() + 1),
                )
            })?;
        let time_s = v[0];
        if samples.last().is_some_and(|p| time_s < p.time_s) {
            return Err(bad(path, Some(n), "time goes backwards"));
        }
        samples.push(DoorSample {
            time_s,
            angles_deg: v[1..].to_vec(),
        });
    }
    Ok(DoorTrack { doors, samples })
}

/// Parses `events.jsonl`: one JSON object a line, each with a finite `time_s` and a `kind`.
pub fn parse_events(path: &Path) -> Result<Vec<Map<String, Value>>> {
    events_from_text(path, &read(path)?)
}

/// [`parse_events`] of a file's text; `path` names it in errors.
pub fn events_from_text(path: &Path, text: &str) -> Result<Vec<Map<String, Value>>> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let n = i + 1;
        let e: Map<String, Value> =
            serde_json::from_str(line).map_err(|e| bad(path, Some(n), e.to_string()))?;
        let time_ok = e
            .get("time_s")
            .and_then(Value::as_f64)
            .is_some_and(f64::is_finite);
        if !time_ok || !e.get("kind").is_some_and(Value::is_string) {
            return Err(bad(path, Some(n), "an event needs a `time_s` and a `kind`"));
        }
        out.push(e);
    }
    Ok(out)
}

/// What a run folder's `report.md` tells: its title, verdict and rules.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ReportSummary {
    /// The title (`# Simulation report: NAME`), if there is one.
    pub title: Option<String>,
    /// The verdict line (`## Verdict: ...`).
    pub verdict: String,
    /// The rules table.
    pub rules: Vec<RuleRow>,
}

/// Reads a `report.md`'s text: its `## Verdict:` line must be there; `path` names it in errors.
pub fn report_from_text(path: &Path, report: &str) -> Result<ReportSummary> {
    let verdict = report
        .lines()
        .find_map(|l| l.strip_prefix("## Verdict: "))
        .ok_or_else(|| bad(path, None, "no `## Verdict:` line"))?
        .trim()
        .to_string();
    let title = report
        .lines()
        .find_map(|l| l.strip_prefix("# Simulation report: "))
        .map(str::to_string);
    Ok(ReportSummary {
        title,
        verdict,
        rules: parse_rules(report),
    })
}

/// The rules table of a `report.md`: rows `| \`rule\` | result | decided | reason |`.
fn parse_rules(report: &str) -> Vec<RuleRow> {
    report
        .lines()
        .take_while(|l| !l.starts_with("## Timeline"))
        .filter_map(|l| {
            let l = l.strip_prefix("| `")?;
            let (rule, rest) = l.split_once("` | ")?;
            let mut cells = rest.trim_end().trim_end_matches('|').splitn(3, " | ");
            Some(RuleRow {
                rule: rule.to_string(),
                result: cells.next()?.trim().to_string(),
                decided_s: cells.next()?.trim().to_string(),
                reason: cells.next().unwrap_or("").trim().replace("\\|", "|"),
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rules_are_read_from_the_report_table() {
        let md = "# Simulation report: x\n\n## Verdict: PASSED\n\n| rule | result | decided at (s) | reason |\n|---|---|---|---|\n| `goal a` | passed | 3.5 | reached \\| ok |\n\n## Timeline\n\n| `not` | a | rule | row |\n";
        let rules = parse_rules(md);
        assert_eq!(rules.len(), 1);
        assert_eq!(rules[0].rule, "goal a");
        assert_eq!(rules[0].result, "passed");
        assert_eq!(rules[0].decided_s, "3.5");
        assert_eq!(rules[0].reason, "reached | ok");
    }

    #[test]
    fn a_report_without_a_verdict_is_refused_and_a_title_is_optional() {
        let p = Path::new("run/report.md");
        let e = report_from_text(p, "# Simulation report: x\n").expect_err("no verdict");
        assert!(
            e.to_string().starts_with("run/report.md: no `## Verdict:`"),
            "{e}"
        );
        let r = report_from_text(p, "## Verdict: FAILED (interrupted at 3 s)  \n").expect("read");
        assert_eq!(r.title, None);
        assert_eq!(r.verdict, "FAILED (interrupted at 3 s)");
        assert!(r.rules.is_empty());
    }

    #[test]
    fn bad_trajectory_rows_name_the_line() {
        let dir = tempfile::tempdir().expect("tempdir");
        let p = dir.path().join("trajectory.csv");
        std::fs::write(
            &p,
            format!("{TRAJECTORY_HEADER}\n0,1,2,3,4,5,6,7\n0.1,1,2\n"),
        )
        .expect("write");
        let e = parse_trajectory(&p).expect_err("malformed");
        assert!(e.to_string().contains("trajectory.csv:3"), "{e}");
        std::fs::write(&p, "nonsense\n").expect("write");
        assert!(parse_trajectory(&p).is_err());
        let ev = dir.path().join("events.jsonl");
        std::fs::write(&ev, "{\"time_s\":1,\"kind\":\"x\"}\n{\"kind\":\"y\"}\n").expect("write");
        let e = parse_events(&ev).expect_err("no time");
        assert!(e.to_string().contains("events.jsonl:2"), "{e}");
    }

    #[test]
    fn doors_csv_is_read_and_bad_rows_name_the_line() {
        let dir = tempfile::tempdir().expect("tempdir");
        let p = dir.path().join("doors.csv");
        std::fs::write(&p, "time_s,door_4,door_9\n0,0,0\n0.1,12.5,-1\n").expect("write");
        let t = parse_doors(&p).expect("doors");
        assert_eq!(t.doors, vec![4, 9]);
        assert_eq!(t.samples.len(), 2);
        assert_eq!(t.samples[1].angles_deg, vec![12.5, -1.0]);
        std::fs::write(&p, "time_s,door_4\n0,0\n0.1,1,2\n").expect("write");
        let e = parse_doors(&p).expect_err("a row too long");
        assert!(e.to_string().contains("doors.csv:3"), "{e}");
        std::fs::write(&p, "time_s,leaf\n").expect("write");
        assert!(parse_doors(&p).is_err());
        std::fs::write(&p, "time_s\n0\n1\n").expect("write");
        assert_eq!(parse_doors(&p).expect("no doors").samples.len(), 2);
    }

    #[test]
    fn json_for_a_page_never_closes_its_script() {
        let mut e = Map::new();
        e.insert("kind".into(), Value::String("</script><b>".into()));
        let run = RecordedRun {
            title: "t".into(),
            verdict: "PASSED".into(),
            passed: true,
            rules: vec![],
            trajectory: vec![],
            doors: DoorTrack::default(),
            events: vec![e],
            scenario_toml: String::new(),
        };
        let json = run.to_json();
        assert!(!json.contains('<'));
        let back: Value = serde_json::from_str(&json).expect("json");
        assert_eq!(back["events"][0]["kind"], "</script><b>");
    }
}
