//! `semsim console` end to end: the real binary on a free port prints its URL, serves the page
//! and the world, and Ctrl-C saves the session as a run folder and exits 0; the session's
//! command log replays (`semsim simulate --replay`) to the same events, bit for bit.

mod util;

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};
use util::Dir;

const TIMEOUT: Duration = Duration::from_secs(90);

const BUILDING: &str = r#"
name = "test room"
[floor]
min_m = [0.0, -2.0]
max_m = [8.0, 2.0]
[ceiling]
height_m = 2.5
[[walls]]
start_m = [5.0, -2.0]
end_m = [5.0, 2.0]
thickness_m = 0.2
"#;

const SCENARIO: &str = r#"
name = "towards the wall"
robot = "pioneer3at"
time_limit_s = 3600.0
start = { x_m = 2.0, y_m = 0.0, yaw_deg = 0.0 }
[[velocity]]
from_s = 0.2
to_s = 3600.0
linear_mps = 0.3
angular_radps = 0.05
[rules]
max_wall_contact_s = 0.5
"#;

/// `GET path`: (status line, body).
fn get(host_port: &str, path: &str) -> (String, Vec<u8>) {
    let mut s = TcpStream::connect(host_port).expect("connects");
    s.set_read_timeout(Some(TIMEOUT)).expect("timeout");
    write!(
        s,
        "GET {path} HTTP/1.1\r\nHost: {host_port}\r\nConnection: close\r\n\r\n"
    )
    .expect("writes");
    let mut raw = vec![];
    s.read_to_end(&mut raw).expect("reads");
    let end = raw
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .expect("a header");
    let head = String::from_utf8_lossy(&raw[..end]).to_string();
    let status = head.lines().next().unwrap_or_default().to_string();
    (status, raw[end + 4..].to_vec())
}

