//! End-to-end tests of the `semsim` binary.

mod util;

use scanner::{Building, BuildingGeometry};
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
fn noiseless_scan_of_a_generated_building_lies_on_the_labelled_surfaces() {
    let d = Dir::new();
    d.run(&["building", "generate", "--seed", "17", "--out", "b.toml"])
        .ok();
    let b = Building::load(&d.join("b.toml")).expect("generated building loads");
    let y = 0.0;
    let x = 0.3 * (b.floor.max_m[0] - b.floor.min_m[0]);
    let cfg = d.small_config();
    d.run(&[
        "scan",
        "--building",
        "b.toml",
        "--pose",
        &format!("{x},{y},15"),
        "--pose",
        "2.0,0.0,-30",
        "--out",
        "scans",
        "--noise",
        "0",
        "--config",
        cfg.to_str().expect("utf8"),
    ])
    .ok();
    let geometry = BuildingGeometry::new(&b);
    let poses = cloud::read_poses(&d.join("scans/poses.txt")).expect("poses");
    assert_eq!(poses.len(), 2);
    for p in &poses {
        let mut scan = cloud::read_cloud(&d.join(&format!("scans/{}.pcd", p.name))).expect("scan");
        scan.transform(&p.world_from_scan);
        let labels = scan.labels.as_ref().expect("labels");
        let mut n = 0;
        for (q, l) in scan.points.iter().zip(labels) {
            if q.is_finite() {
                let dist = geometry.distance_to_entity(*q, l.entity);
                assert!(
                    dist < 1e-3,
                    "{}: {q} is {dist} m off entity {}",
                    p.name,
                    l.entity
                );
                n += 1;
            }
        }
        assert!(n > 3000, "{}: only {n} returns", p.name);
    }
}

#[test]
fn same_seed_generates_the_same_file() {
    let d = Dir::new();
    d.run(&["building", "generate", "--seed", "4", "--out", "a.toml"])
        .ok();
    d.run(&["building", "generate", "--seed", "4", "--out", "b.json"])
        .ok();
    d.run(&["building", "generate", "--seed", "5", "--out", "c.toml"])
        .ok();
    let a = Building::load(&d.join("a.toml")).expect("a");
    assert_eq!(a, Building::load(&d.join("b.json")).expect("b"));
    assert_ne!(a, Building::load(&d.join("c.toml")).expect("c"));
    let check = d.run(&["building", "check", "a.toml"]).ok();
    assert!(
        check.contains("valid") && check.contains("staircases"),
        "{check}"
    );
}

#[test]
fn door_wider_than_its_wall_is_bad_input_and_writes_nothing() {
    let d = Dir::new();
    let text = Building::default_building().expect("default");
    let mut b = text.clone();
    b.walls[4].doors[0].width_m = 30.0;
    let toml = toml::to_string(&b).expect("serialise");
    d.write("wide.toml", toml);
    d.run(&[
        "scan",
        "--building",
        "wide.toml",
        "--pose",
        "1,0,0",
        "--out",
        "out",
    ])
    .bad_input(&["wide.toml", "walls[4]", "doors[0]", "wider than its wall"]);
    assert!(!d.join("out").exists() || d.listing("out").is_empty());
    d.run(&["building", "check", "wide.toml"])
        .bad_input(&["wider than its wall"]);
}

