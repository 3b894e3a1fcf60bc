//! Issue 14: a session driven through the protocol, through the stair room's door and up the
//! stairs, gives the same run as the scripted scenario.
//!
//! The default scenario (what `semsim simulate` runs with no arguments: the built-in
//! scenario in the built-in building) is not a list of timed velocity segments but four
//! waypoints followed by a closed-loop controller, whose command changes almost every step.
//! So the operator here does what the controller does: before each step it computes the
//! controller's command from the robot's pose (with `sim::Controller`, the scenario's own
//! controller, outside the simulation), sends it as `drive` (or `stop` for a standstill) whenever it
//! changes, and advances with `step`, so that every command lands before exactly the step the
//! controller would have given it to. A command set through the protocol reaches the motors
//! exactly as the controller's does (the console clamps it to the robot's limits, and the
//! motors clamp the controller's command to the same limits), and JSON numbers round-trip
//! (`serde_json`'s `float_roundtrip`), so the run is the same bit for bit: the same events
//! (kinds, entities, times, values), trajectory, report and verdict as `sim::run_scenario`.

mod common;

use common::*;
use console::{CommandLog, ConsoleConfig, ConsoleWorld, SessionSetup};
use serde_json::{json, Value};
use sim::{RobotPose, Scenario};
use std::path::Path;

/// The scripted run, step by step as `Simulation::run` takes it: the controller's command
/// before each step (as `sim::Controller` computes it), the robot's pose before each step and at the
/// end, and the outcome.
struct Scripted {
    commands: Vec<(f64, f64)>,
    poses: Vec<RobotPose>,
    outcome: sim::Outcome,
}

fn scripted(setup: &SessionSetup) -> Scripted {
    let sc = &setup.scenario;
    let mut s = sim::Simulation::new(&setup.world.spec, sc, &setup.robot).expect("simulation");
    let mut follower = sim::Controller::default();
    let (mut commands, mut poses) = (vec![], vec![]);
    while !s.is_finished() {
        let pose = s.robot_pose();
        commands.push(follower.command(
            s.time_s(),
            &pose,
            &sc.velocity,
            &sc.waypoints,
            &sc.controller,
        ));
        poses.push(pose);
        s.step();
    }
    poses.push(s.robot_pose());
    Scripted {
        commands,
        poses,
        outcome: s.outcome(),
    }
}

/// The world and scenario `semsim simulate` runs by default, saving into `out`.
fn default_setup(out: &Path) -> SessionSetup {
    let scenario = Scenario::default_scenario().expect("the default scenario");
    assert_eq!(scenario.building, "default");
    let building = scanner::Building::default_building().expect("the default building");
    SessionSetup {
        world: ConsoleWorld::from_building(&building).expect("world"),
        robot: sim::RobotModel::builtin(&scenario.robot).expect("robot"),
        scenario_toml: Scenario::default_scenario_toml().to_string(),
        scenario,
        out_dir: out.to_path_buf(),
        cloud: None,
    }
}