/// Waits for the child to end (killing it and failing after [`TIMEOUT`]).
fn wait(mut child: Child) -> (i32, String, String) {
    let t0 = Instant::now();
    loop {
        if let Some(status) = child.try_wait().expect("waits") {
            let mut out = String::new();
            let mut err = String::new();
            if let Some(mut s) = child.stdout.take() {
                s.read_to_string(&mut out).expect("stdout");
            }
            if let Some(mut s) = child.stderr.take() {
                s.read_to_string(&mut err).expect("stderr");
            }
            return (status.code().unwrap_or(-1), out, err);
        }
        if t0.elapsed() > TIMEOUT {
            let _ = child.kill();
            panic!("semsim console did not stop");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

#[test]
fn console_serves_the_page_and_ctrl_c_saves_a_replayable_run() {
    let d = Dir::new();
    d.write("building.toml", BUILDING);
    d.write("scenario.toml", SCENARIO);
    let mut child = Command::new(env!("CARGO_BIN_EXE_semsim"))
        .args([
            "console",
            "--building",
            "building.toml",
            "--scenario",
            "scenario.toml",
        ])
        .args(["--port", "0", "--out", "runs"])
        .current_dir(d.path())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("semsim starts");
    // The URL line, read on a thread so that a silent console fails after the timeout.
    let stdout = child.stdout.take().expect("stdout");
    let (tx, rx) = mpsc::channel();
    let reader = std::thread::spawn(move || {
        let mut lines = BufReader::new(stdout).lines();
        for line in lines.by_ref() {
            let line = line.expect("a line");
            if line.starts_with("console: ") {
                let _ = tx.send(line);
                break;
            }
        }
        lines.map_while(Result::ok).collect::<Vec<String>>()
    });
    let line = match rx.recv_timeout(TIMEOUT) {
        Ok(line) => line,
        Err(_) => {
            let _ = child.kill();
            panic!("no URL printed: {:?}", wait(child));
        }
    };
    let url = line.trim_start_matches("console: ");
    let host_port = url
        .strip_prefix("http://127.0.0.1:")
        .map(|rest| format!("127.0.0.1:{}", rest.trim_end_matches('/')))
        .unwrap_or_else(|| panic!("a loopback URL: {line}"));
    let (status, page) = get(&host_port, "/");
    assert!(status.contains(" 200 "), "{status}");
    assert!(String::from_utf8_lossy(&page).contains("<title>semsim console</title>"));
    let (status, glb) = get(&host_port, "/world.glb");
    assert!(status.contains(" 200 "), "{status}");
    assert_eq!(&glb[..4], b"glTF");
    // Let the simulation take some steps, then Ctrl-C.
    std::thread::sleep(Duration::from_secs(1));
    let sent = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(sent.success());
    let (code, _, err) = wait(child);
    let rest = reader.join().expect("the reader");
    assert_eq!(code, 0, "{err}");
    assert!(
        rest.iter().any(|l| l.contains("saved runs/session-001")),
        "{rest:?}"
    );
    let run = d.join("runs/session-001");
    for f in console::RUN_FILES {
        assert!(run.join(f).is_file(), "{f} was not written");
    }
    let report = std::fs::read_to_string(run.join("report.md")).expect("report");
    assert!(report.contains("interrupted"), "{report}");
    // The session replays to the same events.
    let replay = d.run(&[
        "simulate",
        "--building",
        "building.toml",
        "--scenario",
        "runs/session-001/scenario.toml",
        "--replay",
        "runs/session-001/commands.jsonl",
        "--out",
        "replay",
    ]);
    assert_eq!(
        replay.code(),
        1,
        "an interrupted run fails: {}",
        replay.stderr()
    );
    let events =
        |dir: &str| std::fs::read_to_string(d.join(dir).join("events.jsonl")).expect("events");
    assert!(events("runs/session-001").lines().count() > 1);
    assert_eq!(events("runs/session-001"), events("replay"));
}

#[test]
fn console_refuses_bad_input_before_listening() {
    let d = Dir::new();
    d.write("building.toml", BUILDING);
    // The default scenario's rules name a door this building does not have.
    let r = d.run(&[
        "console",
        "--building",
        "building.toml",
        "--port",
        "0",
        "--out",
        "runs",
    ]);
    assert_eq!(r.code(), 2, "{}", r.stderr());
    assert!(r.stderr().contains("door@14.5,1.3"), "{}", r.stderr());
    assert!(!r.stdout().contains("console: "), "{}", r.stdout());
    let r = d.run(&["console", "--map", "missing.json", "--port", "0"]);
    assert_eq!(r.code(), 2, "{}", r.stderr());
    assert!(r.stderr().contains("missing.json"), "{}", r.stderr());
    d.write("runs", "a file, not a folder");
    d.write("scenario.toml", SCENARIO);
    let r = d.run(&[
        "console",
        "--building",
        "building.toml",
        "--scenario",
        "scenario.toml",
        "--port",
        "0",
        "--out",
        "runs",
    ]);
    assert_eq!(r.code(), 2, "{}", r.stderr());
    assert!(!d.join("runs").is_dir());
}

#[test]
fn console_refuses_a_bad_cloud_before_listening_and_picks_up_the_one_beside_a_run() {
    let d = Dir::new();
    d.write("building.toml", BUILDING);
    d.write("scenario.toml", SCENARIO);
    let live = [
        "console",
        "--building",
        "building.toml",
        "--scenario",
        "scenario.toml",
        "--port",
        "0",
        "--out",
        "runs",
    ];
    let r = d.run(&[&live[..], &["--cloud", "missing.pcd"]].concat());
    assert_eq!(r.code(), 2, "{}", r.stderr());
    assert!(r.stderr().contains("missing.pcd"), "{}", r.stderr());
    d.write("empty.xyz", "");
    let r = d.run(&[&live[..], &["--cloud", "empty.xyz"]].concat());
    assert_eq!(r.code(), 2, "{}", r.stderr());
    assert!(r.stderr().contains("empty.xyz"), "{}", r.stderr());
    assert!(!r.stdout().contains("console: "), "{}", r.stdout());
    // A run folder in a `semsim run` output: the registered cloud beside it is picked up (here
    // a broken one, so the console stops before listening and names it).
    d.run(&["simulate", "--out", "out/simulation"]).ok();
    std::fs::create_dir_all(d.join("out/registration")).expect("mkdir");
    d.write("out/registration/map.pcd", "not a PCD file");
    let r = d.run(&["console", "--run", "out/simulation", "--port", "0"]);
    assert_eq!(r.code(), 2, "{}", r.stderr());
    assert!(r.stderr().contains("map.pcd"), "{}", r.stderr());
    // And the semantic map beside it is the world the run is replayed in (a broken one here,
    // named before listening); --building overrides it.
    std::fs::create_dir_all(d.join("out/map")).expect("mkdir");
    d.write("out/map/semantic_map.json", "{ not json");
    let r = d.run(&["console", "--run", "out/simulation", "--port", "0"]);
    assert_eq!(r.code(), 2, "{}", r.stderr());
    assert!(r.stderr().contains("semantic_map.json"), "{}", r.stderr());
}
