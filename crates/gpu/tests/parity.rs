//! The GPU search and reductions against brute force on the CPU, on virtual-laser scans.
//! Runs on any Vulkan adapter, Mesa's lavapipe included; skips (with a message) only where
//! there is no adapter at all.

use glam::{Mat4, Quat, Vec3};
use gpu::{AdapterChoice, GpuContext, GpuIcp, GpuKernel};
use scanner::{Building, BuildingGeometry, LaserConfig, ScanPose, VirtualLaser};

fn open() -> Option<GpuIcp> {
    match GpuContext::new(AdapterChoice::Any) {
        Ok(ctx) => {
            eprintln!("GPU adapter: {}", ctx.adapter_name());
            Some(GpuIcp::new(ctx).expect("kernels compile"))
        }
        Err(e) => {
            eprintln!("skipping: {e}");
            None
        }
    }
}

fn scans() -> (Vec<Vec3>, Vec<Vec3>) {
    let b = Building::default_building().expect("default");
    let g = BuildingGeometry::new(&b);
    let laser = VirtualLaser::new(LaserConfig {
        beams: 121,
        rotation_steps: 61,
        ..Default::default()
    })
    .expect("laser");
    let a = laser
        .scan(
            &g,
            &ScanPose {
                x_m: 6.5,
                y_m: 0.0,
                yaw_deg: 0.0,
            },
            0,
        )
        .without_invalid();
    let s = laser
        .scan(
            &g,
            &ScanPose {
                x_m: 7.3,
                y_m: 0.5,
                yaw_deg: 5.0,
            },
            1,
        )
        .without_invalid();
    (a.points, s.points)
}

fn brute(p: Vec3, target: &[Vec3], max_d2: f32) -> Option<f32> {
    target
        .iter()
        .map(|q| (*q - p).length_squared())
        .filter(|d| *d <= max_d2)
        .min_by(f32::total_cmp)
}

#[test]
fn gpu_correspondences_equal_brute_force_within_the_bucket() {
    let Some(mut icp) = open() else { return };
    let (target, source) = scans();
    let bucket = 0.25f32;
    icp.set_target(&target, None, bucket).expect("target");
    icp.set_source(&source).expect("source");
    let t = Mat4::from_rotation_translation(Quat::from_rotation_z(0.08), Vec3::new(0.7, 0.45, 0.0));
    let moved =
        Mat4::from_rotation_translation(Quat::from_rotation_z(0.05), Vec3::new(0.6, 0.5, 0.02));
    let gate = bucket; // within one bucket edge the 27-bucket search is exact
                       // The first search has no hints; the later ones start from the previous iteration's
                       // correspondences (a transform that moved, then one that did not): all must be exact.
    for (k, t) in [t, moved, moved].into_iter().enumerate() {
        let corr = icp.correspondences(t, gate).expect("search");
        assert_eq!(corr.len(), source.len());
        let mut found = 0;
        for (s, c) in source.iter().zip(&corr) {
            let p = t.transform_point3(*s);
            let truth = brute(p, &target, gate * gate);
            match (truth, c) {
                (None, None) => {}
                (Some(d), Some((idx, d2))) => {
                    assert!(
                        (d.sqrt() - d2.sqrt()).abs() < 1e-6,
                        "search {k}: distance {} vs {}",
                        d.sqrt(),
                        d2.sqrt()
                    );
                    assert!(((target[*idx as usize] - p).length_squared() - d).abs() < 1e-6);
                    found += 1;
                }
                other => panic!("search {k}: GPU and brute force disagree on {p}: {other:?}"),
            }
        }
        assert!(
            found > source.len() / 2,
            "search {k}: only {found} correspondences"
        );
    }
}

#[test]
fn gpu_sums_equal_cpu_sums() {
    let Some(mut icp) = open() else { return };
    let (target, source) = scans();
    // Normals are only carried, not checked here: any unit vectors will do.
    let normals: Vec<Vec3> = target.iter().map(|p| p.normalize_or(Vec3::Z)).collect();
    icp.set_target(&target, Some(&normals), 0.3)
        .expect("target");
    icp.set_source(&source).expect("source");
    let t = Mat4::from_rotation_translation(Quat::from_rotation_z(0.087), Vec3::new(0.8, 0.5, 0.0));
    let reference = Vec3::new(7.0, 0.0, 1.0);
    let corr = icp.correspondences(t, 0.3).expect("search");
    let (sums, _) = icp.p2p_sums(t, 0.3, reference).expect("p2p");
    let (sys, _) = icp
        .p2plane_system(t, 0.3, reference, GpuKernel::None)
        .expect("p2plane");
    let (mut n, mut sp, mut sq, mut d2s, mut r2) =
        (0.0f64, [0.0f64; 3], [0.0f64; 3], 0.0f64, 0.0f64);
    for (s, c) in source.iter().zip(&corr) {
        let Some((idx, d2)) = c else { continue };
        let p = t.transform_point3(*s) - reference;
        let q = target[*idx as usize] - reference;
        n += 1.0;
        for k in 0..3 {
            sp[k] += p[k] as f64;
            sq[k] += q[k] as f64;
        }
        d2s += *d2 as f64;
        r2 += ((p - q).dot(normals[*idx as usize]) as f64).powi(2);
    }
    assert_eq!(sums.count, n);
    assert_eq!(sys.count, n);
    for k in 0..3 {
        assert!(
            (sums.sum_p[k] - sp[k]).abs() < 1e-3 * n,
            "sum p {k}: {} vs {}",
            sums.sum_p[k],
            sp[k]
        );
        assert!((sums.sum_q[k] - sq[k]).abs() < 1e-3 * n, "sum q {k}");
    }
    assert!(
        (sums.sum_d2 - d2s).abs() < 1e-4 * d2s.max(1.0),
        "{} vs {d2s}",
        sums.sum_d2
    );
    assert!(
        (sys.sum_wr2 - r2).abs() < 1e-3 * r2.max(1.0),
        "{} vs {r2}",
        sys.sum_wr2
    );
}

