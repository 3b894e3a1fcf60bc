//! The E57 and LAS/LAZ readers and writers against other implementations: files written by
//! libE57Format (pye57) and laspy (+ lazrs) are read by semsim and compared point for point
//! with what those libraries read back (`tools/oracles/make_*.py`); files semsim writes
//! are read back by pye57 and laspy (`tools/oracles/read_reference.py`); and real public
//! samples (`tests/data/real/`) are read by both.
//!
//! Tolerances: semsim keeps positions as f32 metres, so a position can differ from the f64
//! reference by the f32 rounding at its magnitude (`f32_rounding`): under 1e-6 m for the
//! test files' ±16 m (the georeferenced LAS files are read relative to a local origin for
//! exactly this reason), more where a file spans more (a 300 m LAS box: 1.5e-5 m; the real
//! simple.las spans 4.6 km: 1.2e-4 m), as each test states.

mod scans_support;

use glam::{DVec3, Vec3};
use interop::{read_cloud, read_scans, write_cloud, ReadOptions};
use scans_support::*;
use serde_json::Value;
use std::path::Path;

#[test]
fn e57_scans_match_pye57() {
    let dir = tempfile::tempdir().unwrap();
    if !run_oracle("make_e57.py", &[dir.path()]) {
        return;
    }
    let path = dir.path().join("scans.e57");
    let reference = read_json(&dir.path().join("scans.json"));
    let set = read_scans(&path, &ReadOptions::default()).unwrap();
    let refs = reference["scans"].as_array().unwrap();
    assert_eq!(set.scans.len(), refs.len());
    assert_eq!(set.local_origin_m, DVec3::ZERO);
    // Every coordinate of the test file lies within 32 m: f32 rounding stays under 1e-6 m.
    let tol = 1e-6;
    let mut merged_count = 0;
    for (scan, r) in set.scans.iter().zip(refs) {
        assert_eq!(scan.name, r["name"].as_str().unwrap());
        let pose = pose_from(&r["rotation_wxyz"], &r["translation"]);
        assert_pose_eq(&scan.world_from_scan.unwrap(), &pose, &scan.name);
        let (x, y, z) = (opt_f64s(&r["x"]), opt_f64s(&r["y"]), opt_f64s(&r["z"]));
        let valid: Vec<bool> = r["valid"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_bool().unwrap())
            .collect();
        let intensity = r["intensity"].as_array().map(|_| f64s(&r["intensity"]));
        let cloud = &scan.cloud;
        cloud.validate().unwrap();
        assert_eq!(
            cloud.intensity.is_some(),
            intensity.is_some(),
            "{}",
            scan.name
        );
        if r["row"].is_null() {
            // Unorganised: the valid points, in file order.
            assert!(cloud.organized.is_none());
            let kept: Vec<usize> = (0..valid.len()).filter(|&i| valid[i]).collect();
            assert_eq!(cloud.len(), kept.len(), "{}", scan.name);
            for (k, &i) in kept.iter().enumerate() {
                close(
                    cloud.points[k],
                    x[i].unwrap(),
                    y[i].unwrap(),
                    z[i].unwrap(),
                    tol,
                    &scan.name,
                );
                if let (Some(got), Some(want)) = (&cloud.intensity, &intensity) {
                    assert_eq!(f64::from(got[k]), want[i], "{} intensity {k}", scan.name);
                }
            }
            merged_count += kept.len();
        } else {
            // Organised: every stored point at its (row, column), the rest missing returns.
            let (rows, cols) = (i64s(&r["row"]), i64s(&r["col"]));
            let shape = cloud.organized.expect("organised");
            assert_eq!((shape.rows, shape.cols), (6, 9));
            let mut seen = vec![false; shape.rows * shape.cols];
            for i in 0..rows.len() {
                let cell = rows[i] as usize * shape.cols + cols[i] as usize;
                seen[cell] = true;
                if valid[i] {
                    close(
                        cloud.points[cell],
                        x[i].unwrap(),
                        y[i].unwrap(),
                        z[i].unwrap(),
                        tol,
                        &scan.name,
                    );
                    merged_count += 1;
                } else {
                    assert!(
                        cloud.points[cell].is_nan(),
                        "cell {cell} is a missing return"
                    );
                }
                assert_eq!(
                    f64::from(cloud.intensity.as_ref().unwrap()[cell]),
                    intensity.as_ref().unwrap()[i]
                );
            }
            for (cell, s) in seen.iter().enumerate() {
                assert!(
                    *s || cloud.points[cell].is_nan(),
                    "cell {cell} not in the file is missing"
                );
            }
            assert_eq!(seen.iter().filter(|s| !**s).count(), 2);
        }
    }
    // The spherical scan: 3 direction-only and 5 invalid points of 120 are skipped.
    assert_eq!(set.scans[2].cloud.len(), 112);
    assert!(
        set.notes
            .iter()
            .any(|n| n.contains("8 points without valid coordinates skipped")),
        "{:?}",
        set.notes
    );

    // read_cloud: the scans placed by their poses and merged.
    let (merged, notes) = read_cloud(&path, &ReadOptions::default()).unwrap();
    assert_eq!(merged.len(), merged_count);
    assert!(merged.organized.is_none() && merged.intensity.is_none());
    assert!(
        notes.iter().any(|n| n.contains("intensity dropped")),
        "{notes:?}"
    );
    let pose_a = set.scans[0].world_from_scan.unwrap();
    for (k, p) in set.scans[0].cloud.points.iter().enumerate().step_by(37) {
        let want = pose_a.transform_point3(p.as_dvec3());
        close(
            merged.points[k],
            want.x,
            want.y,
            want.z,
            1e-5,
            "merged scan-a",
        );
    }
}

