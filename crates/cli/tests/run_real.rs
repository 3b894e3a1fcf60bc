//! `semsim run <dataset> --out <dir>` with no other flag on each real scan sequence of
//! `shared/data/real` (see its MANIFEST.md): no scenario is given, so one is planned in the
//! map's world. Every run ends with a verdict or a failed job (exit 0 or 1), never as bad
//! input (exit 2) or a panic; where it reaches the simulation, `simulation/scenario.toml` is
//! the planned scenario and `report.md` says what was not reachable.

mod util;

use util::{real_data, Dir};

/// Runs one dataset and checks what every run must show; returns (exit code, stdout, stderr).
fn run_dataset(name: &str) -> Option<(i32, String, String)> {
    let data = real_data()?.join(name);
    let dir = Dir::new();
    let out = dir.join("out");
    let r = dir.run(&[
        "run",
        data.to_str().expect("utf-8 path"),
        "--out",
        out.to_str().expect("utf-8 path"),
    ]);
    let (code, stdout, stderr) = (r.code(), r.stdout(), r.stderr());
    assert!(
        code == 0 || code == 1,
        "{name}: exit {code} (never 2)\nstdout: {stdout}\nstderr: {stderr}"
    );
    assert!(!stderr.contains("panicked"), "{name}: {stderr}");
    if stdout.contains("verdict: PASSED") || stderr.contains("verdict: FAILED") {
        // A verdict: the planned scenario and the report are written beside the outputs.
        assert!(stdout.contains("planned tour: "), "{name}: {stdout}");
        let sim = out.join("simulation");
        let scenario = sim::Scenario::load(&sim.join("scenario.toml"))
            .unwrap_or_else(|e| panic!("{name}: scenario.toml: {e}"));
        assert_eq!(scenario.rules.max_wall_contact_s, Some(0.5), "{name}");
        assert!(scenario.rules.no_tipping, "{name}");
        let text = std::fs::read_to_string(sim.join("scenario.toml")).expect("scenario.toml");
        assert!(text.starts_with("# Planned by semsim"), "{name}: {text}");
        let report = std::fs::read_to_string(sim.join("report.md")).expect("report.md");
        assert!(report.contains("## Verdict: "), "{name}: {report}");
        assert!(report.contains("## Not reachable"), "{name}: {report}");
    }
    Some((code, stdout, stderr))
}

#[test]
fn run_with_no_flags_on_the_3dtk_corridor_plans_a_scenario_and_gives_a_verdict() {
    let Some((_, stdout, stderr)) = run_dataset("3dtk-corridor") else {
        return;
    };
    // The corridor's three scans register from their .pose odometry and make a map: this run
    // must get as far as the verdict.
    assert!(
        stdout.contains("verdict: PASSED") || stderr.contains("verdict: FAILED"),
        "stdout: {stdout}\nstderr: {stderr}"
    );
}

#[test]
fn run_with_no_flags_on_the_pcl_room_never_exits_as_bad_input() {
    // Two scans without odometry, 0.69 rad apart (PCL's NDT tutorial starts from that guess):
    // registration from the identity may fail (exit 1, the job's failure); a verdict, if
    // reached, is checked like every other.
    if let Some((code, stdout, stderr)) = run_dataset("pcl-room") {
        eprintln!("pcl-room: exit {code}\n{stdout}\n{stderr}");
    }
}

#[test]
fn run_with_no_flags_on_small_gicp_never_exits_as_bad_input() {
    if let Some((code, stdout, stderr)) = run_dataset("small-gicp") {
        eprintln!("small-gicp: exit {code}\n{stdout}\n{stderr}");
    }
}
