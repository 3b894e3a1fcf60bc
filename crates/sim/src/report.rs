//! Outputs of a run: `events.jsonl`, `trajectory.csv`, `doors.csv` (the doors' angles over
//! time, so that a replay swings them as they moved) and a Markdown `report.md` (the timeline
//! of significant events and the verdict), each written atomically.

use crate::error::Result;
use crate::events::{events_to_jsonl, fmt_f, EventKind};
use crate::simulation::{DoorTrack, Outcome, TrajectoryPoint};
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// What the Markdown report shows.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ReportConfig {
    /// At most this many timeline rows (the rest are counted).
    pub max_timeline_rows: usize,
}

impl Default for ReportConfig {
    fn default() -> Self {
        ReportConfig {
            max_timeline_rows: 200,
        }
    }
}

/// The trajectory as CSV: `time_s,x_m,y_m,z_m,roll_deg,pitch_deg,yaw_deg,speed_mps`, 4 decimals.
pub fn trajectory_to_csv(trajectory: &[TrajectoryPoint]) -> String {
    let mut s = String::from("time_s,x_m,y_m,z_m,roll_deg,pitch_deg,yaw_deg,speed_mps\n");
    for p in trajectory {
        let q = &p.pose;
        let row = [
            p.time_s,
            q.x_m,
            q.y_m,
            q.z_m,
            q.roll_deg,
            q.pitch_deg,
            q.yaw_deg,
            q.speed_mps,
        ];
        let cells: Vec<String> = row.iter().map(|v| fmt_f(*v)).collect();
        s.push_str(&cells.join(","));
        s.push('\n');
    }
    s
}

/// The name of a run's door-angle file.
pub const DOORS_CSV: &str = "doors.csv";

/// The doors' angles as CSV: `time_s` and one column `door_ID` (degrees, 0 = closed) per door,
/// in the world's order, one row per trajectory sample, 4 decimals. A world without doors gives
/// the `time_s` column alone.
pub fn doors_to_csv(track: &DoorTrack) -> String {
    let mut s = String::from("time_s");
    for id in &track.doors {
        let _ = write!(s, ",door_{id}");
    }
    s.push('\n');
    for sample in &track.samples {
        s.push_str(&fmt_f(sample.time_s));
        for a in &sample.angles_deg {
            s.push(',');
            s.push_str(&fmt_f(*a));
        }
        s.push('\n');
    }
    s
}

/// The Markdown report: summary, verdict table and the timeline of significant events
/// (movement and collision-continued events are left out).
pub fn report_markdown(outcome: &Outcome, cfg: &ReportConfig) -> String {
    let v = &outcome.verdict;
    let mut s = String::new();
    let title = if outcome.scenario_name.is_empty() {
        "Simulation report".to_string()
    } else {
        format!("Simulation report: {}", outcome.scenario_name)
    };
    let _ = writeln!(s, "# {title}\n");
    let _ = writeln!(
        s,
        "Robot model `{}`, simulated {} s, {} events ({} significant).\n",
        outcome.robot_model,
        fmt_secs(v.end_time_s),
        outcome.events.len(),
        outcome
            .events
            .iter()
            .filter(|e| e.kind.is_significant())
            .count()
    );
    match v.interrupted_at_s {
        Some(t) => {
            let _ = writeln!(
                s,
                "## Verdict: FAILED (interrupted at {} s)\n\nThe run was interrupted at {} s, before its end; the rules not decided by then say so.\n",
                fmt_secs(t),
                fmt_secs(t)
            );
        }
        None => {
            let _ = writeln!(
                s,
                "## Verdict: {}\n",
                if v.passed { "PASSED" } else { "FAILED" }
            );
        }
    }
    if v.rules.is_empty() {
        let _ = writeln!(s, "No rules.\n");
    } else {
        let _ = writeln!(
            s,
            "| rule | result | decided at (s) | reason |\n|---|---|---|---|"
        );
        for r in &v.rules {
            let _ = writeln!(
                s,
                "| `{}` | {} | {} | {} |",
                r.rule,
                match (r.passed, r.undecided) {
                    (_, true) => "not decided",
                    (true, false) => "passed",
                    (false, false) => "FAILED",
                },
                fmt_secs(r.decided_s),
                r.reason.replace('|', "\\|")
            );
        }
        s.push('\n');
    }
    let _ = writeln!(
        s,
        "## Timeline\n\n| time (s) | event | entities | values |\n|---|---|---|---|"
    );
    let significant: Vec<_> = outcome
        .events
        .iter()
        .filter(|e| e.kind.is_significant())
        .collect();
    for e in significant.iter().take(cfg.max_timeline_rows) {
        let ents: Vec<String> = e
            .entities
            .iter()
            .map(|x| format!("{} ({})", x.name, x.class.name()))
            .collect();
        let mut vals: Vec<String> = e
            .values
            .iter()
            .map(|(k, x)| format!("{k} = {x:.2}"))
            .collect();
        if !e.detail.is_empty() {
            vals.insert(0, e.detail.clone());
        }
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} |",
            fmt_secs(e.time_s),
            e.kind.name(),
            ents.join(", "),
            vals.join(", ")
        );
    }
    if significant.len() > cfg.max_timeline_rows {
        let _ = writeln!(
            s,
            "\n{} more significant events are in events.jsonl.",
            significant.len() - cfg.max_timeline_rows
        );
    }
    let moves = outcome
        .events
        .iter()
        .filter(|e| e.kind == EventKind::Movement)
        .count();
    let _ = writeln!(
        s,
        "\n{moves} movement events are in events.jsonl; the trajectory is in trajectory.csv."
    );
    s
}