#[test]
fn scan_poses_must_be_sane() {
    let d = Dir::new();
    d.run(&["building", "generate", "--seed", "2", "--out", "b.toml"])
        .ok();
    d.run(&[
        "scan",
        "--building",
        "b.toml",
        "--pose",
        "0,0,0",
        "--out",
        "o",
    ])
    .bad_input(&["pose 0", "inside walls["]);
    d.run(&[
        "scan",
        "--building",
        "b.toml",
        "--pose",
        "500,0,0",
        "--out",
        "o",
    ])
    .bad_input(&["outside the building"]);
    d.run(&[
        "scan",
        "--building",
        "b.toml",
        "--pose",
        "1,nan,0",
        "--out",
        "o",
    ])
    .bad_input(&["x,y,yaw"]);
    d.run(&[
        "scan",
        "--building",
        "b.toml",
        "--pose",
        "1,0",
        "--out",
        "o",
    ])
    .bad_input(&["three finite numbers"]);
    d.run(&[
        "scan",
        "--building",
        "missing.toml",
        "--pose",
        "1,0,0",
        "--out",
        "o",
    ])
    .bad_input(&["missing.toml"]);
    let cfg = d.write("bad.toml", "[laser]\nbeams = 0\n");
    d.run(&[
        "scan",
        "--building",
        "b.toml",
        "--pose",
        "1,0,0",
        "--out",
        "o",
        "--config",
        cfg.to_str().expect("utf8"),
    ])
    .bad_input(&["beams"]);
    let cfg = d.write("typo.toml", "[lasr]\nbeams = 10\n");
    d.run(&["demo", "--config", cfg.to_str().expect("utf8")])
        .bad_input(&["typo.toml", "lasr"]);
}

#[test]
fn register_pair_prints_one_json_object_near_the_truth() {
    let d = Dir::new();
    let cfg = d.small_config();
    d.run(&[
        "demo",
        "--out",
        "demo",
        "--config",
        cfg.to_str().expect("utf8"),
    ])
    .ok();
    let out = d
        .run(&[
            "register",
            "demo/scan002.pcd",
            "demo/scan001.pcd",
            "--guess",
            "2.4,-0.1,0,0,0,2",
            "--json",
            "--plot",
            "rmse.svg",
        ])
        .ok();
    let v: serde_json::Value = serde_json::from_str(out.trim()).expect("exactly one JSON object");
    for key in [
        "transform",
        "iterations",
        "rmse_m",
        "fitness",
        "ms_per_iteration",
        "total_ms",
    ] {
        assert!(v.get(key).is_some(), "{key} missing: {out}");
    }
    let m: Vec<f64> = v["transform"]
        .as_array()
        .expect("array")
        .iter()
        .map(|x| x.as_f64().expect("number"))
        .collect();
    assert_eq!(m.len(), 16);
    let truth = cloud::read_poses(&d.join("demo/poses.txt")).expect("poses");
    let t = truth[1].world_from_scan.inverse() * truth[2].world_from_scan;
    assert!(
        (m[3] - t.translation.x).abs() < 0.01 && (m[7] - t.translation.y).abs() < 0.01,
        "{m:?} vs {t:?}"
    );
    assert!(std::fs::read_to_string(d.join("rmse.svg"))
        .expect("plot")
        .contains("<svg"));
}

#[test]
fn register_rejects_bad_input_and_reports_non_convergence() {
    let d = Dir::new();
    let cfg = d.small_config();
    d.run(&[
        "demo",
        "--out",
        "demo",
        "--config",
        cfg.to_str().expect("utf8"),
    ])
    .ok();
    d.write("g15.txt", "1 0 0 0 0 1 0 0 0 0 1 0 0 0 0");
    d.run(&[
        "register",
        "demo/scan001.pcd",
        "demo/scan000.pcd",
        "--guess",
        "g15.txt",
    ])
    .bad_input(&["g15.txt", "16 numbers", "found 15"]);
    d.write("empty.xyz", "# nothing\n");
    d.run(&["register", "empty.xyz", "demo/scan000.pcd"])
        .bad_input(&["empty.xyz", "no points"]);
    d.write(
        "missing.pcd",
        "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 2\n\
         VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 4\nDATA ascii\nnan nan nan\nnan nan nan\nnan nan nan\nnan nan nan\n",
    );
    d.run(&["register", "missing.pcd", "demo/scan000.pcd"])
        .bad_input(&["missing.pcd (source)", "no valid point"]);
    d.write("nan.xyz", "1 2 3\nnan 1 1\n");
    d.run(&["register", "nan.xyz", "demo/scan000.pcd"])
        .bad_input(&["nan.xyz"]);
    d.run(&[
        "register",
        "demo/scan001.pcd",
        "demo/scan000.pcd",
        "--guess",
        "100,0,0,0,0,0",
    ])
    .bad_input(&["overlap"]);
    let hard = d.write(
        "hard.toml",
        "[registration.icp]\nmax_iterations = 2\nmethod = \"point_to_point\"\n",
    );
    let r = d.run(&[
        "register",
        "demo/scan004.pcd",
        "demo/scan000.pcd",
        "--config",
        hard.to_str().expect("utf8"),
    ]);
    assert_eq!(r.code(), 1, "{}{}", r.stdout(), r.stderr());
    assert!(
        r.stderr().contains("did not converge") && !r.stdout().contains("target_from_source"),
        "{}",
        r.stderr()
    );
}

