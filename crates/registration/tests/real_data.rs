//! Registration of the real scans in `shared/data/real` (see its MANIFEST.md) against their
//! reference registrations. Each test skips, saying so, when the folder is absent.

mod common;

use cloud::io::threedtk::{read_3d, read_frames_3dtk, read_pose_3dtk};
use cloud::{pose_error, read_cloud};
use common::real_data;
use glam::{DAffine3, DMat4, DQuat, DVec3};
use registration::*;

/// Reads a 4x4 row-major text matrix.
fn read_matrix(path: &std::path::Path) -> DAffine3 {
    let text = std::fs::read_to_string(path).expect("matrix file");
    let v: Vec<f64> = text
        .split_whitespace()
        .map(|t| t.parse().expect("number"))
        .collect();
    assert_eq!(v.len(), 16, "{}", path.display());
    DAffine3::from_mat4(DMat4::from_cols_array(&v.try_into().expect("16")).transpose())
}

#[test]
fn small_gicp_street_pair_matches_the_reference_from_identity() {
    let Some(dir) = real_data("small_gicp_street_pair") else {
        return;
    };
    let dir = dir.join("small-gicp");
    let source = read_cloud(&dir.join("source.ply")).expect("source");
    let target = read_cloud(&dir.join("target.ply")).expect("target");
    let reference = read_matrix(&dir.join("T_target_source.txt"));
    // Outdoor lidar: ranges of tens of metres, so coarser voxels than indoors (as small_gicp's
    // own example does).
    let config = IcpConfig {
        source_voxel_m: Some(0.25),
        target_voxel_m: Some(0.25),
        normal_voxel_m: 0.25,
        neighbours_k: 10,
        ..IcpConfig::default()
    };
    let r = register(&source, &target, DAffine3::IDENTITY, &config).expect("registers");
    let (et, er) = pose_error(&r.target_from_source, &reference);
    eprintln!(
        "small_gicp: {et:.4} m {er:.3} deg from the reference, {} it, {:.0} ms, fitness {:.2}",
        r.iterations.len(),
        r.total_ms,
        r.fitness
    );
    assert!(et < 0.05 && er < 0.5, "{et} m {er} deg");
}

#[test]
fn threedtk_corridor_sequence_matches_the_2009_registration() {
    let Some(dir) = real_data("threedtk_corridor_sequence") else {
        return;
    };
    let dir = dir.join("3dtk-corridor");
    let mut scans = Vec::new();
    let mut odometry = Vec::new();
    let mut reference = Vec::new();
    for k in 0..3 {
        let name = format!("scan{k:03}");
        scans.push(read_3d(&dir.join(format!("{name}.3d"))).expect("scan"));
        odometry.push(read_pose_3dtk(&dir.join(format!("{name}.pose"))).expect("pose"));
        let frames = read_frames_3dtk(&dir.join("frames_2009").join(format!("{name}.frames")))
            .expect("frames");
        reference.push(*frames.last().expect("a frame"));
    }
    // The 2009 reference came from point-to-point ICP on (nearly) full-resolution scans; our
    // point-to-point on 2 cm voxels with a shrinking gate reproduces it. (GICP and
    // point-to-plane on 5 cm voxels land about 1-1.5 degrees of pitch away from it on this
    // old, noisy scanner's data: see the crate documentation.)
    let config = SequenceConfig {
        icp: IcpConfig {
            max_iterations: 200,
            final_correspondence_distance_m: 0.1,
            ..IcpConfig::point_to_point()
        },
        // The paper's ICP: every point weighs the same.
        range_knee_m: 0.0,
        scan_voxel_m: 0.02,
        map_voxel_m: 0.02,
        ..SequenceConfig::default()
    };
    let mut calls = Vec::new();
    let result = register_sequence(&scans, &odometry, &config, &mut |done, total| {
        calls.push((done, total))
    })
    .expect("sequence registers");
    assert_eq!(calls.last(), Some(&(3, 3)));
    assert!(result.results[0].is_none() && result.results[1..].iter().all(|r| r.is_some()));
    assert!(
        result.world_from_scan[0].abs_diff_eq(odometry[0], 1e-12),
        "scan 0 keeps its pose"
    );
    for k in 1..3 {
        let ours = result.world_from_scan[0].inverse() * result.world_from_scan[k];
        let theirs = reference[0].inverse() * reference[k];
        let odo = odometry[0].inverse() * odometry[k];
        let (et, er) = pose_error(&ours, &theirs);
        let (ot, or) = pose_error(&odo, &theirs);
        eprintln!("3dtk scan {k}: {et:.4} m {er:.3} deg from the 2009 registration (odometry was {ot:.3} m {or:.2} deg off)");
        assert!(et < 0.05 && er < 1.0, "scan {k}: {et} m {er} deg");
    }
    let map = &result.map;
    assert!(map.len() > 50_000 && map.organized.is_none());
}

