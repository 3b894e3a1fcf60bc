//! The protocol against a real console on a loopback port, through a real WebSocket client:
//! hello and states, driving, a wall touched, bad messages refused while the session goes on,
//! the rate limit, drivers and watchers.

mod common;

use common::*;
use serde_json::{json, Value};

fn x_of(state: &Value) -> f64 {
    state["robot"]["pose"]["x_m"].as_f64().expect("x_m")
}

fn step_of(state: &Value) -> u64 {
    state["step"].as_u64().expect("step")
}

fn is(kind: &'static str) -> impl Fn(&Value) -> bool {
    move |m| m["type"] == kind
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn hello_then_states() {
    let out = tempfile::tempdir().expect("temp dir");
    let console = start(any_port(), setup(out.path().into(), 600.0)).await;
    let mut ws = connect(console.addr).await;
    let hello = next(&mut ws).await;
    assert_eq!(hello["type"], "hello");
    assert_eq!(hello["protocol"], 1);
    assert_eq!(hello["role"], "driver");
    assert_eq!(hello["session"], 1);
    assert_eq!(hello["world"]["robot"]["model"], "pioneer3at");
    assert!(
        hello["world"]["robot"]["max_speed_mps"]
            .as_f64()
            .expect("limit")
            > 0.0
    );
    assert_eq!(hello["limits"]["max_message_bytes"], 65536);
    let rules: Vec<&str> = hello["scenario"]["rules"]
        .as_array()
        .expect("rules")
        .iter()
        .map(|r| r["rule"].as_str().expect("rule"))
        .collect();
    assert_eq!(rules, ["max_wall_contact_s = 0.5", "no_tipping"]);
    assert_eq!(hello["scenario"]["rules"][0]["state"], "pending");
    let state = wait_for(&mut ws, "state", is("state")).await;
    assert!((x_of(&state) - 2.0).abs() < 0.1, "{state}");
    assert_eq!(state["doors"], json!([]));
    assert_eq!(
        state["robot"]["wheel_angles_rad"].as_array().map(Vec::len),
        Some(4)
    );
    let later = wait_for(&mut ws, "a later state", |m| {
        m["type"] == "state" && step_of(m) > step_of(&state)
    })
    .await;
    assert_eq!(later["paused"], false);
    console.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn driving_moves_the_robot_into_the_wall() {
    let out = tempfile::tempdir().expect("temp dir");
    let console = start(any_port(), setup(out.path().into(), 600.0)).await;
    let mut ws = connect(console.addr).await;
    next(&mut ws).await;
    fast(&mut ws).await;
    send(
        &mut ws,
        json!({"type": "drive", "linear_m_s": 0.6, "angular_rad_s": 0.0}),
    )
    .await;
    let moved = wait_for(&mut ws, "the robot 0.5 m further", |m| {
        m["type"] == "state" && x_of(m) > 2.5
    })
    .await;
    assert_eq!(moved["operator"]["linear_m_s"], 0.6);
    assert_eq!(moved["speed"], 10.0);
    let touched = wait_for(&mut ws, "wall_touched", |m| {
        m["type"] == "event" && m["event"]["kind"] == "wall_touched"
    })
    .await;
    let entities = touched["event"]["entities"].as_array().expect("entities");
    assert_eq!(entities[1]["class"], "wall", "{touched}");
    // Pushing on: the wall-contact rule fails, and the rules say so.
    let failed = wait_for(&mut ws, "the wall rule failed", |m| {
        m["type"] == "rules" && m["rules"][0]["state"] == "failed"
    })
    .await;
    assert!(failed["rules"][0]["reason"]
        .as_str()
        .expect("reason")
        .contains("walls"));
    send(&mut ws, json!({"type": "stop"})).await;
    wait_for(&mut ws, "the stop applied", |m| {
        m["type"] == "state" && m["operator"]["linear_m_s"] == 0.0
    })
    .await;
    console.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn bad_messages_get_errors_and_the_session_goes_on() {
    let out = tempfile::tempdir().expect("temp dir");
    let console = start(any_port(), setup(out.path().into(), 600.0)).await;
    let mut ws = connect(console.addr).await;
    next(&mut ws).await;
    let bad: Vec<(String, &str)> = vec![
        ("{not json".into(), "malformed"),
        (r#"{"type":"fly"}"#.into(), "unknown variant"),
        (r#"{"type":"stop","now":true}"#.into(), "unknown field"),
        (
            r#"{"type":"drive","linear_m_s":0.5}"#.into(),
            "missing field",
        ),
        (
            r#"{"type":"drive","linear_m_s":50,"angular_rad_s":0}"#.into(),
            "out of range",
        ),
        (r#"{"type":"speed","factor":0}"#.into(), "out of range"),
        (
            format!(r#"{{"type":"stop","pad":"{}"}}"#, "x".repeat(70 * 1024)),
            "limit is 65536 bytes",
        ),
    ];
    for (text, expected) in bad {
        send_text(&mut ws, text.clone()).await;
        let e = wait_for(&mut ws, "an error", is("error")).await;
        let message = e["message"].as_str().expect("message");
        assert!(message.contains(expected), "{:.80} gave {message}", text);
    }
    // The session went on: states keep coming, and a good command still works.
    let s1 = wait_for(&mut ws, "a state", is("state")).await;
    wait_for(&mut ws, "a later state", |m| {
        m["type"] == "state" && step_of(m) > step_of(&s1)
    })
    .await;
    send(&mut ws, json!({"type": "pause"})).await;
    wait_for(&mut ws, "paused", |m| {
        m["type"] == "state" && m["paused"] == true
    })
    .await;
    console.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_rate_limit_answers_the_excess_and_keeps_the_connection() {
    let out = tempfile::tempdir().expect("temp dir");
    let config = console::ConsoleConfig {
        max_messages_per_s: 5,
        ..any_port()
    };
    let console = start(config, setup(out.path().into(), 600.0)).await;
    let mut ws = connect(console.addr).await;
    next(&mut ws).await;
    for _ in 0..60 {
        send(&mut ws, json!({"type": "resume"})).await;
    }
    let e = wait_for(&mut ws, "a rate-limit error", is("error")).await;
    assert!(
        e["message"]
            .as_str()
            .expect("message")
            .contains("rate limit"),
        "{e}"
    );
    let s1 = wait_for(&mut ws, "a state", is("state")).await;
    wait_for(&mut ws, "a later state", |m| {
        m["type"] == "state" && step_of(m) > step_of(&s1)
    })
    .await;
    console.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_first_tab_drives_the_others_watch() {
    let out = tempfile::tempdir().expect("temp dir");
    let console = start(any_port(), setup(out.path().into(), 600.0)).await;
    let mut first = connect(console.addr).await;
    assert_eq!(next(&mut first).await["role"], "driver");
    let mut second = connect(console.addr).await;
    let hello = next(&mut second).await;
    assert_eq!(hello["role"], "watcher");
    assert_ne!(hello["connection"], 0);
    send(
        &mut second,
        json!({"type": "drive", "linear_m_s": 0.5, "angular_rad_s": 0.0}),
    )
    .await;
    let e = wait_for(&mut second, "an error", is("error")).await;
    assert!(
        e["message"].as_str().expect("message").contains("watches"),
        "{e}"
    );
    // The driver leaves: the watcher drives.
    first.close(None).await.expect("closes");
    drop(first);
    let role = wait_for(&mut second, "a role message", is("role")).await;
    assert_eq!(role["role"], "driver");
    send(
        &mut second,
        json!({"type": "drive", "linear_m_s": 0.5, "angular_rad_s": 0.0}),
    )
    .await;
    wait_for(&mut second, "the new driver's command applied", |m| {
        m["type"] == "state" && m["operator"]["linear_m_s"] == 0.5
    })
    .await;
    console.stop().await;
}