/// The 16 numbers of `semsim register --json`'s transform.
fn json_transform(out: &str) -> Vec<f64> {
    let v: serde_json::Value = serde_json::from_str(out.trim()).expect("exactly one JSON object");
    v["transform"]
        .as_array()
        .expect("array")
        .iter()
        .map(|x| x.as_f64().expect("number"))
        .collect()
}

#[test]
fn register_on_the_gpu_gives_the_cpus_transform_and_bad_devices_are_bad_input() {
    let d = Dir::new();
    let cfg = d.small_config();
    d.run(&[
        "demo",
        "--out",
        "demo",
        "--config",
        cfg.to_str().expect("utf8"),
    ])
    .ok();
    let pair = |device: &str| {
        d.run(&[
            "register",
            "demo/scan002.pcd",
            "demo/scan001.pcd",
            "--guess",
            "2.4,-0.1,0,0,0,2",
            "--method",
            "p2plane",
            "--device",
            device,
            "--json",
        ])
    };
    let cpu = pair("cpu");
    let cpu_out = cpu.ok();
    assert!(cpu.stderr().contains("device: CPU"), "{}", cpu.stderr());
    let gpu = pair("gpu");
    if gpu.code() == 2 && gpu.stderr().contains("no GPU adapter") {
        eprintln!("SKIPPED the GPU half: {}", gpu.stderr());
    } else {
        let gpu_out = gpu.ok();
        assert!(gpu.stderr().contains("device: GPU"), "{}", gpu.stderr());
        let (a, b) = (json_transform(&cpu_out), json_transform(&gpu_out));
        for (x, y) in a.iter().zip(&b) {
            assert!((x - y).abs() < 1e-4, "GPU {b:?} vs CPU {a:?}");
        }
        let v: serde_json::Value = serde_json::from_str(gpu_out.trim()).expect("json");
        assert!(v["device"].as_str().is_some_and(|s| s.starts_with("GPU")));
    }
    // auto says what it chose, and on a software adapter (or none) falls back to the CPU.
    let auto = pair("auto");
    auto.ok();
    assert!(auto.stderr().contains("device: "), "{}", auto.stderr());
    pair("tpu").bad_input(&["tpu", "auto, cpu or gpu"]);
    let gicp = d.write(
        "gicp_gpu.toml",
        "[registration.icp]\nmethod = \"gicp\"\ndevice = \"gpu\"\n",
    );
    d.run(&[
        "register",
        "demo/scan002.pcd",
        "demo/scan001.pcd",
        "--config",
        gicp.to_str().expect("utf8"),
    ])
    .bad_input(&["device", "GICP"]);
}

#[test]
fn register_sequence_of_the_3dtk_corridor_uses_its_pose_files() {
    let Some(real) = util::real_data() else {
        return;
    };
    let d = Dir::new();
    let corridor = real.join("3dtk-corridor");
    let out = d
        .run(&[
            "register",
            "--sequence",
            corridor.to_str().expect("utf8"),
            "--out",
            "reg",
        ])
        .ok();
    assert!(out.contains("scan002"), "{out}");
    let poses = cloud::read_poses(&d.join("reg/poses.txt")).expect("poses");
    assert_eq!(poses.len(), 3);
    let map = cloud::read_cloud(&d.join("reg/map.pcd")).expect("map");
    assert!(map.len() > 10_000);
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
