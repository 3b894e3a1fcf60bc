//! ROS 2 bags written by mcap-ros2-support (`tools/oracles/make_mcap.py`: zstd, lz4 and
//! uncompressed chunks) read by semsim and compared message for message and point for point
//! with what mcap-ros2-support decodes, odometry poses (interpolated between messages) and
//! topic selection included. f64 data within ±30 m: f32 rounding under 1e-6 m; f32 data exact.

mod scans_support;

use glam::{DAffine3, DQuat, DVec3};
use interop::{read_cloud, read_scans, ReadOptions};
use scans_support::*;
use std::path::Path;

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
