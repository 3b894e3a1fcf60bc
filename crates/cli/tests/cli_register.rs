//! End-to-end tests of `semsim register`: pairs, bad input, the GPU and sequences.

mod util;

use util::Dir;

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
