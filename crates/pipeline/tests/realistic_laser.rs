//! The realistic virtual laser through the pipeline: a scan folder written with the `real`
//! preset holds no-echo readings at the sensor's no-echo range (as real SICK scans do), the
//! pipeline's reader drops exactly those and keeps every return, and the recorded ground truth
//! is the tilted sensor's pose (every labelled return lands on its building surface).

use pipeline::{read_scans_with, write_scan_folder, Config, ScanSource};
use scanner::{Building, BuildingGeometry, ScanPose};

#[test]
fn no_echo_readings_of_the_real_laser_are_dropped_by_the_scan_reader() {
    let dir = tempfile::tempdir().expect("temp dir");
    let building = Building::default_building().expect("default");
    let mut cfg = Config::default();
    cfg.laser.realism = scanner::Realism::real();
    let no_echo = cfg
        .laser
        .realism
        .no_echo_range_m
        .expect("the preset writes no-echo") as f32;
    let pose = ScanPose {
        x_m: 6.5,
        y_m: 0.0,
        yaw_deg: 0.0,
    };
    write_scan_folder(&building, &[pose], &cfg, dir.path(), &mut |_, _| {}).expect("written");
    let file = dir.path().join("scan000.pcd");
    let written = cloud::read_cloud(&file).expect("reads back");
    let at_no_echo = written
        .points
        .iter()
        .filter(|p| (p.length() - no_echo).abs() < 1e-3)
        .count();
    let returns = written
        .points
        .iter()
        .filter(|p| p.is_finite() && p.length() <= cfg.laser.max_range_m as f32)
        .count();
    // Every beam is a return or a no-echo reading (the default building is closed), and the
    // no-echo readings are enough for the reader to recognise them (see `no_echo.rs`).
    assert_eq!(at_no_echo + returns, written.len());
    assert!(
        at_no_echo >= pipeline::NO_ECHO_MIN_POINTS
            && at_no_echo as f64 >= pipeline::NO_ECHO_MIN_SHARE * written.len() as f64,
        "{at_no_echo} no-echo readings of {}",
        written.len()
    );
    // (Outlier and mixed-pixel removal off: this is about the no-echo readings;
    // `tests/outliers.rs` and `tests/mixed_pixels.rs` measure what they take from the
    // realistic laser.)
    let no_outliers = pipeline::OutlierConfig {
        enabled: false,
        ..Default::default()
    };
    let no_mixed = pipeline::MixedPixelConfig {
        enabled: false,
        ..Default::default()
    };
    let read =
        read_scans_with(&[ScanSource::file(&file)], None, &no_outliers, &no_mixed).expect("read");
    assert_eq!(read.len(), 1);
    assert_eq!(read[0].len(), returns, "the reader keeps every return");
    assert!(read[0].points.iter().all(|p| p.length() < no_echo - 1.0));

    // The truth pose places the tilted scan's labelled returns on their surfaces.
    let truth = cloud::read_poses(&dir.path().join("poses.txt")).expect("truth");
    let mut placed = written.clone();
    placed.transform(&truth[0].world_from_scan);
    let geometry = BuildingGeometry::new(&building);
    let labels = placed.labels.as_ref().expect("labelled");
    let mut worst = 0.0f32;
    for (p, l) in placed.points.iter().zip(labels) {
        if l.entity != 0 && p.is_finite() {
            worst = worst.max(geometry.distance_to_entity(*p, l.entity));
        }
    }
    // Range noise: 1 cm at short range, 1 mm more per metre, more at grazing incidence;
    // 20 cm is beyond any credible 30 m return (a 0.3 degree tilt left out would put 30 m
    // returns 16 cm off, and a wrong pose far more).
    assert!(worst < 0.2, "a labelled return {worst} m off its surface");
}