#[test]
fn e57_written_by_semsim_reads_in_pye57() {
    let dir = tempfile::tempdir().unwrap();
    let mut cloud = cloud::PointCloud::from_points(
        (0..20)
            .map(|i| {
                Vec3::new(
                    i as f32 * 0.37 - 3.0,
                    (i * i) as f32 * 0.01,
                    1.0 / (i + 1) as f32,
                )
            })
            .collect(),
    );
    for i in [3, 11, 17] {
        cloud.points[i] = Vec3::NAN;
    }
    cloud.intensity = Some((0..20).map(|i| i as f32 * 1.5).collect());
    cloud.organized = Some(cloud::Organized { rows: 4, cols: 5 });
    let path = dir.path().join("organised.e57");
    write_cloud(&path, &cloud).unwrap();
    let Some(reference) = reference(&path) else {
        return;
    };
    let scan = &reference["scans"][0];
    assert_eq!(scan["name"], "organised");
    let (x, y, z) = (
        opt_f64s(&scan["x"]),
        opt_f64s(&scan["y"]),
        opt_f64s(&scan["z"]),
    );
    let (rows, cols) = (i64s(&scan["row"]), i64s(&scan["col"]));
    let intensity = f64s(&scan["intensity"]);
    assert_eq!(x.len(), 20);
    for i in 0..20 {
        assert_eq!((rows[i], cols[i]), (i as i64 / 5, i as i64 % 5));
        let valid = scan["valid"][i].as_bool().unwrap();
        assert_eq!(valid, cloud.points[i].is_finite(), "point {i}");
        if valid {
            // Written as f64 of the f32: exact.
            let p = cloud.points[i].as_dvec3();
            assert_eq!(
                (x[i].unwrap(), y[i].unwrap(), z[i].unwrap()),
                (p.x, p.y, p.z)
            );
        }
        assert_eq!(
            intensity[i],
            f64::from(cloud.intensity.as_ref().unwrap()[i])
        );
    }
    // And semsim reads its own file back as it was.
    let (back, _) = read_cloud(&path, &ReadOptions::default()).unwrap();
    assert_eq!(back.organized, cloud.organized);
    assert_eq!(back.intensity, cloud.intensity);
    for (a, b) in back.points.iter().zip(&cloud.points) {
        assert!(a == b || (a.is_nan() && b.is_nan()));
    }
}

/// Compares a LAS/LAZ file read by semsim with laspy's dump, in the georeferenced frame.
fn check_las_against(path: &Path, reference: &Value, tol: f64) {
    let set = read_scans(path, &ReadOptions::default()).unwrap();
    assert_eq!(set.scans.len(), 1);
    let cloud = &set.scans[0].cloud;
    let (x, y, z) = (
        f64s(&reference["x"]),
        f64s(&reference["y"]),
        f64s(&reference["z"]),
    );
    assert_eq!(cloud.len(), x.len(), "{}", path.display());
    assert_eq!(reference["count"].as_u64().unwrap() as usize, x.len());
    let origin = set.local_origin_m;
    let mut worst: f64 = 0.0;
    for (i, p) in cloud.points.iter().enumerate() {
        let world = p.as_dvec3() + origin;
        worst = worst.max((world - DVec3::new(x[i], y[i], z[i])).abs().max_element());
    }
    assert!(
        worst <= tol,
        "{}: worst {worst} m > {tol} m",
        path.display()
    );
    let intensity: Vec<f32> = i64s(&reference["intensity"])
        .iter()
        .map(|&v| v as f32)
        .collect();
    let classes: Vec<u8> = i64s(&reference["classification"])
        .iter()
        .map(|&v| v as u8)
        .collect();
    assert_eq!(cloud.intensity.as_ref(), Some(&intensity));
    assert_eq!(cloud.classification.as_ref(), Some(&classes));
    if origin != DVec3::ZERO {
        assert!(
            set.notes.iter().any(|n| n.contains("local origin")),
            "{:?}",
            set.notes
        );
    }
}

