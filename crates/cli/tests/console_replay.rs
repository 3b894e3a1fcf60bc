//! Showing a recorded run (issue 14, items 5 and 6): `semsim report RUN_DIR --html F` writes
//! one self-contained HTML file (the world as embedded GLB, three.js inlined as `data:`
//! modules, the trajectory, every event, the verdict and rules), refuses bad run folders with
//! exit 2 naming the file, and, where the browser oracles are installed, opens from file://
//! in headless Chromium (`tools/oracles/report_e2e.mjs`): no console errors, a non-blank
//! canvas, the time slider moves the robot. The screenshots are also copied to
//! `target/report_e2e/`.

mod util;

use fixtures::oracles;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;
use util::Dir;

/// `semsim simulate` (the default scenario) into `d/run`.
fn simulated_run(d: &Dir) -> PathBuf {
    d.run(&["simulate", "--out", "run"]).ok();
    d.join("run")
}

/// The text of the `<script ... id="ID">` element.
fn script_text<'a>(html: &'a str, id: &str) -> &'a str {
    let open = format!("id=\"{id}\">");
    let start = html
        .find(&open)
        .unwrap_or_else(|| panic!("no element {id}"))
        + open.len();
    let len = html[start..].find("</script>").expect("closed");
    &html[start..start + len]
}

fn jsonl(path: &Path) -> Vec<Value> {
    std::fs::read_to_string(path)
        .expect("read")
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| serde_json::from_str(l).expect("json line"))
        .collect()
}

#[test]
fn a_report_is_one_self_contained_html_file() {
    let d = Dir::new();
    let run = simulated_run(&d);
    let out = d.run(&["report", "run", "--html", "r.html"]).ok();
    assert!(out.contains("verdict: PASSED"), "{out}");
    // One file, written atomically: no temporary file is left beside it.
    assert_eq!(d.listing(""), ["r.html", "run"]);
    let html = std::fs::read_to_string(d.join("r.html")).expect("html");

    // The world: a GLB ("glTF" magic, base64 "Z2xURg") embedded as base64.
    let glb = script_text(&html, "glb").trim();
    assert!(glb.starts_with("Z2xURg"), "{}", &glb[..glb.len().min(40)]);
    assert!(glb.len() > 10_000 && glb.len().is_multiple_of(4));
    assert!(glb
        .bytes()
        .all(|b| b.is_ascii_alphanumeric() || b"+/=".contains(&b)));

    // three.js and its loader: modules inlined as data: URLs, nothing fetched.
    let start = html
        .find("<script type=\"importmap\">")
        .expect("an import map")
        + 25;
    let end = start + html[start..].find("</script>").expect("closed");
    let map: Value = serde_json::from_str(&html[start..end]).expect("import map json");
    let imports = map["imports"].as_object().expect("imports");
    for name in [
        "three",
        "three/core",
        "three/addons/loaders/GLTFLoader.js",
        "three/addons/controls/OrbitControls.js",
    ] {
        let url = imports[name].as_str().expect("a url");
        assert!(url.starts_with("data:text/javascript;base64,"), "{name}");
    }
    for bad in [
        "src=\"http",
        "src='http",
        "href=\"http",
        "href='http",
        "src=http",
    ] {
        assert!(!html.contains(bad), "the report references {bad}...");
    }
    assert!(!html.contains("<script src"), "a script from a file");
    assert!(
        !html.contains("<link rel=\"stylesheet\""),
        "a style sheet from a file"
    );
    assert!(!html.contains("@@"), "a placeholder left");

    // The run: every event of events.jsonl, the whole trajectory, the verdict and rules.
    let data: Value = serde_json::from_str(script_text(&html, "run")).expect("run json");
    let events = jsonl(&run.join("events.jsonl"));
    assert!(events.len() > 10);
    assert_eq!(data["events"].as_array().expect("events"), &events);
    let rows = std::fs::read_to_string(run.join("trajectory.csv"))
        .expect("csv")
        .lines()
        .count()
        - 1;
    assert_eq!(
        data["trajectory"].as_array().expect("trajectory").len(),
        rows
    );
    assert_eq!(data["verdict"], "PASSED");
    assert_eq!(data["passed"], true);
    let rules = data["rules"].as_array().expect("rules");
    assert!(rules.iter().any(|r| r["rule"]
        .as_str()
        .is_some_and(|n| n.starts_with("reach_top_of_stairs"))));
    assert!(rules.iter().all(|r| r["result"] == "passed"));
    assert_eq!(data["title"], "corridor, door, stairs");
    // The doors' angles (doors.csv), one sample per trajectory row.
    assert!(!data["doors"]["doors"].as_array().expect("doors").is_empty());
    assert_eq!(
        data["doors"]["samples"].as_array().expect("samples").len(),
        rows
    );
    // No --cloud: no cloud embedded.
    assert_eq!(script_text(&html, "cloud-meta"), "null");

    // Written again over itself (atomic rename), and with an explicit world.
    d.run(&["report", "run", "--html", "r.html", "--building", "default"])
        .ok();
    assert_eq!(d.listing(""), ["r.html", "run"]);
}

