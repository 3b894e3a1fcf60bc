//! Sequences without odometry: the initial alignment (`SequenceConfig::initial_alignment`)
//! finds each scan's yaw and position against the map, on virtual scans of the default
//! building with known truth and on PCL's room pair.

mod common;

use cloud::{pose_error, read_cloud, PointCloud};
use common::{real_data, scan_pair_at};
use glam::{DAffine3, DQuat, DVec3};
use registration::*;
use scanner::{Building, BuildingGeometry, LaserConfig, ScanPose, VirtualLaser};

/// The test laser of the fixtures: 271 beams x 151 rotation steps (1 cm range noise).
const BEAMS: usize = 271;
const STEPS: usize = 151;

/// Scan 0 in room A of the default building (x 0..6 m, y 1.3..6.3 m, a table at (3, 4.5)).
const ROOM_TARGET: ScanPose = ScanPose {
    x_m: 2.0,
    y_m: 2.5,
    yaw_deg: 0.0,
};

/// Registers `[target, source]` as a sequence without odometry; returns the registered
/// `target_from_source` and the sequence's result.
fn register_pair(
    target: &PointCloud,
    source: &PointCloud,
    config: &SequenceConfig,
) -> Result<(DAffine3, SequenceResult)> {
    let r = register_sequence(
        &[target.clone(), source.clone()],
        &[],
        config,
        &mut |_, _| {},
    )?;
    Ok((r.world_from_scan[0].inverse() * r.world_from_scan[1], r))
}

#[test]
fn a_room_scan_turned_40_90_and_170_degrees_and_moved_registers_without_odometry() {
    // Moved 1.2 to 2 m across the room and turned far beyond ICP's basin.
    for (x_m, y_m, yaw_deg) in [(3.6, 2.9, 40.0), (3.9, 3.2, 90.0), (3.0, 3.4, 170.0)] {
        let source_pose = ScanPose { x_m, y_m, yaw_deg };
        let (target, source, truth) = scan_pair_at(BEAMS, STEPS, ROOM_TARGET, source_pose);
        let (found, r) =
            register_pair(&target, &source, &SequenceConfig::default()).expect("registers");
        let (et, er) = pose_error(&found, &truth);
        let report = r.initial[1].as_ref().expect("the search ran: no odometry");
        eprintln!(
            "room, {yaw_deg} deg: {et:.4} m {er:.3} deg from the truth; search {:.0} ms \
             ({} yaws), verification {:.0} ms ({} hypotheses), score {:.3}, fitness {:.2}",
            report.search_ms,
            report.yaw_steps,
            report.verify_ms,
            report.verified,
            report.score,
            report.fitness
        );
        assert!(et < 0.02 && er < 0.2, "{yaw_deg} deg: {et} m {er} deg");
        assert!(!report.guess_won, "the previous pose is {yaw_deg} deg off");
    }
}

#[test]
fn without_the_initial_alignment_a_turned_scan_lands_wrong() {
    // What the search fixes: from the previous pose, a scan turned 90 degrees does not
    // register to the truth (it fails, or converges somewhere else).
    let source_pose = ScanPose {
        x_m: 3.9,
        y_m: 3.2,
        yaw_deg: 90.0,
    };
    let (target, source, truth) = scan_pair_at(BEAMS, STEPS, ROOM_TARGET, source_pose);
    let off = SequenceConfig {
        initial_alignment: InitialAlignment::Off,
        ..SequenceConfig::default()
    };
    match register_pair(&target, &source, &off) {
        Ok((found, r)) => {
            let (et, er) = pose_error(&found, &truth);
            assert!(et > 0.1 || er > 1.0, "{et} m {er} deg");
            assert!(r.initial.iter().all(Option::is_none));
        }
        Err(e) => assert!(matches!(e, RegistrationError::NotConverged { .. }), "{e}"),
    }
}