#[test]
fn bad_inputs_are_errors() {
    let Some(mut icp) = open() else { return };
    assert!(icp.set_target(&[], None, 0.2).is_err());
    assert!(icp.set_target(&[Vec3::NAN], None, 0.2).is_err());
    assert!(icp.set_target(&[Vec3::ZERO], None, 0.0).is_err());
    assert!(icp
        .set_target(&[Vec3::ZERO, Vec3::splat(1e7)], None, 0.001)
        .is_err());
    assert!(
        icp.p2p_sums(Mat4::IDENTITY, 0.5, Vec3::ZERO).is_err(),
        "no clouds yet"
    );
    icp.set_target(&[Vec3::ZERO, Vec3::X], None, 0.5)
        .expect("target");
    assert!(icp.set_source(&[]).is_err());
    icp.set_source(&[Vec3::ZERO]).expect("source");
    assert!(
        icp.p2plane_system(Mat4::IDENTITY, 0.5, Vec3::ZERO, GpuKernel::None)
            .is_err(),
        "no normals"
    );
    assert!(icp.p2p_sums(Mat4::IDENTITY, -1.0, Vec3::ZERO).is_err());
    assert!(
        icp.set_back_face_test(Some(Vec3::ZERO)).is_err(),
        "the back-face test needs normals"
    );
    icp.set_target(&[Vec3::ZERO, Vec3::X], Some(&[Vec3::Z, Vec3::Z]), 0.5)
        .expect("target");
    assert!(icp.set_back_face_test(Some(Vec3::NAN)).is_err());
}

#[test]
fn back_faces_are_no_pairs_exactly_as_brute_force_says() {
    let Some(mut icp) = open() else { return };
    let (target, source) = scans();
    // Normals pointing toward +y or -y by the point's index: about half the surfaces are seen
    // from behind by any sensor.
    let normals: Vec<Vec3> = (0..target.len())
        .map(|i| if i % 3 == 0 { Vec3::Y } else { -Vec3::Y })
        .collect();
    let gate = 0.25f32;
    icp.set_target(&target, Some(&normals), gate)
        .expect("target");
    icp.set_source(&source).expect("source");
    let sensor_in_source = Vec3::new(0.1, -0.2, 0.3);
    icp.set_back_face_test(Some(sensor_in_source))
        .expect("normals are there");
    let t = Mat4::from_rotation_translation(Quat::from_rotation_z(0.08), Vec3::new(0.7, 0.45, 0.0));
    let eye = t.transform_point3(sensor_in_source);
    let (mut kept, mut rejected) = (0, 0);
    for round in 0..2 {
        let corr = icp.correspondences(t, gate).expect("search");
        for (s, c) in source.iter().zip(&corr) {
            let p = t.transform_point3(*s);
            // The nearest point (smallest distance, then smallest index) and its facing.
            let nearest = target
                .iter()
                .enumerate()
                .map(|(j, q)| ((*q - p).length_squared(), j))
                .filter(|(d, _)| *d < gate * gate)
                .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            let facing = |j: usize| normals[j].dot(eye - target[j]) >= 0.0;
            match (nearest, c) {
                (None, None) => {}
                (Some((_, j)), None) if !facing(j) => rejected += 1,
                (Some((d, j)), Some((i, d2))) if facing(j) => {
                    assert_eq!(*i as usize, j, "round {round}: {p}");
                    assert!((d - d2).abs() < 1e-6);
                    kept += 1;
                }
                other => panic!("round {round}: {p}: brute force and GPU disagree: {other:?}"),
            }
        }
    }
    eprintln!("back-face test over two rounds: {kept} pairs kept, {rejected} rejected");
    assert!(
        kept > 1000 && rejected > 1000,
        "{kept} kept, {rejected} rejected"
    );
    // Off again: every nearest point pairs.
    icp.set_back_face_test(None).expect("off");
    let all = icp.correspondences(t, gate).expect("search");
    assert_eq!(all.iter().flatten().count(), (kept + rejected) / 2);
}
