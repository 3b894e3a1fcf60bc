//! The console replaying a recorded run (`semsim console --run RUN_DIR`, issue 14 item 5):
//! the run is served at `/api/run.json` with the world and the page (which has the replay
//! controls), every WebSocket message is refused (nothing can be driven), cross-origin
//! upgrades are refused as in a live console, and a live console answers `null` there.

mod common;

use common::*;
use console::{RecordedRun, RunConsole, RunSetup, REPLAY_REFUSAL, TRAJECTORY_HEADER};
use serde_json::{json, Value};
use std::path::Path;
use tokio_tungstenite::tungstenite::client::IntoClientRequest;
use tokio_tungstenite::tungstenite::http::HeaderValue;

const EVENTS: &str = r#"{"time_s":0.1000,"kind":"movement","entities":[{"id":31,"class":"robot","name":"robot"}],"detail":"","values":{}}
{"time_s":0.2000,"kind":"wall_touched","entities":[{"id":31,"class":"robot","name":"robot"},{"id":3,"class":"wall","name":"walls[0]"}],"detail":"</script>","values":{}}
"#;

const REPORT: &str = "# Simulation report: replay test\n\n## Verdict: FAILED\n\n| rule | result | decided at (s) | reason |\n|---|---|---|---|\n| `max_wall_contact_s = 0.5` | FAILED | 0.2 | touched a wall |\n\n## Timeline\n";

/// A small run folder written by hand: three trajectory rows, two events, a failed verdict.
fn write_run(dir: &Path) {
    let rows = "0.0,10.0,0.0,0.2,0,0,0,0\n0.1,10.1,0.0,0.2,0,0,0,1\n0.2,10.2,0.1,0.2,0,0,10,1\n";
    std::fs::write(
        dir.join("trajectory.csv"),
        format!("{TRAJECTORY_HEADER}\n{rows}"),
    )
    .expect("csv");
    std::fs::write(dir.join("events.jsonl"), EVENTS).expect("events");
    std::fs::write(dir.join("report.md"), REPORT).expect("report");
    std::fs::write(dir.join("scenario.toml"), scenario_toml(600.0)).expect("scenario");
}