#[test]
fn with_odometry_the_search_runs_only_where_asked() {
    let source_pose = ScanPose {
        x_m: 3.6,
        y_m: 2.9,
        yaw_deg: 40.0,
    };
    let (target, source, truth) = scan_pair_at(BEAMS, STEPS, ROOM_TARGET, source_pose);
    let scans = [target, source];
    // Odometry 5 cm and 1 degree off the truth.
    let odometry = [
        DAffine3::IDENTITY,
        DAffine3::from_translation(DVec3::new(0.05, 0.0, 0.0))
            * DAffine3::from_rotation_z(1f64.to_radians())
            * truth,
    ];
    let with = |initial_alignment| {
        let config = SequenceConfig {
            initial_alignment,
            ..SequenceConfig::default()
        };
        register_sequence(&scans, &odometry, &config, &mut |_, _| {}).expect("registers")
    };
    let auto = with(InitialAlignment::Auto);
    let off = with(InitialAlignment::Off);
    assert!(auto.initial.iter().all(Option::is_none), "auto: odometry");
    assert_eq!(
        auto.world_from_scan, off.world_from_scan,
        "the same registration"
    );
    let always = with(InitialAlignment::Always);
    let report = always.initial[1].as_ref().expect("always searches");
    assert!(report.verified > 1, "the guess and the search's hypotheses");
    let (et, er) = pose_error(&always.world_from_scan[1], &truth);
    assert!(et < 0.02 && er < 0.2, "always: {et} m {er} deg");
}

/// The demo's 9-scan survey of the default building (down the corridor, a 45 and an 80
/// degree turn into the stair room) scanned by `laser`, registered without odometry; returns
/// each scan's pose error against the truth (relative to scan 0).
fn survey_errors_without_odometry(laser: LaserConfig) -> Vec<(f64, f64)> {
    let building = Building::default_building().expect("default building");
    let geometry = BuildingGeometry::new(&building);
    let laser = VirtualLaser::new(laser).expect("laser");
    let poses = Building::default_survey_poses();
    let scans: Vec<PointCloud> = poses
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let mut scan = laser.scan(&geometry, p, k as u64).without_invalid();
            // A real laser's "no echo" readings (at its no-echo range) are no returns: the
            // pipeline drops them before registering (`pipeline/src/no_echo.rs`).
            if let Some(no_echo) = laser.config().realism.no_echo_range_m {
                let keep: Vec<usize> = (0..scan.len())
                    .filter(|&i| scan.points[i].length() < no_echo as f32 * 0.99)
                    .collect();
                scan = scan.select(&keep);
            }
            scan
        })
        .collect();
    let truth: Vec<DAffine3> = poses.iter().map(|p| laser.world_from_sensor(p)).collect();
    let r = register_sequence(&scans, &[], &SequenceConfig::default(), &mut |_, _| {})
        .expect("registers");
    (1..scans.len())
        .map(|k| {
            let ours = r.world_from_scan[0].inverse() * r.world_from_scan[k];
            let (et, er) = pose_error(&ours, &(truth[0].inverse() * truth[k]));
            let report = r.initial[k].as_ref().expect("searched: no odometry");
            eprintln!(
                "survey scan {k}: {et:.4} m {er:.3} deg from the truth; search {:.0} ms, \
                 verification {:.0} ms, guess won: {}",
                report.search_ms, report.verify_ms, report.guess_won
            );
            (et, er)
        })
        .collect()
}

#[test]
fn with_auto_a_scan_whose_odometry_fails_is_aligned_again() {
    let source_pose = ScanPose {
        x_m: 3.9,
        y_m: 3.2,
        yaw_deg: 90.0,
    };
    let (target, source, truth) = scan_pair_at(BEAMS, STEPS, ROOM_TARGET, source_pose);
    let scans = [target, source];
    // Odometry that lost track: the second scan 40 m away, where nothing overlaps.
    let odometry = [
        DAffine3::IDENTITY,
        DAffine3::from_translation(DVec3::new(40.0, 0.0, 0.0)) * truth,
    ];
    let with = |initial_alignment| {
        let config = SequenceConfig {
            initial_alignment,
            ..SequenceConfig::default()
        };
        register_sequence(&scans, &odometry, &config, &mut |_, _| {})
    };
    let off = with(InitialAlignment::Off);
    assert!(
        matches!(off, Err(RegistrationError::NoOverlap { .. })),
        "{off:?}"
    );
    let auto = with(InitialAlignment::Auto).expect("aligned again");
    assert!(
        auto.initial[1].is_some(),
        "the search ran after the failure"
    );
    let (et, er) = pose_error(&auto.world_from_scan[1], &truth);
    assert!(et < 0.02 && er < 0.2, "{et} m {er} deg");
}

