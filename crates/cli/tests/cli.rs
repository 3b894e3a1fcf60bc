//! End-to-end tests of the `semsim` binary: help, the demo pipeline, map, eval and simulate.

mod util;

use scanner::Building;
use util::Dir;

#[test]
fn help_works_on_every_command() {
    let d = Dir::new();
    for args in [
        vec!["--help"],
        vec!["demo", "--help"],
        vec!["convert", "--help"],
        vec!["info", "--help"],
        vec!["scan", "--help"],
        vec!["building", "--help"],
        vec!["building", "generate", "--help"],
        vec!["building", "check", "--help"],
        vec!["console", "--help"],
    ] {
        let out = d.run(&args).ok();
        assert!(out.contains("Usage"), "{args:?}: {out}");
    }
    d.run(&["frobnicate"]).bad_input(&["frobnicate"]);
}

#[test]
fn demo_writes_scans_ground_truth_odometry_and_config() {
    let d = Dir::new();
    let cfg = d.small_config();
    let out = d
        .run(&[
            "demo",
            "--out",
            "demo",
            "--config",
            cfg.to_str().expect("utf8"),
        ])
        .ok();
    assert!(out.contains("9 scans"), "{out}");
    assert!(
        out.contains("semsim console --map "),
        "the console command: {out}"
    );
    let files = d.listing("demo");
    for f in [
        "building.toml",
        "config.toml",
        "entities.json",
        "odometry.txt",
        "poses.txt",
        "scan000.pcd",
        "scan008.pcd",
    ] {
        assert!(files.contains(&f.to_string()), "{f} missing: {files:?}");
    }
    let scan = cloud::read_cloud(&d.join("demo/scan003.pcd")).expect("readable scan");
    let o = scan.organized.expect("organised");
    assert_eq!((o.rows, o.cols), (61, 121));
    assert!(scan.labels.is_some());
    let truth = cloud::read_poses(&d.join("demo/poses.txt")).expect("poses");
    let odo = cloud::read_poses(&d.join("demo/odometry.txt")).expect("odometry");
    assert_eq!(truth.len(), 9);
    assert!(truth[0]
        .world_from_scan
        .abs_diff_eq(odo[0].world_from_scan, 1e-9));
    let drift =
        (truth[8].world_from_scan.translation - odo[8].world_from_scan.translation).length();
    assert!(drift > 0.02 && drift < 3.0, "odometry drift {drift}");
    // The written configuration is the one used, and can be passed back.
    let used = std::fs::read_to_string(d.join("demo/config.toml")).expect("config");
    assert!(
        used.contains("beams = 121") && used.contains("seed = 5"),
        "{used}"
    );
    let b = Building::load(&d.join("demo/building.toml")).expect("building reloads");
    assert_eq!(b, Building::default_building().expect("default"));
    // The map stage: its files, a map that loads again, labels for every point.
    let map_files = d.listing("demo/map");
    for f in [
        "semantic_map.json",
        "labels.pcd",
        "projection.png",
        "filtered.png",
        "dilated.png",
        "skeleton.png",
        "segments.png",
        "merged_segments.png",
        "top_view.png",
        "labels.png",
        "config.toml",
    ] {
        assert!(
            map_files.contains(&f.to_string()),
            "{f} missing: {map_files:?}"
        );
    }
    let map = semantic::SemanticMap::load(&d.join("demo/map/semantic_map.json")).expect("loads");
    assert!(map.of_class(semantic::EntityClass::Wall).count() >= 4);
    let labelled = cloud::read_cloud(&d.join("demo/map/labels.pcd")).expect("labels.pcd");
    assert!(labelled.labels.is_some() && labelled.len() > 10_000);
    // eval map against the truth seen by the demo's scans: floor and ceiling found, the JSON
    // parses.
    let scans: Vec<String> = d
        .listing("demo")
        .into_iter()
        .filter(|f| f.starts_with("scan") && f.ends_with(".pcd"))
        .map(|f| format!("demo/{f}"))
        .collect();
    assert!(scans.len() >= 2, "{scans:?}");
    let mut args = vec!["eval", "map", "demo/map/semantic_map.json"];
    args.extend([
        "--building",
        "demo/building.toml",
        "--poses",
        "demo/poses.txt",
    ]);
    args.push("--cloud");
    args.extend(scans.iter().map(String::as_str));
    args.push("--json");
    let ev: serde_json::Value = serde_json::from_str(&d.run(&args).ok()).expect("one JSON object");
    assert_eq!(ev["floor"]["matched"], 1, "{ev}");
    assert_eq!(ev["ceiling"]["matched"], 1, "{ev}");
    let walls = &ev["walls"];
    eprintln!("coarse-laser demo map: walls {walls}");
    assert!(walls["f1"].as_f64().expect("f1") >= 0.75, "{ev}");
    // --true-poses relates a registration's frame to the building's: with the true poses as
    // --poses too, the frames are one and the score is the same; a pose file naming none of
    // the scans is bad input naming it.
    let mut same = args.clone();
    same.extend(["--true-poses", "demo/poses.txt"]);
    let ev_same: serde_json::Value =
        serde_json::from_str(&d.run(&same).ok()).expect("one JSON object");
    assert_eq!(ev_same, ev);
    d.write("other.txt", "elsewhere 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n");
    let mut other = args.clone();
    other.extend(["--true-poses", "other.txt"]);
    d.run(&other).bad_input(&["other.txt", "no scan of"]);
    // The map's own labels.pcd is not ground truth: a clear error, not a meaningless score.
    d.run(&[
        "eval",
        "map",
        "demo/map/semantic_map.json",
        "--building",
        "demo/building.toml",
        "--cloud",
        "demo/map/labels.pcd",
    ])
    .bad_input(&["not its ground-truth labels"]);
    // The simulation ran in the map's world and left its scenario; rerunning it from the map
    // gives the same events byte for byte.
    let sim_files = d.listing("demo/simulation");
    assert!(
        sim_files.contains(&"scenario.toml".to_string()),
        "{sim_files:?}"
    );
    let rerun = d.run(&[
        "simulate",
        "--map",
        "demo/map/semantic_map.json",
        "--scenario",
        "demo/simulation/scenario.toml",
        "--out",
        "rerun",
    ]);
    assert!(rerun.code() == 0 || rerun.code() == 1, "{}", rerun.stderr());
    assert_eq!(
        std::fs::read(d.join("demo/simulation/events.jsonl")).expect("events"),
        std::fs::read(d.join("rerun/events.jsonl")).expect("rerun events")
    );
}

