//! Write-then-read round trips of synthetic clouds through every format and encoding.

use cloud::io::{pcd, ply, threedtk, xyz};
use cloud::{
    read_cloud, write_cloud, CloudFormat, EntityClass, Label, Organized, PcdEncoding, PlyEncoding,
    PointCloud,
};
use glam::{Quat, Vec3};
use std::path::Path;

const PCD_ENCODINGS: [PcdEncoding; 3] = [
    PcdEncoding::Ascii,
    PcdEncoding::Binary,
    PcdEncoding::BinaryCompressed,
];
const PLY_ENCODINGS: [PlyEncoding; 3] = [
    PlyEncoding::Ascii,
    PlyEncoding::BinaryLittleEndian,
    PlyEncoding::BinaryBigEndian,
];

/// An organised 4 x 6 cloud with awkward values, three missing returns (NaN), intensity,
/// labels of every class and a sensor pose.
fn sample() -> PointCloud {
    let (rows, cols) = (4, 6);
    let points = (0..rows * cols)
        .map(|i| {
            if [3, 10, 17].contains(&i) {
                return Vec3::NAN;
            }
            let f = i as f32;
            Vec3::new(
                f / 3.0,
                if i == 0 { -0.0 } else { 1e-7 * f },
                12345.678 - f * 0.1,
            )
        })
        .collect();
    let labels = (0..rows * cols)
        .map(|i| Label {
            entity: if i == 5 { u32::MAX } else { i as u32 * 7 },
            class: EntityClass::ALL[i % EntityClass::ALL.len()],
        })
        .collect();
    PointCloud {
        points,
        intensity: Some((0..rows * cols).map(|i| i as f32 * 0.37 - 2.0).collect()),
        labels: Some(labels),
        classification: None,
        organized: Some(Organized { rows, cols }),
        sensor_origin: Vec3::new(1.0, 2.0, 0.5),
        sensor_orientation: Quat::from_rotation_z(0.3),
    }
}

/// Asserts two clouds are identical, bit for bit (so NaN equals NaN).
fn assert_identical(a: &PointCloud, b: &PointCloud, what: &str) {
    let bits = |v: &[Vec3]| -> Vec<[u32; 3]> {
        v.iter().map(|p| p.to_array().map(f32::to_bits)).collect()
    };
    assert_eq!(bits(&a.points), bits(&b.points), "{what}: points");
    let ibits = |v: &Option<Vec<f32>>| {
        v.as_ref()
            .map(|v| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>())
    };
    assert_eq!(
        ibits(&a.intensity),
        ibits(&b.intensity),
        "{what}: intensity"
    );
    assert_eq!(a.labels, b.labels, "{what}: labels");
    assert_eq!(a.organized, b.organized, "{what}: shape");
    assert_eq!(a.sensor_origin, b.sensor_origin, "{what}: sensor origin");
    assert_eq!(
        a.sensor_orientation, b.sensor_orientation,
        "{what}: sensor orientation"
    );
}

fn only_file(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .expect("readable")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect()
}

#[test]
fn pcd_round_trips_exactly_in_every_encoding() {
    let dir = tempfile::tempdir().expect("tempdir");
    let organised = sample();
    let unorganised = organised.without_invalid();
    assert_eq!(unorganised.len(), 21);
    for cloud in [&organised, &unorganised] {
        for enc in PCD_ENCODINGS {
            let path = dir.path().join("c.pcd");
            pcd::write_pcd(&path, cloud, enc).expect("write");
            let back = pcd::read_pcd(&path).expect("read");
            assert_identical(cloud, &back, &format!("{enc:?}"));
        }
    }
    assert_eq!(only_file(dir.path()), ["c.pcd"], "no temporary file left");
}

#[test]
fn pcd_without_optional_channels_round_trips() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("plain.pcd");
    let empty = PointCloud::from_points(Vec::new());
    let plain = PointCloud::from_points(vec![Vec3::new(1.0, 2.0, 3.0); 1000]);
    for cloud in [&empty, &plain] {
        for enc in PCD_ENCODINGS {
            pcd::write_pcd(&path, cloud, enc).expect("write");
            assert_identical(
                cloud,
                &pcd::read_pcd(&path).expect("read"),
                &format!("{enc:?}"),
            );
        }
    }
    // 1000 equal points compress well.
    pcd::write_pcd(&path, &plain, PcdEncoding::BinaryCompressed).expect("write");
    assert!(std::fs::metadata(&path).expect("exists").len() < 1000);
}

#[test]
fn ply_round_trips_exactly_in_every_encoding() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("c.ply");
    let organised = sample();
    let mut expected = organised.without_invalid();
    expected.sensor_origin = Vec3::ZERO;
    expected.sensor_orientation = Quat::IDENTITY;
    for enc in PLY_ENCODINGS {
        ply::write_ply(&path, &organised, enc).expect("write");
        assert_identical(
            &expected,
            &ply::read_ply(&path).expect("read"),
            &format!("{enc:?}"),
        );
        ply::write_ply(&path, &expected, enc).expect("write");
        assert_identical(
            &expected,
            &ply::read_ply(&path).expect("read"),
            &format!("{enc:?}"),
        );
    }
}