#[test]
fn the_demo_survey_registers_without_odometry() {
    let laser = LaserConfig {
        beams: BEAMS,
        rotation_steps: STEPS,
        ..LaserConfig::default()
    };
    for (k, (et, er)) in survey_errors_without_odometry(laser)
        .into_iter()
        .enumerate()
    {
        assert!(et < 0.03 && er < 0.3, "scan {}: {et} m {er} deg", k + 1);
    }
}

#[test]
fn the_demo_survey_registers_without_odometry_with_a_realistic_laser() {
    // People walking by, glass, lost returns, mixed pixels and a tilted mount: what the
    // free-space evidence must survive.
    let laser = LaserConfig {
        beams: BEAMS,
        rotation_steps: STEPS,
        realism: scanner::Realism::real(),
        ..LaserConfig::default()
    };
    for (k, (et, er)) in survey_errors_without_odometry(laser)
        .into_iter()
        .enumerate()
    {
        assert!(et < 0.03 && er < 0.3, "scan {}: {et} m {er} deg", k + 1);
    }
}

#[test]
fn pcl_room_pair_registers_without_a_guess_where_the_ndt_tutorial_guess_leads() {
    let Some(dir) = real_data("pcl_room_pair_without_a_guess") else {
        return;
    };
    let dir = dir.join("pcl-room");
    let scan1 = read_cloud(&dir.join("room_scan1.pcd")).expect("scan1");
    let scan2 = read_cloud(&dir.join("room_scan2.pcd")).expect("scan2");
    // The reference: scan2 -> scan1 from PCL's NDT tutorial guess (as `real_data.rs` does).
    #[allow(clippy::approx_constant)]
    let guess = DAffine3::from_rotation_translation(
        DQuat::from_rotation_z(0.6931),
        DVec3::new(1.79387, 0.720047, 0.0),
    );
    let reference = register(&scan2, &scan1, guess, &IcpConfig::default())
        .expect("registers from the tutorial's guess")
        .target_from_source;
    // The sequence registers scan 1 (room_scan2) into scan 0's (room_scan1) frame.
    let (found, r) = register_pair(&scan1, &scan2, &SequenceConfig::default()).expect("registers");
    let (et, er) = pose_error(&found, &reference);
    let report = r.initial[1].as_ref().expect("searched");
    eprintln!(
        "pcl room without a guess: {et:.4} m {er:.3} deg from the registration from the \
         tutorial's guess; search {:.0} ms ({} yaws), verification {:.0} ms, score {:.3}",
        report.search_ms, report.yaw_steps, report.verify_ms, report.score
    );
    assert!(et < 0.05 && er < 1.0, "{et} m {er} deg");
}

#[test]
fn initial_alignment_settings_parse_and_are_checked() {
    let c: SequenceConfig =
        toml::from_str("initial_alignment = \"always\"\ninitial_cell_m = 0.3").expect("parses");
    assert_eq!(c.initial_alignment, InitialAlignment::Always);
    assert_eq!(c.initial_cell_m, 0.3);
    assert_eq!(
        SequenceConfig::default().initial_alignment,
        InitialAlignment::Auto
    );
    assert!(toml::from_str::<SequenceConfig>("initial_alignment = \"sometimes\"").is_err());
    assert!(toml::from_str::<SequenceConfig>("initial_cell = 0.3").is_err());
    let back: SequenceConfig =
        toml::from_str(&toml::to_string(&c).expect("writes")).expect("reads back");
    assert_eq!(back, c);
    let scans = [
        PointCloud::from_points(vec![glam::Vec3::X; 10]),
        PointCloud::from_points(vec![glam::Vec3::Y; 10]),
    ];
    for bad in [0.0, 0.01, f64::NAN, 50.0] {
        let config = SequenceConfig {
            initial_cell_m: bad,
            ..SequenceConfig::default()
        };
        match register_sequence(&scans, &[], &config, &mut |_, _| {}) {
            Err(RegistrationError::InvalidParameter(p)) => assert_eq!(p.name, "initial_cell_m"),
            other => panic!("{bad}: {other:?}"),
        }
    }
}