#[test]
fn a_run_folder_without_doors_csv_still_reports_and_replays_doors_at_their_initial_angle() {
    let d = Dir::new();
    let run = simulated_run(&d);
    std::fs::remove_file(run.join("doors.csv")).expect("rm");
    d.run(&["report", "run", "--html", "r.html"]).ok();
    let html = std::fs::read_to_string(d.join("r.html")).expect("html");
    let data: Value = serde_json::from_str(script_text(&html, "run")).expect("run json");
    assert_eq!(data["doors"]["samples"], serde_json::json!([]));
    // A malformed doors.csv is refused naming its line.
    std::fs::write(run.join("doors.csv"), "time_s,door_3\n0,1,2\n").expect("w");
    d.run(&["report", "run", "--html", "r.html"])
        .bad_input(&["doors.csv:2"]);
}

#[test]
fn a_report_embeds_a_small_downsampled_cloud() {
    let d = Dir::new();
    simulated_run(&d);
    // 250,000 points on a 5 m x 5 m sheet (1 cm apart): downsampled to at most 30,000.
    let mut text = String::new();
    for i in 0..500 {
        for j in 0..500 {
            text.push_str(&format!("{} {} 1.0\n", i as f64 * 0.01, j as f64 * 0.01));
        }
    }
    d.write("sheet.xyz", text);
    d.run(&["report", "run", "--html", "plain.html"]).ok();
    d.run(&["report", "run", "--html", "r.html", "--cloud", "sheet.xyz"])
        .ok();
    let html = std::fs::read_to_string(d.join("r.html")).expect("html");
    let meta: Value = serde_json::from_str(script_text(&html, "cloud-meta")).expect("json");
    let points = meta["info"]["points"].as_u64().expect("points");
    assert!((1_000..=30_000).contains(&points), "{meta}");
    assert_eq!(meta["info"]["points_in_file"], 250_000);
    assert_eq!(meta["info"]["classes"], false);
    // 13 bytes a point, base64.
    let bin = script_text(&html, "cloud-bin").trim();
    assert_eq!(bin.len(), (points as usize * 13).div_ceil(3) * 4);
    // The cloud adds at most 30,000 x 13 bytes in base64 (520 kB) to the file.
    let plain = std::fs::metadata(d.join("plain.html"))
        .expect("plain")
        .len() as usize;
    assert!(
        html.len() - plain <= 530_000,
        "{} bytes more",
        html.len() - plain
    );
}

#[test]
fn bad_run_folders_exit_2_naming_the_file() {
    let d = Dir::new();
    d.run(&["report", "missing", "--html", "r.html"])
        .bad_input(&["missing"]);
    let run = simulated_run(&d);
    let csv = std::fs::read_to_string(run.join("trajectory.csv")).expect("csv");
    let events = std::fs::read_to_string(run.join("events.jsonl")).expect("events");

    std::fs::remove_file(run.join("trajectory.csv")).expect("rm");
    d.run(&["report", "run", "--html", "r.html"])
        .bad_input(&["trajectory.csv"]);

    std::fs::write(run.join("trajectory.csv"), format!("{csv}1.0,2.0,oops\n")).expect("w");
    let line = csv.lines().count() + 1;
    d.run(&["report", "run", "--html", "r.html"])
        .bad_input(&[&format!("trajectory.csv:{line}")]);

    std::fs::write(run.join("trajectory.csv"), &csv).expect("w");
    std::fs::write(run.join("events.jsonl"), format!("{events}{{\"kind\":\n")).expect("w");
    let line = events.lines().count() + 1;
    d.run(&["report", "run", "--html", "r.html"])
        .bad_input(&[&format!("events.jsonl:{line}")]);

    std::fs::write(run.join("events.jsonl"), &events).expect("w");
    std::fs::remove_file(run.join("report.md")).expect("rm");
    d.run(&["report", "run", "--html", "r.html"])
        .bad_input(&["report.md"]);
    assert!(!d.join("r.html").exists(), "nothing written on bad input");
}

#[test]
fn the_report_opens_from_a_file_in_a_real_browser() {
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
    simulated_run(&d);
    d.run(&["report", "run", "--html", "r.html"]).ok();
    let shots = d.join("shots");
    let out = oracles::run_ok(
        Command::new(node)
            .arg(oracles::script("report_e2e.mjs"))
            .arg(d.join("r.html"))
            .arg(&shots)
            .env("CHROMIUM", &chromium),
    );
    let result: Value = serde_json::from_str(out.trim()).expect("one JSON line");
    assert_eq!(result["ok"], true, "{out}");
    assert_eq!(result["verdict"], "Verdict: PASSED", "{out}");
    assert!(
        result["marker_moved_m"].as_f64().is_some_and(|m| m > 0.5),
        "{out}"
    );
    let keep = oracles::workspace_root().join("target/report_e2e");
    let _ = std::fs::create_dir_all(&keep);
    for name in ["report_start.png", "report_moved.png"] {
        let shot = shots.join(name);
        assert!(shot.is_file(), "no screenshot {name}");
        let _ = std::fs::copy(&shot, keep.join(name));
    }
}

#[test]
fn console_run_refuses_a_bad_run_folder_before_listening() {
    let d = Dir::new();
    d.run(&["console", "--run", "missing", "--port", "0"])
        .bad_input(&["missing"]);
    let run = simulated_run(&d);
    std::fs::write(run.join("trajectory.csv"), "time_s\n").expect("w");
    d.run(&["console", "--run", "run", "--port", "0"])
        .bad_input(&["trajectory.csv:1"]);
    d.run(&["console", "--run", "run", "--scenario", "s.toml"])
        .bad_input(&["--scenario"]);
}