#[test]
fn georeferenced_las_and_laz_match_laspy() {
    let dir = tempfile::tempdir().unwrap();
    if !run_oracle("make_las.py", &[dir.path()]) {
        return;
    }
    // 20 m boxes: local coordinates within ±10.5 m of the origin, f32 rounding < 4.8e-7 m.
    for name in ["geo_12.las", "geo_14.laz"] {
        let path = dir.path().join(name);
        let reference = read_json(&dir.path().join(format!("{name}.json")));
        check_las_against(&path, &reference, 1e-6);
        let set = read_scans(&path, &ReadOptions::default()).unwrap();
        assert_eq!(
            set.local_origin_m,
            DVec3::new(500_123.0, 5_400_457.0, 102.0),
            "{name}"
        );
    }
    // A 300 m box: local coordinates up to ±150 m, where f32 spacing is 1.5e-5 m.
    let path = dir.path().join("geo_13.las");
    let reference = read_json(&dir.path().join("geo_13.las.json"));
    check_las_against(&path, &reference, f32_rounding(160.0));
    // The legacy overlap class 12 is kept.
    let classes = i64s(&reference["classification"]);
    assert!(classes.contains(&12));
}

#[test]
fn las_and_laz_written_by_semsim_read_in_laspy() {
    let dir = tempfile::tempdir().unwrap();
    let n = 300;
    let mut cloud = cloud::PointCloud::from_points(
        (0..n)
            .map(|i| {
                let t = i as f32 * 0.1;
                Vec3::new(t.sin() * 12.0, t.cos() * 7.0, t * 0.05 - 1.0)
            })
            .collect(),
    );
    cloud.intensity = Some((0..n).map(|i| (i * 211 % 65_536) as f32 + 0.25).collect());
    cloud.classification = Some(
        (0..n)
            .map(|i| [0u8, 1, 2, 6, 12, 40, 200, 255][i % 8])
            .collect(),
    );
    for name in ["written.las", "written.laz"] {
        let path = dir.path().join(name);
        write_cloud(&path, &cloud).unwrap();
        let Some(reference) = reference(&path) else {
            return;
        };
        assert_eq!(reference["version"], "1.4");
        assert_eq!(reference["point_format"], 6);
        let (x, y, z) = (
            f64s(&reference["x"]),
            f64s(&reference["y"]),
            f64s(&reference["z"]),
        );
        assert_eq!(x.len(), n);
        // Stored at 0.1 mm: within half of it.
        for (i, p) in cloud.points.iter().enumerate() {
            close(*p, x[i], y[i], z[i], 0.5e-4 + 1e-9, name);
        }
        let intensity: Vec<f32> = i64s(&reference["intensity"])
            .iter()
            .map(|&v| v as f32)
            .collect();
        let rounded: Vec<f32> = cloud
            .intensity
            .as_ref()
            .unwrap()
            .iter()
            .map(|v| v.round())
            .collect();
        assert_eq!(intensity, rounded, "{name}");
        let classes: Vec<u8> = i64s(&reference["classification"])
            .iter()
            .map(|&v| v as u8)
            .collect();
        assert_eq!(Some(&classes), cloud.classification.as_ref(), "{name}");
    }
}

#[test]
fn real_e57_samples_match_pye57() {
    for (name, count) in [
        ("e57rs_tiny_spherical.e57", 360),
        ("e57rs_bunnyInt19.e57", 30571),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(name);
        std::fs::copy(real(name), &path).unwrap();
        let Some(reference) = reference(&path) else {
            return;
        };
        let set = read_scans(&path, &ReadOptions::default()).unwrap();
        assert_eq!(set.scans.len(), 1, "{name}");
        let r = &reference["scans"][0];
        assert_eq!(r["x"].as_array().unwrap().len(), count);
        let valid: Vec<usize> = (0..count)
            .filter(|&i| r["valid"][i].as_bool().unwrap())
            .collect();
        let cloud = &set.scans[0].cloud;
        assert_eq!(cloud.len(), valid.len(), "{name}");
        let (x, y, z) = (opt_f64s(&r["x"]), opt_f64s(&r["y"]), opt_f64s(&r["z"]));
        // Both samples lie within 1 m of their origin: f32 rounding < 6e-8 m.
        for (k, &i) in valid.iter().enumerate() {
            close(
                cloud.points[k],
                x[i].unwrap(),
                y[i].unwrap(),
                z[i].unwrap(),
                1e-6,
                name,
            );
        }
    }
}

#[test]
fn real_las_and_laz_samples_match_laspy() {
    // simple.las / .laz span 3.4 km x 4.6 km x 180 m (local coordinates up to ±2.4 km: f32
    // spacing 2.4e-4 m); test1_4.las 500 m x 5 m x 6 m (up to ±251 m: 1.5e-5 m).
    for (name, extent) in [
        ("laspy_simple.las", 2400.0),
        ("laspy_simple.laz", 2400.0),
        ("laspy_test1_4.las", 260.0),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(name);
        std::fs::copy(real(name), &path).unwrap();
        let Some(reference) = reference(&path) else {
            return;
        };
        check_las_against(&path, &reference, f32_rounding(extent));
    }
}
