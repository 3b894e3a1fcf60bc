//! `semsim building generate --style` and `semsim scan --survey`: the real binary in a
//! temporary folder.

mod util;
use util::Dir;

#[test]
fn a_generated_garage_is_scanned_along_surveyed_poses_with_odometry() {
    let d = Dir::new();
    let cfg = d.small_config();
    let cfg = cfg.to_str().expect("utf-8");
    d.run(&[
        "building", "generate", "--style", "garage", "--seed", "3", "--out", "g.toml",
    ])
    .ok();
    let text = std::fs::read_to_string(d.join("g.toml")).expect("written");
    assert!(
        text.contains("[[ramps]]") && text.contains("class = \"column\""),
        "not a garage"
    );
    let stdout = d
        .run(&[
            "--config",
            cfg,
            "scan",
            "--building",
            "g.toml",
            "--survey",
            "--out",
            "s",
        ])
        .ok();
    let poses = std::fs::read_to_string(d.join("s/poses.txt")).expect("poses");
    let odometry = std::fs::read_to_string(d.join("s/odometry.txt")).expect("odometry");
    let n = poses.lines().filter(|l| l.starts_with("scan")).count();
    assert!(n >= 5, "{n} surveyed poses");
    assert_eq!(
        odometry.lines().filter(|l| l.starts_with("scan")).count(),
        n
    );
    assert!(stdout.contains(&format!("survey: {n} poses")), "{stdout}");
    let scans = d
        .listing("s")
        .iter()
        .filter(|f| f.ends_with(".pcd"))
        .count();
    assert_eq!(scans, n);
}

#[test]
fn survey_and_explicit_poses_conflict_and_an_unknown_style_is_refused() {
    let d = Dir::new();
    d.run(&["building", "generate", "--seed", "1", "--out", "b.toml"])
        .ok();
    let r = d.run(&[
        "scan",
        "--building",
        "b.toml",
        "--survey",
        "--pose",
        "1,0,0",
        "--out",
        "s",
    ]);
    assert_eq!(r.code(), 2, "{}", r.stderr());
    assert!(
        r.stderr().contains("--survey") && r.stderr().contains("--pose"),
        "{}",
        r.stderr()
    );
    let r = d.run(&[
        "building", "generate", "--style", "castle", "--out", "c.toml",
    ]);
    assert_eq!(r.code(), 2);
    assert!(
        r.stderr().contains("castle") && r.stderr().contains("garage"),
        "{}",
        r.stderr()
    );
}

#[test]
fn a_survey_of_a_building_without_free_floor_is_bad_input_naming_it() {
    let d = Dir::new();
    d.write(
        "full.toml",
        "name = \"storeroom\"\n[floor]\nmin_m = [0.0, 0.0]\nmax_m = [4.0, 4.0]\n[ceiling]\n\
         height_m = 2.5\n[[boxes]]\ncenter_m = [2.0, 2.0, 1.0]\nsize_m = [4.0, 4.0, 2.0]\n",
    );
    d.run(&["scan", "--building", "full.toml", "--survey", "--out", "s"])
        .bad_input(&["full.toml", "storeroom", "no free floor"]);
}

#[test]
fn the_survey_section_of_the_config_sets_the_poses_and_is_checked() {
    let d = Dir::new();
    d.run(&["building", "generate", "--seed", "2", "--out", "b.toml"])
        .ok();
    let count = |cfg: &str, out: &str| {
        d.run(&[
            "--config",
            cfg,
            "scan",
            "--building",
            "b.toml",
            "--survey",
            "--out",
            out,
        ])
        .ok();
        std::fs::read_to_string(d.join(&format!("{out}/poses.txt")))
            .expect("poses")
            .lines()
            .filter(|l| l.starts_with("scan"))
            .count()
    };
    let near = d.write(
        "near.toml",
        "[laser]\nbeams = 61\nrotation_steps = 31\n[survey]\ncover_radius_m = 3.0\n",
    );
    let far = d.write(
        "far.toml",
        "[laser]\nbeams = 61\nrotation_steps = 31\n[survey]\ncover_radius_m = 8.0\n",
    );
    let (n_near, n_far) = (
        count(near.to_str().expect("utf-8"), "near"),
        count(far.to_str().expect("utf-8"), "far"),
    );
    // Each scan covering more floor needs fewer stops.
    assert!(
        n_far < n_near,
        "{n_far} poses covering 8 m, {n_near} covering 3 m"
    );
    // The config written beside the scans is the one used.
    let written = std::fs::read_to_string(d.join("far/config.toml")).expect("config");
    assert!(written.contains("[survey]") && written.contains("cover_radius_m = 8.0"));
    let bad = d.write("bad.toml", "[survey]\nclearance_m = -1.0\n");
    d.run(&[
        "--config",
        bad.to_str().expect("utf-8"),
        "scan",
        "--building",
        "b.toml",
        "--survey",
        "--out",
        "x",
    ])
    .bad_input(&["bad.toml", "[survey]", "clearance_m"]);
}

/// Regression: office-5's survey starts in a doorway, and its second scan, 2 m along the
/// corridor, sees rooms through doors the first does not. Those returns, paired with whatever
/// lies within ICP's wide first gate, kept the RMSE at 0.31 m, so the gate never narrowed and
/// GICP cycled between two poses 11 cm off, until `register --sequence` failed ("no stop
/// criterion met"). Now a cycle halves the gate.
#[test]
fn a_scan_that_sees_rooms_the_map_does_not_registers_without_cycling() {
    let d = Dir::new();
    // The survey's first two poses of that building (in the doorway, then along the corridor).
    let scans = d.registered_office(
        5,
        &["--pose=3.3,-1.14248026,14", "--pose=5.3,-0.64248026,14"],
    );
    let error_m = scans[1]["error_m"]
        .as_f64()
        .expect("scan 1's error against the truth");
    let error_deg = scans[1]["error_deg"].as_f64().expect("and in degrees");
    assert!(
        error_m < 0.02 && error_deg < 0.2,
        "{error_m} m {error_deg} deg"
    );
}

/// Regression: in the generated office of seed 17, scanned along its survey with the realistic
/// laser, the first scan inside a room off the corridor (scan 22, 8.5 m of simulated odometry
/// from the last) started 16 cm and 1.5 degrees from the truth and ended 18 cm and 3.5 degrees
/// off with an RMSE of 0.32 m: the room's surfaces, new to the map, paired with whatever lay
/// within the 1 m gate and held the pose where they balanced, and the gate (three times the
/// RMSE) never closed. A settled RMSE above the final gate now halves the gate.
#[test]
fn a_room_first_seen_through_its_door_is_not_turned_by_a_gate_that_never_closed() {
    let scans = Dir::new().registered_office(17, &["--survey"]);
    assert!(scans.len() > 22, "{} scans", scans.len());
    for s in &scans {
        let (m, deg) = (s["error_m"].as_f64(), s["error_deg"].as_f64());
        let (m, deg) = (m.expect("error_m"), deg.expect("error_deg"));
        assert!(m < 0.05 && deg < 0.5, "{}: {m} m, {deg} deg", s["scan"]);
    }
}
