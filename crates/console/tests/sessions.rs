//! Sessions are runs: saved as `semsim simulate` writes a run plus the command log, when the
//! run ends, on `save`, on `reset` and when the console stops; a replay of the log gives the
//! same events bit for bit.

mod common;

use common::*;
use console::{replay, CommandLog, Session, RUN_FILES};
use serde_json::json;
use std::path::Path;

fn read(dir: &Path, name: &str) -> String {
    std::fs::read_to_string(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

#[test]
fn a_replayed_log_gives_the_same_run_bit_for_bit() {
    let out = tempfile::tempdir().expect("temp dir");
    let setup = setup(out.path().into(), 600.0);
    let mut session = Session::new(&setup, 7).expect("session");
    let drive = |v: f64, w: f64| console::protocol::ClientMessage::Drive {
        linear_m_s: v,
        angular_rad_s: w,
    };
    // Forward into the wall, pausing and turning on the way, at odd steps.
    for (steps, command) in [
        (13, drive(0.6, 0.0)),
        (90, console::protocol::ClientMessage::Pause {}),
        (1, drive(0.7, 0.3)),
        (150, drive(0.6, -0.3)),
        (200, console::protocol::ClientMessage::Stop {}),
        (37, drive(0.6, 0.0)),
    ] {
        for _ in 0..steps {
            session.step();
        }
        session.apply(&command);
    }
    for _ in 0..240 {
        session.step();
    }
    let (dir, outcome) = session.save(&setup).expect("saves");
    assert_eq!(dir, out.path().join("session-007"));
    for f in RUN_FILES {
        assert!(dir.join(f).is_file(), "{f}");
    }
    assert!(
        outcome
            .events
            .iter()
            .any(|e| e.kind == sim::EventKind::WallTouched),
        "the drive reaches the wall"
    );
    assert!(outcome.verdict.interrupted_at_s.is_some());
    let log = CommandLog::load(&dir.join("commands.jsonl")).expect("log");
    assert_eq!(log.commands.len(), 6);
    assert_eq!(log.commands[0].0, 13);
    let again = replay(&setup.world.spec, &setup.scenario, &setup.robot, &log).expect("replay");
    let replayed = tempfile::tempdir().expect("temp dir");
    sim::write_outputs(replayed.path(), &again, &sim::ReportConfig::default()).expect("writes");
    for f in ["events.jsonl", "trajectory.csv", "report.md"] {
        assert_eq!(read(&dir, f), read(replayed.path(), f), "{f} differs");
    }
    // Without the log's commands the run differs (the test could fail).
    let idle = CommandLog {
        commands: vec![],
        end: log.end,
    };
    let idle = replay(&setup.world.spec, &setup.scenario, &setup.robot, &idle).expect("replay");
    assert_ne!(
        sim::events_to_jsonl(&idle.events),
        read(&dir, "events.jsonl")
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn save_writes_a_run_folder_and_the_session_goes_on() {
    let out = tempfile::tempdir().expect("temp dir");
    let console = start(any_port(), setup(out.path().into(), 600.0)).await;
    let mut ws = connect(console.addr).await;
    next(&mut ws).await;
    send(
        &mut ws,
        json!({"type": "drive", "linear_m_s": 0.3, "angular_rad_s": 0.0}),
    )
    .await;
    wait_for(&mut ws, "the drive applied", |m| {
        m["type"] == "state" && m["operator"].is_object()
    })
    .await;
    send(&mut ws, json!({"type": "save"})).await;
    let verdict = wait_for(&mut ws, "a verdict", |m| m["type"] == "verdict").await;
    assert_eq!(verdict["saved_as"], "session-001");
    assert!(
        verdict["verdict"]["interrupted_at_s"].is_number(),
        "{verdict}"
    );
    let dir = out.path().join("session-001");
    for f in RUN_FILES {
        assert!(dir.join(f).is_file(), "{f}");
    }
    let log = read(&dir, "commands.jsonl");
    assert!(
        log.contains(r#""command":{"type":"drive","linear_m_s":0.3,"angular_rad_s":0.0}"#),
        "{log}"
    );
    assert!(log.contains(r#""command":{"type":"save"}"#), "{log}");
    assert!(log.trim_end().ends_with(r#""end":"interrupted"}"#), "{log}");
    assert_eq!(read(&dir, "scenario.toml"), scenario_toml(600.0));
    let s1 = wait_for(&mut ws, "a state", |m| m["type"] == "state").await;
    wait_for(&mut ws, "a later state", |m| {
        m["type"] == "state" && m["step"].as_u64() > s1["step"].as_u64()
    })
    .await;
    // Reset: the session is saved again and the next one starts.
    send(&mut ws, json!({"type": "reset"})).await;
    // (Once it has stepped: a session that took no step is not saved.)
    wait_for(&mut ws, "session 2 running", |m| {
        m["type"] == "state" && m["session"] == 2 && m["step"].as_u64() > Some(0)
    })
    .await;
    let saved = console.stop().await;
    assert_eq!(saved, vec![dir, out.path().join("session-002")]);
    assert!(out.path().join("session-002/commands.jsonl").is_file());
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_finished_run_is_judged_and_saved() {
    let out = tempfile::tempdir().expect("temp dir");
    // An earlier console's session is kept: this one is the next number.
    std::fs::create_dir_all(out.path().join("session-004")).expect("mkdir");
    let console = start(any_port(), setup(out.path().into(), 2.0)).await;
    let mut ws = connect(console.addr).await;
    let hello = next(&mut ws).await;
    assert_eq!(hello["session"], 5);
    fast(&mut ws).await;
    let verdict = wait_for(&mut ws, "the verdict", |m| m["type"] == "verdict").await;
    assert_eq!(verdict["saved_as"], "session-005");
    assert_eq!(verdict["verdict"]["passed"], true, "{verdict}");
    assert!(verdict["verdict"].get("interrupted_at_s").is_none());
    let dir = out.path().join("session-005");
    assert!(read(&dir, "commands.jsonl")
        .trim_end()
        .ends_with(r#""end":"finished"}"#));
    assert!(read(&dir, "report.md").contains("PASS"));
    // Driving a finished run is refused.
    send(
        &mut ws,
        json!({"type": "drive", "linear_m_s": 0.3, "angular_rad_s": 0.0}),
    )
    .await;
    let e = wait_for(&mut ws, "an error", |m| m["type"] == "error").await;
    assert!(
        e["message"].as_str().expect("message").contains("reset"),
        "{e}"
    );
    // Stopping saves nothing more: the run was saved when it ended.
    assert_eq!(console.stop().await, vec![dir]);
}