#[test]
fn map_eval_and_run_reject_bad_input() {
    let d = Dir::new();
    d.write("empty.xyz", "");
    d.write("bad.json", "{\"format\": \"semsim.semantic_map\", \"version\": 1, \"entities\": [{\"id\": 1, \"class\": \"window\"}]}");
    d.run(&["map", "nope.pcd", "--out", "m"])
        .bad_input(&["nope.pcd"]);
    d.run(&["map", "empty.xyz", "--out", "m"]).bad_input(&[]);
    d.run(&["map", "empty.xyz", "--voxel-m=-1", "--out", "m"])
        .bad_input(&["--voxel-m"]);
    d.run(&["eval", "map", "bad.json", "--building", "default"])
        .bad_input(&["bad.json"]);
    d.run(&["simulate", "--map", "bad.json", "--out", "s"])
        .bad_input(&["bad.json"]);
    d.write("s.toml", "name = \"x\"\ntime_limit_s = -1.0\n");
    d.run(&["run", "empty.xyz", "--scenario", "s.toml", "--out", "r"])
        .bad_input(&[]);
    assert!(!d.join("m/semantic_map.json").exists());
}

#[test]
fn simulate_default_scenario_passes_deterministically_and_rejects_bad_input() {
    let d = Dir::new();
    let out = d.run(&["simulate", "--out", "a"]).ok();
    assert!(out.contains("PASSED"), "{out}");
    d.run(&["simulate", "--out", "b", "--scenario", "a/scenario.toml"])
        .ok();
    let a = std::fs::read(d.join("a/events.jsonl")).expect("events");
    assert!(!a.is_empty());
    assert_eq!(
        a,
        std::fs::read(d.join("b/events.jsonl")).expect("events"),
        "events differ between runs"
    );
    let text = std::fs::read_to_string(d.join("a/scenario.toml")).expect("scenario");
    d.write("bad.toml", text.replace("stairs@16.9,4.2", "stairs@99,99"));
    d.run(&["simulate", "--out", "c", "--scenario", "bad.toml"])
        .bad_input(&["stairs@99,99"]);
    d.write(
        "neg.toml",
        text.replace("time_limit_s = 60.0", "time_limit_s = -1.0"),
    );
    d.run(&["simulate", "--out", "c", "--scenario", "neg.toml"])
        .bad_input(&["time_limit_s"]);
}
