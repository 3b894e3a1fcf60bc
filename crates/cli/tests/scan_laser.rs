//! `semsim scan --laser real|ideal`: the realistic laser preset from the command line, the
//! configuration written beside the scans, and a bad preset refused as bad input.

mod util;

use util::Dir;

#[test]
fn scan_with_the_real_laser_writes_no_echo_readings_and_its_realism_table() {
    let d = Dir::new();
    let cfg = d.small_config();
    let b = d.write(
        "b.toml",
        include_str!("../../scanner/data/default_building.toml"),
    );
    let (b, cfg) = (b.to_str().expect("utf-8"), cfg.to_str().expect("utf-8"));
    let scan = |laser: &str, out: &str| {
        d.run(&[
            "scan",
            "--building",
            b,
            "--pose",
            "6.5,0,0",
            "--out",
            out,
            "--config",
            cfg,
            "--laser",
            laser,
        ])
    };
    scan("real", "real").ok();
    let written = std::fs::read_to_string(d.join("real/config.toml")).expect("config.toml");
    assert!(
        written.contains("[laser.realism.returns]") && written.contains("no_echo_range_m = 32.767"),
        "{written}"
    );
    let cloud = cloud::read_cloud(&d.join("real/scan000.pcd")).expect("scan");
    let no_echo = cloud
        .points
        .iter()
        .filter(|p| (p.length() - 32.767).abs() < 1e-3)
        .count();
    assert!(no_echo > 0, "no no-echo readings");
    // The ideal laser: every beam of the closed building returns, none at 32.767 m.
    scan("ideal", "ideal").ok();
    let ideal = cloud::read_cloud(&d.join("ideal/scan000.pcd")).expect("scan");
    assert!(ideal.points.iter().all(|p| p.length() < 30.0));
    // A preset that does not exist: bad input, naming the choices.
    scan("perfect", "bad").bad_input(&["perfect", "ideal", "real"]);
}