fn read(dir: &Path, name: &str) -> String {
    std::fs::read_to_string(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Reads messages until a state satisfying `wanted`, keeping the events on the way; any
/// error reply fails the test.
async fn state_where(
    ws: &mut Ws,
    events: &mut Vec<Value>,
    what: &str,
    wanted: impl Fn(&Value) -> bool,
) -> Value {
    loop {
        let m = next(ws).await;
        match m["type"].as_str() {
            Some("event") => events.push(m["event"].clone()),
            Some("error") => panic!("{what}: the console refused a message: {m}"),
            Some("verdict") => panic!("{what}: a verdict before it: {m}"),
            Some("state") if wanted(&m) => return m,
            _ => {}
        }
    }
}

/// Opens the WebSocket with Nagle's algorithm off: the operator sends a `drive` and a `step`
/// back to back and waits for the step's state, thousands of times.
async fn connect_nodelay(addr: std::net::SocketAddr) -> Ws {
    let (ws, _) = tokio::time::timeout(
        TIMEOUT,
        tokio_tungstenite::connect_async_with_config(format!("ws://{addr}/ws"), None, true),
    )
    .await
    .expect("connects in time")
    .expect("connects");
    ws
}

fn step_of(state: &Value) -> u64 {
    state["step"].as_u64().expect("step")
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_operator_driven_session_gives_the_scripted_run() {
    let out = tempfile::tempdir().expect("temp dir");
    let setup = default_setup(out.path());

    // The scripted run, as `sim::run_scenario` gives it.
    let script = scripted(&setup);
    let reference = sim::run_scenario(&setup.world.spec, &setup.scenario, &setup.robot)
        .expect("the scripted run");
    assert_eq!(
        script.outcome, reference,
        "stepping by hand is run_scenario"
    );
    assert!(
        reference.verdict.passed,
        "the scripted run passes: {:#?}",
        reference.verdict
    );
    let last_step = script.commands.len() as u64;
    let door_events = reference
        .events
        .iter()
        .filter(|e| serde_json::to_string(e).is_ok_and(|t| t.contains("walls[4].doors[2]")))
        .count();
    let stair_steps = reference
        .events
        .iter()
        .filter(|e| e.kind == sim::EventKind::StairsStepReached)
        .count();
    assert!(
        door_events > 0 && stair_steps == 7,
        "through the door and up the stairs"
    );

    // The console, with room for one message per step and one per change of command.
    let config = ConsoleConfig {
        max_messages_per_s: 10_000,
        ..any_port()
    };
    let console = start(config, setup.clone()).await;
    let mut ws = connect_nodelay(console.addr).await;
    let hello = next(&mut ws).await;
    assert_eq!(hello["type"], "hello");
    assert_eq!(hello["role"], "driver");
    assert_eq!(hello["scenario"]["name"], setup.scenario.name);
    // Pause at once: the steps taken before the pause lands are the scenario's own.
    send(&mut ws, json!({"type": "pause"})).await;
    let mut events = vec![];
    let paused = state_where(&mut ws, &mut events, "the pause", |m| m["paused"] == true).await;
    let first = step_of(&paused);
    assert!(first < last_step, "paused at step {first}");
    assert_eq!(
        paused["robot"]["pose"],
        serde_json::to_value(script.poses[first as usize]).expect("json"),
        "the pose at step {first}"
    );
    assert_eq!(paused["operator"], Value::Null, "the scenario drove so far");

    // The operator drives: the controller's command before each step, then `step`.
    let mut sent: Option<(f64, f64)> = None;
    let mut drives = vec![];
    for k in first..last_step {
        let (v, w) = script.commands[k as usize];
        if sent.is_none_or(|s| s.0.to_bits() != v.to_bits() || s.1.to_bits() != w.to_bits()) {
            let command = if v.to_bits() == 0 && w.to_bits() == 0 {
                json!({"type": "stop"})
            } else {
                json!({"type": "drive", "linear_m_s": v, "angular_rad_s": w})
            };
            send(&mut ws, command.clone()).await;
            drives.push((k, command));
            sent = Some((v, w));
        }
        send(&mut ws, json!({"type": "step"})).await;
        let state = state_where(&mut ws, &mut events, "a step", |m| {
            m["type"] == "state" && step_of(m) > k
        })
        .await;
        assert_eq!(step_of(&state), k + 1, "one step a `step`");
        assert_eq!(state["paused"], true);
        // The operator's command as the console applied it is the one sent, unclamped.
        assert_eq!(
            state["operator"]["linear_m_s"].as_f64(),
            Some(v),
            "step {k}"
        );
        assert_eq!(
            state["operator"]["angular_rad_s"].as_f64(),
            Some(w),
            "step {k}"
        );
        // The robot is where the scripted run had it, bit for bit.
        assert_eq!(
            state["robot"]["pose"],
            serde_json::to_value(script.poses[k as usize + 1]).expect("json"),
            "the driven robot left the scripted path at step {}",
            k + 1
        );
    }
    // The run ends at its time limit: judged, saved, and its verdict sent.
    let verdict = loop {
        let m = next(&mut ws).await;
        match m["type"].as_str() {
            Some("event") => events.push(m["event"].clone()),
            Some("error") => panic!("the console refused a message: {m}"),
            Some("verdict") => break m,
            _ => {}
        }
    };
    assert_eq!(verdict["saved_as"], "session-001");
    assert_eq!(verdict["verdict"]["passed"], true, "{verdict}");
    assert_eq!(
        verdict["verdict"],
        serde_json::to_value(&reference.verdict).expect("json"),
        "the verdict is the scripted run's"
    );

    // The same events, in the same order, with the same entities, times and values: as they
    // were sent, and as the run folder has them.
    let expected: Vec<Value> = reference
        .events
        .iter()
        .map(|e| serde_json::to_value(e).expect("json"))
        .collect();
    assert_eq!(events.len(), expected.len(), "as many events");
    for (i, (got, want)) in events.iter().zip(&expected).enumerate() {
        assert_eq!(got, want, "event {i}");
    }
    let dir = out.path().join("session-001");
    assert_eq!(
        read(&dir, "events.jsonl"),
        sim::events_to_jsonl(&reference.events)
    );
    let scripted_dir = tempfile::tempdir().expect("temp dir");
    sim::write_outputs(
        scripted_dir.path(),
        &reference,
        &sim::ReportConfig::default(),
    )
    .expect("writes");
    for f in ["events.jsonl", "trajectory.csv", "report.md"] {
        assert_eq!(read(&dir, f), read(scripted_dir.path(), f), "{f} differs");
    }
    assert!(read(&dir, "report.md").contains("## Verdict: PASSED"));
    assert_eq!(
        read(&dir, "scenario.toml"),
        Scenario::default_scenario_toml()
    );

    // The command log has the operator's commands at the steps they were sent before.
    let log = CommandLog::load(&dir.join("commands.jsonl")).expect("the command log");
    let logged: Vec<(u64, Value)> = log
        .commands
        .iter()
        .filter(|(_, c)| c.drives())
        .map(|(k, c)| (*k, serde_json::to_value(c).expect("json")))
        .collect();
    assert_eq!(logged, drives);
    assert_eq!(log.end, Some((last_step, console::RunEnd::Finished)));
    assert_eq!(console.stop().await, vec![dir]);
}
