//! End-to-end tests of `semsim scan` and `semsim building`: generated buildings, their scans
//! and the checks on poses, doors and configurations.

mod util;

use scanner::{Building, BuildingGeometry};
use util::Dir;

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
