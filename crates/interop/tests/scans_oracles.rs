//! The scan readers and writers against other implementations: files written by libE57Format
//! (pye57), laspy (+ lazrs) and mcap-ros2-support are read by semsim and compared point for
//! point with what those libraries read back (`tools/oracles/make_*.py`); files semsim writes
//! are read back by pye57 and laspy (`tools/oracles/read_reference.py`); and real public
//! samples (`tests/data/real/`) are read by both.
//!
//! Tolerances: semsim keeps positions as f32 metres, so a position can differ from the f64
//! reference by the f32 rounding at its magnitude (`f32_rounding`): under 1e-6 m for the
//! test files' ±16 m (the georeferenced LAS files are read relative to a local origin for
//! exactly this reason), more where a file spans more (a 300 m LAS box: 1.5e-5 m; the real
//! simple.las spans 4.6 km: 1.2e-4 m), as each test states.

mod scans_support;

use glam::{DAffine3, DQuat, DVec3, Vec3};
use interop::{read_cloud, read_scans, write_cloud, ReadOptions};
use scans_support::*;
use serde_json::Value;
use std::path::Path;

fn pose_from(rotation_wxyz: &Value, translation: &Value) -> DAffine3 {
    let q = f64s(rotation_wxyz);
    let t = f64s(translation);
    DAffine3::from_rotation_translation(
        DQuat::from_xyzw(q[1], q[2], q[3], q[0]).normalize(),
        DVec3::new(t[0], t[1], t[2]),
    )
}

fn assert_pose_eq(a: &DAffine3, b: &DAffine3, what: &str) {
    let d = (a.to_cols_array().iter().zip(b.to_cols_array()))
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(d < 1e-12, "{what}: poses differ by {d}: {a:?} vs {b:?}");
}

