//! `semsim console` in a real browser (issue 14): the real binary serves the page, and
//! headless Chromium (driven by npm `playwright-core`, `tools/oracles/console_e2e.mjs`) loads
//! it, renders the world with WebGL (software rendering), drives the robot with the keyboard
//! and into a wall until the timeline shows a `wall_touched` event. The screenshots are also
//! copied to `target/console_e2e/` for a person to look at.
//!
//! The oracles are `node`, `playwright-core` and `chromium`: without them the test says so and
//! passes, unless `SEMSIM_REQUIRE_ORACLES=1` (`scripts/test.sh`), which makes it fail.

mod util;

use fixtures::oracles;
use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};
use util::Dir;

/// How long the console may take to print its URL, and to stop on Ctrl-C.
const SERVER_TIMEOUT: Duration = Duration::from_secs(90);
/// How long the browser script may take (software WebGL on a loaded machine is slow); the
/// script has its own, shorter, per-step time limits and says which step failed.
const BROWSER_TIMEOUT: Duration = Duration::from_secs(240);

/// The default building with no scripted commands: the robot waits in the corridor at
/// (10, 0) facing east (+x), with 9 m of corridor ahead of it and the corridor's north wall
/// (no door between x = 9 and 14) 1.2 m to its left.
const SCENARIO: &str = r#"
name = "browser test: wait for the operator"
building = "default"
robot = "inspection"
time_limit_s = 3600.0
start = { x_m = 10.0, y_m = 0.0, yaw_deg = 0.0 }
[rules]
max_wall_contact_s = 0.5
"#;

const SCREENSHOTS: [&str; 3] = [
    "console_loaded.png",
    "console_after_drive.png",
    "console_wall_event.png",
];

/// Runs `command` to its end, killing it (and failing) after `timeout`: (code, stdout, stderr).
fn run_with_timeout(command: &mut Command, timeout: Duration) -> (i32, String, String) {
    let mut child = command
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("could not start {command:?}: {e}"));
    // Read both pipes on threads so that a chatty child never blocks on a full pipe.
    let drain = |mut r: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut s = String::new();
            let _ = r.read_to_string(&mut s);
            s
        })
    };
    let out = drain(Box::new(child.stdout.take().expect("stdout")));
    let err = drain(Box::new(child.stderr.take().expect("stderr")));
    let status = wait_for(&mut child, timeout);
    let out = out.join().expect("stdout reader");
    let err = err.join().expect("stderr reader");
    match status {
        Some(code) => (code, out, err),
        None => {
            panic!("{command:?} did not finish within {timeout:?}:\nstdout:\n{out}\nstderr:\n{err}")
        }
    }
}