#[test]
fn xyz_round_trips_exactly_without_labels_and_missing_returns() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("c.xyz");
    let mut expected = sample().without_invalid();
    expected.labels = None;
    expected.sensor_origin = Vec3::ZERO;
    expected.sensor_orientation = Quat::IDENTITY;
    xyz::write_xyz(&path, &sample()).expect("write");
    assert_identical(&expected, &xyz::read_xyz(&path).expect("read"), "xyz");
    expected.intensity = None;
    xyz::write_xyz(&path, &expected).expect("write");
    assert_identical(
        &expected,
        &xyz::read_xyz(&path).expect("read"),
        "xyz, no intensity",
    );
}

#[test]
fn threedtk_round_trips_within_print_precision() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("scan000.3d");
    let mut full = sample();
    full.points
        .iter_mut()
        .filter(|p| p.is_nan())
        .for_each(|p| *p = Vec3::new(-1.5, 2.25, 0.125));
    full.labels = None;
    full.sensor_origin = Vec3::ZERO;
    full.sensor_orientation = Quat::IDENTITY;
    let mut holes = sample();
    holes.labels = None;
    let holes_expected = PointCloud {
        sensor_origin: Vec3::ZERO,
        sensor_orientation: Quat::IDENTITY,
        ..holes.without_invalid()
    };
    for (cloud, expected) in [(&full, &full), (&holes, &holes_expected)] {
        threedtk::write_3d(&path, cloud).expect("write");
        let back = threedtk::read_3d(&path).expect("read");
        assert_eq!(back.organized, expected.organized);
        assert_eq!(
            back.intensity, expected.intensity,
            "the intensity column is exact"
        );
        assert_eq!(back.len(), expected.len());
        for (a, b) in back.points.iter().zip(&expected.points) {
            assert!(
                (*a - *b).abs().max_element() <= 1e-6 + 1.2e-7 * b.abs().max_element(),
                "{a} vs {b}"
            );
        }
    }
    // The full organised cloud is written with its `W x H` line; 3DTK axes are y up, z forward.
    let text = std::fs::read_to_string(&path).expect("exists");
    assert!(
        !text.starts_with("6 x 4"),
        "a cloud with holes has no shape line"
    );
    threedtk::write_3d(
        &path,
        &PointCloud::from_points(vec![Vec3::new(1.0, 2.0, 3.0)]),
    )
    .expect("write");
    assert_eq!(
        std::fs::read_to_string(&path).expect("exists").trim(),
        "-200.0000 300.0000 100.0000"
    );
    threedtk::write_3d(&path, &full).expect("write");
    assert!(std::fs::read_to_string(&path)
        .expect("exists")
        .starts_with("6 x 4\n"));
}

#[test]
fn extension_picks_the_format() {
    let dir = tempfile::tempdir().expect("tempdir");
    let cloud = sample().without_invalid();
    for name in ["a.pcd", "a.PLY", "a.xyz", "a.txt", "a.3d"] {
        let path = dir.path().join(name);
        write_cloud(&path, &cloud).expect("write");
        let back = read_cloud(&path).expect("read");
        assert_eq!(back.len(), cloud.len(), "{name}");
    }
    let path = dir.path().join("a.pcd");
    let text = std::fs::read(&path).expect("exists");
    assert!(String::from_utf8_lossy(&text).contains("DATA binary\n"));
    assert_eq!(
        CloudFormat::from_path(Path::new("x.ply")).expect("known"),
        CloudFormat::Ply(PlyEncoding::BinaryLittleEndian)
    );
}

/// Not a test of correctness: prints how long PCD of 162,841 points takes (best of 5, so
/// that other work on the machine matters less). Run with
/// `cargo test --release -p cloud --test round_trip -- --ignored --nocapture`.
#[test]
#[ignore]
fn time_pcd_162k() {
    let n = 162_841;
    let points: Vec<Vec3> = (0..n)
        .map(|i| Vec3::new(i as f32 * 0.001, (i % 977) as f32 * 0.01, (i % 13) as f32))
        .collect();
    let mut full = PointCloud::from_points(points.clone());
    full.intensity = Some((0..n).map(|i| (i % 255) as f32).collect());
    full.labels = Some(
        (0..n)
            .map(|i| Label {
                entity: i as u32 % 40,
                class: EntityClass::Wall,
            })
            .collect(),
    );
    let xyz_only = PointCloud::from_points(points);
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("t.pcd");
    let best = |f: &mut dyn FnMut()| {
        (0..5)
            .map(|_| {
                let t = std::time::Instant::now();
                f();
                t.elapsed()
            })
            .min()
            .unwrap_or_default()
    };
    for (what, cloud) in [("x y z", &xyz_only), ("x y z intensity label class", &full)] {
        for enc in PCD_ENCODINGS {
            let w = best(&mut || pcd::write_pcd(&path, cloud, enc).expect("write"));
            let r = best(&mut || assert_eq!(pcd::read_pcd(&path).expect("read").len(), n));
            let size = std::fs::metadata(&path).expect("exists").len();
            println!("{what}, {enc:?}: write {w:?} (incl. fsync), read {r:?}, {size} bytes");
        }
    }
}
