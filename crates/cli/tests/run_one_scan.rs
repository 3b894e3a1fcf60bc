//! `semsim run` on a single scan: one station of a stop-and-scan survey, or a cloud a surveyor
//! registered already (one E57 or LAS of a whole floor). There is nothing to register it
//! against, so it defines the world as it stands, and the chain goes on to the map, a planned
//! tour and a verdict. `register --sequence` still asks for two scans: registering one is no
//! registration.

mod util;

use std::path::Path;
use util::{real_data, Dir};

fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

/// The poses of a `poses.txt` (name, then the row-major 4x4 `world_from_scan`).
fn poses(path: &Path) -> Vec<(String, Vec<f64>)> {
    std::fs::read_to_string(path)
        .expect("poses.txt")
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| {
            let mut t = l.split_whitespace();
            let name = t.next().expect("a name").to_string();
            (name, t.filter_map(|v| v.parse().ok()).collect())
        })
        .collect()
}

/// Runs `semsim run SCAN --out out` and checks what a run of one scan must show: a verdict
/// (exit 0 or 1, never bad input), one registered pose, the scan's own (identity here: the
/// files carry no pose), a map and a planned scenario. Returns the map.
fn run_one(d: &Dir, scan: &Path) -> semantic::SemanticMap {
    let out = d.join("out");
    let r = d.run(&["run", s(scan), "--out", s(&out)]);
    let (code, stdout, stderr) = (r.code(), r.stdout(), r.stderr());
    assert!(
        code == 0 || code == 1,
        "exit {code}\nstdout: {stdout}\nstderr: {stderr}"
    );
    assert!(
        stdout.contains("verdict: PASSED") || stderr.contains("verdict: FAILED"),
        "stdout: {stdout}\nstderr: {stderr}"
    );
    assert!(stdout.contains("planned tour: "), "{stdout}");
    assert!(
        stdout.contains("one scan, which defines the world"),
        "{stdout}"
    );
    let poses = poses(&out.join("registration/poses.txt"));
    assert_eq!(poses.len(), 1, "{poses:?}");
    let identity = [
        1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
    ];
    assert_eq!(poses[0].1.len(), 16, "{poses:?}");
    for (a, b) in poses[0].1.iter().zip(identity) {
        assert!((a - b).abs() < 1e-9, "{poses:?}");
    }
    assert!(out.join("simulation/scenario.toml").is_file());
    assert!(out.join("simulation/report.md").is_file());
    semantic::SemanticMap::load(&out.join("map/semantic_map.json")).expect("the map")
}

#[test]
fn run_on_one_virtual_scan_maps_it_as_it_stands_and_gives_a_verdict() {
    let d = Dir::new();
    let cfg = d.small_config();
    d.scan_default_building("scans", &["2,0,0"], &cfg).ok();
    let map = run_one(&d, &d.join("scans/scan000.pcd"));
    // The corridor the scanner stood in: its floor and the walls along it.
    assert_eq!(map.of_class(cloud::EntityClass::Floor).count(), 1);
    let walls = map.of_class(cloud::EntityClass::Wall).count();
    assert!(walls >= 2, "{walls} walls");
}

#[test]
fn run_on_one_real_scan_maps_it_as_it_stands_and_gives_a_verdict() {
    let Some(data) = real_data() else {
        return;
    };
    // PCL's room_scan1.pcd: one scan of an office room, no pose in the file.
    let d = Dir::new();
    let map = run_one(&d, &data.join("pcl-room/room_scan1.pcd"));
    assert_eq!(map.of_class(cloud::EntityClass::Floor).count(), 1);
    assert!(map.of_class(cloud::EntityClass::Wall).count() >= 1);
}

#[test]
fn register_sequence_of_one_scan_is_still_bad_input() {
    let Some(data) = real_data() else {
        return;
    };
    let d = Dir::new();
    let scan = data.join("pcl-room/room_scan1.pcd");
    d.run(&["register", "--sequence", s(&scan), "--out", "reg"])
        .bad_input(&[
            "room_scan1.pcd",
            "a sequence needs at least two scans, found 1",
        ]);
    assert!(!d.join("reg").exists());
}

#[test]
fn run_on_a_folder_with_no_scan_files_names_the_formats_it_reads() {
    let d = Dir::new();
    std::fs::create_dir_all(d.join("empty")).expect("a folder");
    std::fs::write(d.join("empty/notes.txt"), "no scans here").expect("a file");
    d.run(&["run", "empty", "--out", "out"]).bad_input(&[
        "empty",
        "no scan files found",
        ".pcd",
        ".e57",
        ".mcap",
    ]);
    assert!(!d.join("out").exists());
}
