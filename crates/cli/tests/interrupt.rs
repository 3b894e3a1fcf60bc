//! A long simulation stopped with Ctrl-C (SIGINT) writes its events so far, its report says it
//! was interrupted, and the command exits 1 (the job did not finish).

mod util;

use std::process::Command;
use std::time::{Duration, Instant};
use util::Dir;

#[test]
fn ctrl_c_stops_a_long_simulation_cleanly_with_the_events_so_far() {
    let d = Dir::new();
    let scenario = include_str!("../../sim/data/default_scenario.toml")
        .replace("time_limit_s = 60.0", "time_limit_s = 1000000.0");
    d.write("long.toml", scenario);
    let child = Command::new(env!("CARGO_BIN_EXE_semsim"))
        .args(["simulate", "--scenario", "long.toml", "--out", "run"])
        .current_dir(d.path())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("semsim starts");
    // Wait until the simulation runs (its handler is installed before it starts), then press Ctrl-C.
    std::thread::sleep(Duration::from_secs(3));
    let sent = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(sent.success());
    let t0 = Instant::now();
    let out = child.wait_with_output().expect("semsim ends");
    assert!(t0.elapsed() < Duration::from_secs(60), "did not stop");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("interrupted at"), "{err}");
    let report = std::fs::read_to_string(d.join("run/report.md")).expect("report written");
    assert!(report.contains("FAILED (interrupted at"), "{report}");
    let events = std::fs::read_to_string(d.join("run/events.jsonl")).expect("events written");
    assert!(events.lines().count() > 1, "the events so far are kept");
}