/// A measurement, not a check (run with `--release -- --ignored --nocapture`): generated
/// buildings surveyed in their walking order, every scan turned by a further 73 degrees, no
/// odometry; prints each seed's worst pose error and the scans that went wrong.
#[test]
#[ignore]
fn measure_generated_surveys_without_odometry() {
    for seed in 1u64..=6 {
        let b = scanner::generate_building(seed, &scanner::GeneratorConfig::default())
            .expect("valid building");
        let g = BuildingGeometry::new(&b);
        let mut poses =
            scanner::survey_poses(&b, &scanner::SurveyConfig::default()).expect("survey");
        for (k, p) in poses.iter_mut().enumerate() {
            p.yaw_deg = (k as f64 * 73.0) % 360.0;
        }
        let laser = VirtualLaser::new(LaserConfig {
            beams: BEAMS,
            rotation_steps: STEPS,
            ..LaserConfig::default()
        })
        .expect("laser");
        let scans: Vec<PointCloud> = poses
            .iter()
            .enumerate()
            .map(|(k, p)| laser.scan(&g, p, k as u64))
            .collect();
        let truth: Vec<DAffine3> = poses.iter().map(|p| laser.world_from_sensor(p)).collect();
        let start = std::time::Instant::now();
        let r = register_sequence(&scans, &[], &SequenceConfig::default(), &mut |_, _| {})
            .expect("registers");
        let mut worst = (0.0f64, 0.0f64);
        for k in 1..scans.len() {
            let ours = r.world_from_scan[0].inverse() * r.world_from_scan[k];
            let (et, er) = pose_error(&ours, &(truth[0].inverse() * truth[k]));
            worst = (worst.0.max(et), worst.1.max(er));
            if et > 0.05 || er > 0.5 {
                let step = (truth[k].translation - truth[k - 1].translation).length();
                eprintln!("  seed {seed} scan {k}: {et:.3} m {er:.2} deg off; {step:.2} m from the scan before");
            }
        }
        eprintln!(
            "seed {seed}: {} scans, worst {:.4} m {:.3} deg, {:.1} s",
            scans.len(),
            worst.0,
            worst.1,
            start.elapsed().as_secs_f64()
        );
    }
}

/// A measurement, not a check (run with `--release -- --ignored --nocapture`): the initial
/// alignment's cost per scan on PCL's room pair and on a pair of full-resolution (541 x 301,
/// 162,841-point) virtual scans of the default building's room A, three runs each.
#[test]
#[ignore]
fn measure_initial_alignment_cost() {
    let mut pairs: Vec<(&str, PointCloud, PointCloud)> = Vec::new();
    if let Some(dir) = real_data("measure_initial_alignment_cost") {
        let dir = dir.join("pcl-room");
        let scan1 = read_cloud(&dir.join("room_scan1.pcd")).expect("scan1");
        let scan2 = read_cloud(&dir.join("room_scan2.pcd")).expect("scan2");
        pairs.push(("pcl room", scan1, scan2));
    }
    let source_pose = ScanPose {
        x_m: 3.9,
        y_m: 3.2,
        yaw_deg: 90.0,
    };
    let (target, source, _) = scan_pair_at(541, 301, ROOM_TARGET, source_pose);
    pairs.push(("541 x 301 virtual scans", target, source));
    for (name, target, source) in &pairs {
        for run in 0..3 {
            let start = std::time::Instant::now();
            let (_, r) =
                register_pair(target, source, &SequenceConfig::default()).expect("registers");
            let report = r.initial[1].as_ref().expect("searched");
            let icp = r.results[1].as_ref().expect("registered");
            eprintln!(
                "{name} ({} + {} points), run {run}: search {:.0} ms ({} yaws), verification \
                 {:.0} ms ({} hypotheses), fine ICP {:.0} ms, sequence {:.0} ms",
                target.len(),
                source.len(),
                report.search_ms,
                report.yaw_steps,
                report.verify_ms,
                report.verified,
                icp.total_ms,
                start.elapsed().as_secs_f64() * 1e3
            );
        }
    }
}