fn close(p: Vec3, x: f64, y: f64, z: f64, tol: f64, what: &str) {
    let d = (p.as_dvec3() - DVec3::new(x, y, z)).abs().max_element();
    assert!(
        d <= tol,
        "{what}: {p:?} vs ({x}, {y}, {z}): {d} m > {tol} m"
    );
}

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
fn ros2_bags_match_mcap_ros2() {
    let dir = tempfile::tempdir().unwrap();
    for compression in ["zstd", "lz4", "none"] {
        if !run_oracle("make_mcap.py", &[dir.path(), Path::new(compression)]) {
            return;
        }
        let path = dir.path().join(format!("bag_{compression}.mcap"));
        let reference = read_json(&dir.path().join(format!("bag_{compression}.mcap.json")));
        let set = read_scans(&path, &ReadOptions::default()).unwrap();
        let clouds = reference["clouds"].as_array().unwrap();
        assert_eq!(set.scans.len(), clouds.len(), "{compression}");
        let mut total = 0;
        for (index, (scan, r)) in set.scans.iter().zip(clouds).enumerate() {
            assert_eq!(scan.name, format!("/lidar/points#{index}"));
            assert_eq!(scan.stamp_ns, r["stamp_ns"].as_i64());
            assert_eq!(scan.frame_id.as_deref(), r["frame_id"].as_str());
            let (x, y, z) = (opt_f64s(&r["x"]), opt_f64s(&r["y"]), opt_f64s(&r["z"]));
            let intensity = r.get("intensity").map(opt_f64s);
            let cloud = &scan.cloud;
            cloud.validate().unwrap();
            assert_eq!(cloud.intensity.is_some(), intensity.is_some());
            let (height, width) = (
                r["height"].as_u64().unwrap() as usize,
                r["width"].as_u64().unwrap() as usize,
            );
            let organised = height > 1;
            assert_eq!(
                cloud.organized.map(|o| (o.rows, o.cols)),
                organised.then_some((height, width))
            );
            let mut k = 0;
            for i in 0..x.len() {
                let finite = x[i].is_some() && y[i].is_some() && z[i].is_some();
                if !finite && !organised {
                    continue; // dropped from unorganised clouds
                }
                if finite {
                    // f64 data within ±30 m: f32 rounding < 1e-6 m (f32 data: exact).
                    close(
                        cloud.points[k],
                        x[i].unwrap(),
                        y[i].unwrap(),
                        z[i].unwrap(),
                        1e-6,
                        &scan.name,
                    );
                    total += 1;
                } else {
                    assert!(cloud.points[k].is_nan());
                }
                if let Some(want) = &intensity {
                    assert_eq!(
                        f64::from(cloud.intensity.as_ref().unwrap()[k]),
                        want[i].unwrap() as f32 as f64
                    );
                }
                k += 1;
            }
            assert_eq!(k, cloud.len());
        }
        assert_eq!(
            (set.scans[0].cloud.len(), set.scans[1].cloud.len()),
            (197, 128)
        );

        // Odometry: message 0 and 2 lie on odometry stamps, message 1 halfway between two.
        let odom: Vec<DAffine3> = reference["odometry"]
            .as_array()
            .unwrap()
            .iter()
            .map(|o| {
                let q = f64s(&o["orientation_xyzw"]);
                let p = f64s(&o["position"]);
                DAffine3::from_rotation_translation(
                    DQuat::from_xyzw(q[0], q[1], q[2], q[3]).normalize(),
                    DVec3::new(p[0], p[1], p[2]),
                )
            })
            .collect();
        let poses = set.odometry.as_ref().expect("odometry");
        assert_eq!(poses.len(), 3);
        assert_pose_eq(&poses[0], &odom[1], "scan 0");
        assert_pose_eq(&poses[2], &odom[3], "scan 2");
        let (q1, q2) = (
            DQuat::from_mat3(&odom[1].matrix3),
            DQuat::from_mat3(&odom[2].matrix3),
        );
        let halfway = DAffine3::from_rotation_translation(
            q1.slerp(q2, 0.5),
            odom[1].translation.lerp(odom[2].translation, 0.5),
        );
        assert_pose_eq(&poses[1], &halfway, "scan 1");
        // Clouds in base_link (the odometry's child) are placed by it; one in odom as it is.
        assert_pose_eq(
            &set.scans[0].world_from_scan.unwrap(),
            &poses[0],
            "placed 0",
        );
        assert_pose_eq(
            &set.scans[1].world_from_scan.unwrap(),
            &poses[1],
            "placed 1",
        );
        assert_eq!(set.scans[2].world_from_scan, Some(DAffine3::IDENTITY));

        let (merged, notes) = read_cloud(&path, &ReadOptions::default()).unwrap();
        assert_eq!(merged.len(), total);
        assert!(
            notes
                .iter()
                .all(|n| n.starts_with(&path.display().to_string())),
            "{notes:?}"
        );
        let first = poses[0].transform_point3(set.scans[0].cloud.points[0].as_dvec3());
        close(merged.points[0], first.x, first.y, first.z, 1e-5, "merged");
    }
}

#[test]
fn ros2_bag_topics_are_chosen_or_listed() {
    let dir = tempfile::tempdir().unwrap();
    if !run_oracle("make_mcap.py", &[dir.path(), Path::new("none")]) {
        return;
    }
    let two = dir.path().join("two_clouds.mcap");
    let e = read_scans(&two, &ReadOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("two_clouds.mcap") && e.contains("\"/front\"") && e.contains("\"/rear\""),
        "{e}"
    );
    let rear = ReadOptions {
        topic: Some("/rear".into()),
        ..Default::default()
    };
    let set = read_scans(&two, &rear).unwrap();
    assert_eq!(set.scans.len(), 1);
    assert_eq!(set.scans[0].frame_id.as_deref(), Some("rear"));
    assert!(set.odometry.is_none());
    let reference = read_json(&dir.path().join("two_clouds.mcap.json"));
    let x = f64s(&reference["clouds"][1]["x"]);
    assert_eq!(set.scans[0].cloud.points[0].x, x[0] as f32);

    let bag = dir.path().join("bag_none.mcap");
    for options in [
        ReadOptions {
            topic: Some("/nope".into()),
            ..Default::default()
        },
        ReadOptions {
            topic: Some("/chatter".into()),
            ..Default::default()
        },
        ReadOptions {
            odometry_topic: Some("/points".into()),
            ..Default::default()
        },
    ] {
        let e = read_scans(&bag, &options).unwrap_err();
        assert!(matches!(e, interop::InteropError::Format { .. }), "{e}");
        let text = e.to_string();
        assert!(
            text.contains("bag_none.mcap") && text.contains("topics:"),
            "{text}"
        );
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