fn fmt_secs(t: f64) -> String {
    format!("{t:.2}")
}

/// Writes `events.jsonl` atomically.
pub fn write_events_jsonl(path: &Path, outcome: &Outcome) -> Result<()> {
    cloud::write_bytes_atomically(path, events_to_jsonl(&outcome.events).as_bytes())?;
    Ok(())
}

/// Writes `trajectory.csv` atomically.
pub fn write_trajectory_csv(path: &Path, outcome: &Outcome) -> Result<()> {
    cloud::write_bytes_atomically(path, trajectory_to_csv(&outcome.trajectory).as_bytes())?;
    Ok(())
}

/// Writes `doors.csv` atomically.
pub fn write_doors_csv(path: &Path, outcome: &Outcome) -> Result<()> {
    cloud::write_bytes_atomically(path, doors_to_csv(&outcome.doors).as_bytes())?;
    Ok(())
}

/// Writes `report.md` atomically.
pub fn write_report_md(path: &Path, outcome: &Outcome, cfg: &ReportConfig) -> Result<()> {
    cloud::write_bytes_atomically(path, report_markdown(outcome, cfg).as_bytes())?;
    Ok(())
}

/// Writes `events.jsonl`, `trajectory.csv`, `report.md` and `doors.csv` into `dir` (which must
/// exist); returns the first three's paths in that order (`doors.csv` is [`DOORS_CSV`] beside
/// them).
pub fn write_outputs(dir: &Path, outcome: &Outcome, cfg: &ReportConfig) -> Result<[PathBuf; 3]> {
    let paths = [
        dir.join("events.jsonl"),
        dir.join("trajectory.csv"),
        dir.join("report.md"),
    ];
    write_events_jsonl(&paths[0], outcome)?;
    write_trajectory_csv(&paths[1], outcome)?;
    write_doors_csv(&dir.join(DOORS_CSV), outcome)?;
    write_report_md(&paths[2], outcome, cfg)?;
    Ok(paths)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulation::DoorSample;

    #[test]
    fn doors_csv_has_one_column_per_door_and_a_row_per_sample() {
        let track = DoorTrack {
            doors: vec![12, 15],
            samples: vec![
                DoorSample {
                    time_s: 0.0,
                    angles_deg: vec![0.0, 0.0],
                },
                DoorSample {
                    time_s: 0.1,
                    angles_deg: vec![12.5, -0.25],
                },
            ],
        };
        let csv = doors_to_csv(&track);
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines[0], "time_s,door_12,door_15");
        assert_eq!(lines.len(), 3);
        let last: Vec<f64> = lines[2].split(',').map(|c| c.parse().unwrap()).collect();
        assert_eq!(last, vec![0.1, 12.5, -0.25]);
        assert_eq!(doors_to_csv(&DoorTrack::default()), "time_s\n");
    }
}