#[test]
fn pcl_room_pair_converges_from_the_ndt_tutorial_guess() {
    let Some(dir) = real_data("pcl_room_pair") else {
        return;
    };
    let dir = dir.join("pcl-room");
    let target = read_cloud(&dir.join("room_scan1.pcd")).expect("scan1");
    let source = read_cloud(&dir.join("room_scan2.pcd")).expect("scan2");
    // PCL's NDT tutorial guess (its yaw happens to be close to ln 2).
    #[allow(clippy::approx_constant)]
    let yaw = 0.6931;
    let guess = DAffine3::from_rotation_translation(
        DQuat::from_rotation_z(yaw),
        DVec3::new(1.79387, 0.720047, 0.0),
    );
    let config = IcpConfig::default();
    let r = register(&source, &target, guess, &config).expect("registers");
    // Residuals of the moved source points: distance to the nearest target point, and to the
    // target surface (the plane through the target's 12 nearest points within 0.3 m). The
    // scans are sparse far from the sensor, so the point distance has a floor of a few cm.
    let tree = KdTree::new(&target.points);
    let mut buf = Vec::new();
    let (mut to_point, mut to_plane) = (Vec::new(), Vec::new());
    for p in source.points.iter().filter(|p| p.is_finite()).step_by(3) {
        let q = r
            .target_from_source
            .transform_point3(p.as_dvec3())
            .as_vec3();
        if let Some((_, d2)) = tree.nearest(q, 10.0) {
            to_point.push(d2.sqrt());
        }
        tree.k_nearest(q, 12, 0.3, &mut buf);
        if buf.len() >= 6 {
            to_plane.push(plane_distance(&target.points, &buf, q));
        }
    }
    let median = |v: &mut Vec<f32>| {
        v.sort_by(f32::total_cmp);
        v[v.len() / 2]
    };
    let (point_median, plane_median) = (median(&mut to_point), median(&mut to_plane));
    let (gt, gr) = pose_error(&r.target_from_source, &guess);
    eprintln!(
        "pcl room: median residual to the target surface {plane_median:.4} m (to the nearest point {point_median:.4} m), {} it, {:.0} ms, {gt:.3} m {gr:.2} deg from the guess, fitness {:.2}",
        r.iterations.len(),
        r.total_ms,
        r.fitness
    );
    assert!(plane_median < 0.05, "median residual {plane_median} m");
    assert!(point_median < 0.1, "median point residual {point_median} m");
    assert!(r.fitness > 0.5);
}

/// Distance from `q` to the least-squares plane of the given points.
fn plane_distance(points: &[glam::Vec3], idx: &[u32], q: glam::Vec3) -> f32 {
    let n = idx.len() as f64;
    let c = idx
        .iter()
        .map(|&j| points[j as usize].as_dvec3())
        .sum::<DVec3>()
        / n;
    let mut m = glam::DMat3::ZERO;
    for &j in idx {
        let d = points[j as usize].as_dvec3() - c;
        m += glam::DMat3::from_cols(d * d.x, d * d.y, d * d.z);
    }
    // Smallest eigenvector by power iteration on (trace I - M).
    let shifted =
        glam::DMat3::from_diagonal(DVec3::splat(m.x_axis.x + m.y_axis.y + m.z_axis.z)) - m;
    let mut v = DVec3::new(0.3, 0.5, 0.8).normalize();
    for _ in 0..100 {
        v = (shifted * v).normalize();
    }
    (q.as_dvec3() - c).dot(v).abs() as f32
}