/// Two wall points, 4 m apart (more than any voxel edge: both are kept).
fn two_point_cloud() -> console::CloudLayer {
    let mut c = cloud::PointCloud::from_points(vec![
        glam::Vec3::new(0.0, 0.0, 1.0),
        glam::Vec3::new(4.0, 0.0, 1.0),
    ]);
    let wall = cloud::Label {
        entity: 1,
        class: cloud::EntityClass::Wall,
    };
    c.labels = Some(vec![wall; 2]);
    console::CloudLayer::from_cloud(&c, "two.pcd", 100).expect("a layer")
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_recorded_run_is_served_and_driving_is_refused() {
    let tmp = tempfile::tempdir().expect("temp dir");
    write_run(tmp.path());
    let run = RecordedRun::load(tmp.path()).expect("a run folder");
    let live = setup(tmp.path().join("unused"), 600.0);
    let setup = RunSetup {
        world: live.world,
        robot_name: live.scenario.robot_name.clone(),
        start: live.scenario.start,
        robot: live.robot,
        run,
        cloud: Some(two_point_cloud()),
    };
    let console = RunConsole::bind(any_port(), setup).await.expect("binds");
    let addr = console.local_addr();
    assert!(addr.ip().is_loopback());
    let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
    let task = tokio::spawn(console.serve(async move {
        let _ = stopped.await;
    }));

    // The run: every event, the trajectory, the verdict and rules.
    let (status, body) = get(addr, "/api/run.json").await;
    assert_eq!(status, 200);
    let data: Value = serde_json::from_slice(&body).expect("JSON");
    let events: Vec<Value> = EVENTS
        .lines()
        .map(|l| serde_json::from_str(l).expect("event"))
        .collect();
    assert_eq!(data["events"].as_array().expect("events"), &events);
    assert_eq!(data["trajectory"].as_array().expect("trajectory").len(), 3);
    assert_eq!(data["trajectory"][2]["yaw_deg"], 10.0);
    assert_eq!(data["verdict"], "FAILED");
    assert_eq!(data["passed"], false);
    assert_eq!(data["rules"][0]["rule"], "max_wall_contact_s = 0.5");
    assert_eq!(data["title"], "replay test");

    // The page with its replay controls, its script, and the world.
    let (status, page) = get(addr, "/").await;
    assert_eq!(status, 200);
    let page = String::from_utf8(page).expect("utf-8");
    for id in ["id=\"replay-slider\"", "id=\"play\"", "id=\"replay-speed\""] {
        assert!(page.contains(id), "the page lacks {id}");
    }
    // The cloud layer: what it is, then the points (3 x f32 each, then the class codes).
    let (status, body) = get(addr, "/api/cloud.json").await;
    assert_eq!(status, 200);
    let meta: Value = serde_json::from_slice(&body).expect("JSON");
    assert_eq!(meta["info"]["points"], 2);
    assert_eq!(meta["info"]["classes"], true);
    assert!(meta["class_codes"]
        .as_array()
        .expect("codes")
        .contains(&serde_json::json!([3, "wall"])));
    let (status, bin) = get(addr, "/api/cloud.bin").await;
    assert_eq!(status, 200);
    assert_eq!(bin.len(), 2 * 13);
    assert_eq!(f32::from_le_bytes(bin[12..16].try_into().expect("4")), 4.0);
    assert_eq!(&bin[24..], &[3, 3]);

    let (status, js) = get(addr, "/replay.js").await;
    assert_eq!(status, 200);
    assert!(String::from_utf8_lossy(&js).contains("export function startReplay"));
    let (status, glb) = get(addr, "/world.glb").await;
    assert_eq!(status, 200);
    assert_eq!(&glb[..4], b"glTF");
    assert_eq!(get(addr, "/nope").await.0, 404);

    // Nothing can be driven or controlled: each message gets an error, the socket stays open.
    let mut ws = connect(addr).await;
    for message in [
        json!({"type": "drive", "linear_m_s": 0.4, "angular_rad_s": 0.0}),
        json!({"type": "stop"}),
        json!({"type": "reset"}),
    ] {
        send(&mut ws, message).await;
        let reply = next(&mut ws).await;
        assert_eq!(reply["type"], "error", "{reply}");
        assert_eq!(reply["message"], REPLAY_REFUSAL);
    }

    // A cross-origin upgrade is refused.
    let mut request = format!("ws://{addr}/ws")
        .into_client_request()
        .expect("request");
    request
        .headers_mut()
        .insert("Origin", HeaderValue::from_static("http://evil.example"));
    match tokio_tungstenite::connect_async(request).await {
        Err(tokio_tungstenite::tungstenite::Error::Http(r)) => {
            assert_eq!(r.status().as_u16(), 403)
        }
        other => panic!("a cross-origin upgrade: {other:?}"),
    }

    drop(ws);
    let _ = stop.send(());
    tokio::time::timeout(std::time::Duration::from_secs(30), task)
        .await
        .expect("stops in time")
        .expect("no panic")
        .expect("stops cleanly");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_live_console_has_no_recorded_run() {
    let out = tempfile::tempdir().expect("temp dir");
    let console = start(any_port(), setup(out.path().into(), 600.0)).await;
    let (status, body) = get(console.addr, "/api/run.json").await;
    assert_eq!(status, 200);
    assert_eq!(body, b"null");
    console.stop().await;
}

#[test]
fn a_bad_run_folder_names_its_file() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let e = RecordedRun::load(&tmp.path().join("none")).expect_err("no folder");
    assert!(e.to_string().contains("none"), "{e}");
    write_run(tmp.path());
    std::fs::write(tmp.path().join("events.jsonl"), "{\"time_s\":1}\n").expect("w");
    let e = RecordedRun::load(tmp.path()).expect_err("an event without a kind");
    assert!(e.to_string().contains("events.jsonl:1"), "{e}");
    std::fs::remove_file(tmp.path().join("trajectory.csv")).expect("rm");
    let e = RecordedRun::load(tmp.path()).expect_err("no trajectory");
    assert!(e.to_string().contains("trajectory.csv"), "{e}");
}