/// Waits for `child` to end: its exit code, or `None` (having killed it) after `timeout`.
fn wait_for(child: &mut Child, timeout: Duration) -> Option<i32> {
    let t0 = Instant::now();
    loop {
        if let Some(status) = child.try_wait().expect("waits") {
            return Some(status.code().unwrap_or(-1));
        }
        if t0.elapsed() > timeout {
            let _ = child.kill();
            let _ = child.wait();
            return None;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// The console, stopped with Ctrl-C (SIGINT) when dropped, so that a failing test leaves no
/// server behind.
struct Server {
    child: Option<Child>,
}

impl Server {
    /// Ctrl-C, then its exit code and stderr.
    fn stop(&mut self) -> (i32, String) {
        let mut child = self.child.take().expect("a running console");
        let _ = Command::new("kill")
            .args(["-INT", &child.id().to_string()])
            .status();
        let code = wait_for(&mut child, SERVER_TIMEOUT);
        let mut err = String::new();
        if let Some(mut s) = child.stderr.take() {
            let _ = s.read_to_string(&mut err);
        }
        (
            code.unwrap_or_else(|| panic!("the console did not stop: {err}")),
            err,
        )
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        if self.child.is_some() {
            let _ = self.stop();
        }
    }
}

/// Starts `semsim console` in `dir` on a free port: the server and its URL.
fn start_console(dir: &Path) -> (Server, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_semsim"))
        .args(["console", "--building", "default"])
        .args([
            "--scenario",
            "scenario.toml",
            "--port",
            "0",
            "--out",
            "runs",
        ])
        .current_dir(dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("semsim starts");
    let stdout = child.stdout.take().expect("stdout");
    let mut server = Server { child: Some(child) };
    let (tx, rx) = mpsc::channel();
    // Reads the URL line, then the rest of stdout (so that the console never blocks on it).
    std::thread::spawn(move || {
        let mut tx = Some(tx);
        for line in BufReader::new(stdout).lines().map_while(Result::ok) {
            if line.starts_with("console: ") {
                if let Some(tx) = tx.take() {
                    let _ = tx.send(line);
                }
            }
        }
    });
    match rx.recv_timeout(SERVER_TIMEOUT) {
        Ok(line) => (server, line.trim_start_matches("console: ").to_string()),
        Err(_) => {
            let (code, err) = server.stop();
            panic!("semsim console printed no URL (exit {code}):\n{err}");
        }
    }
}

/// A number from the script's JSON result.
fn number(v: &serde_json::Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("no number {key} in {v}"))
}

#[test]
fn console_renders_and_drives_in_a_real_browser() {
    let Some(node) = oracles::program("node") else {
        return;
    };
    if oracles::node_package("playwright-core").is_none() {
        return;
    }
    let Some(chromium) = oracles::program("chromium") else {
        return;
    };
    let d = Dir::new();
    d.write("scenario.toml", SCENARIO);
    let (mut server, url) = start_console(d.path());
    let shots = d.join("screenshots");
    let t0 = Instant::now();
    let (code, out, err) = run_with_timeout(
        Command::new(&node)
            .arg(oracles::script("console_e2e.mjs"))
            .arg(&url)
            .arg(&shots)
            .env("CHROMIUM", &chromium),
        BROWSER_TIMEOUT,
    );
    let took = t0.elapsed();
    // Keep the screenshots for a person to look at, whatever happened.
    let keep: PathBuf = oracles::workspace_root().join("target/console_e2e");
    let _ = std::fs::create_dir_all(&keep);
    for name in SCREENSHOTS {
        let _ = std::fs::copy(shots.join(name), keep.join(name));
    }
    assert_eq!(
        code, 0,
        "the browser test failed after {took:.1?}:\nstdout:\n{out}\nstderr:\n{err}"
    );
    eprintln!("console_e2e.mjs ({took:.1?}): {out}");
    let line = out
        .lines()
        .rev()
        .find(|l| l.starts_with('{'))
        .unwrap_or_else(|| panic!("no JSON line:\n{out}\n{err}"));
    let r: serde_json::Value = serde_json::from_str(line).expect("JSON results");
    assert_eq!(r["ok"], true, "{r}");
    assert_eq!(r["console_errors"], serde_json::json!([]), "{r}");
    assert!(number(&r, "canvas_colours") > 16.0, "a blank canvas: {r}");
    assert!(
        number(&r, "canvas_non_background") > 0.05,
        "a blank canvas: {r}"
    );
    let moved = number(&r, "moved_m");
    assert!(moved > 0.2, "W moved the robot only {moved} m: {r}");
    // Forwards: east, along the corridor.
    assert!(number(&r, "moved_dx_m") > 0.2, "{r}");
    assert!(
        r["wall_event"]
            .as_str()
            .is_some_and(|s| s.contains("wall touched")),
        "{r}"
    );
    for name in SCREENSHOTS {
        let png = std::fs::read(shots.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(&png[1..4], b"PNG", "{name}");
    }
    // The console stops on Ctrl-C and saves the session.
    let (code, err) = server.stop();
    assert_eq!(code, 0, "{err}");
    assert!(d.join("runs/session-001/events.jsonl").is_file(), "{err}");
    let events = std::fs::read_to_string(d.join("runs/session-001/events.jsonl")).expect("events");
    assert!(events.contains("\"wall_touched\""), "{events}");
}
