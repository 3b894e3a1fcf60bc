//! Registration benchmarks on two 541 x 301 virtual-laser scans (162,841 points each, 1 cm
//! noise) of the default building's corridor, 1 m and 5 degrees apart, the source started
//! 0.3 m / 5 degrees off the truth. Run: `cargo bench -p registration --bench icp`.

use cloud::PointCloud;
use criterion::{criterion_group, criterion_main, Criterion};
use glam::{Affine3A, DAffine3, DMat4, DQuat, DVec3, Vec3};
use rayon::prelude::*;
use registration::*;
use scanner::{Building, BuildingGeometry, LaserConfig, ScanPose, VirtualLaser};

fn scans() -> (PointCloud, PointCloud, DAffine3) {
    let building = Building::default_building().expect("default building");
    let geometry = BuildingGeometry::new(&building);
    let config = LaserConfig::default();
    let mount = config.mount_height_m;
    let laser = VirtualLaser::new(config).expect("laser");
    let (a, b) = (
        ScanPose {
            x_m: 6.5,
            y_m: 0.0,
            yaw_deg: 0.0,
        },
        ScanPose {
            x_m: 7.5,
            y_m: 0.0,
            yaw_deg: 5.0,
        },
    );
    let truth = a.world_from_scan(mount).inverse() * b.world_from_scan(mount);
    let off = DAffine3::from_rotation_translation(
        DQuat::from_axis_angle(DVec3::new(0.1, -0.1, 1.0).normalize(), 5f64.to_radians()),
        DVec3::new(1.0, 1.0, 0.3).normalize() * 0.3,
    );
    (
        laser.scan(&geometry, &a, 0),
        laser.scan(&geometry, &b, 1),
        off * truth,
    )
}

/// One pass of hinted nearest-neighbour queries, parallel over chunks as the registration does.
fn nn_pass(nn: &dyn NearestNeighbors, target: &[Vec3], queries: &[Vec3]) -> usize {
    queries
        .par_chunks(2048)
        .map(|chunk| {
            let mut last: Option<u32> = None;
            let mut found = 0;
            for q in chunk {
                let hint = last.map(|j| (j, (target[j as usize] - *q).length_squared()));
                if let Some((j, _)) = nn.nearest_with_hint(*q, 0.5, hint) {
                    last = Some(j);
                    found += 1;
                }
            }
            found
        })
        .sum()
}

fn take(r: Result<IcpResult>) -> IcpResult {
    match r {
        Ok(r) => r,
        Err(RegistrationError::NotConverged { result, .. }) => *result,
        Err(e) => panic!("{e}"),
    }
}

fn benches(c: &mut Criterion) {
    let (target, source, start) = scans();
    let finite = |c: &PointCloud| -> Vec<Vec3> {
        c.points.iter().copied().filter(|p| p.is_finite()).collect()
    };
    let tgt = finite(&target);
    let a = Affine3A::from_mat4(DMat4::from(start).as_mat4());
    let queries: Vec<Vec3> = finite(&source)
        .iter()
        .map(|p| a.transform_point3(*p))
        .collect();

    let mut g = c.benchmark_group("nn_pass_162841");
    g.sample_size(10);
    let grid = BucketGrid::new(&tgt, 0.5).expect("grid");
    let tree = KdTree::new(&tgt);
    g.bench_function("grid_0.5m", |b| b.iter(|| nn_pass(&grid, &tgt, &queries)));
    g.bench_function("kdtree", |b| b.iter(|| nn_pass(&tree, &tgt, &queries)));
    g.bench_function("build_grid_0.5m", |b| {
        b.iter(|| BucketGrid::new(&tgt, 0.5).expect("grid"))
    });
    g.bench_function("build_kdtree", |b| b.iter(|| KdTree::new(&tgt)));
    g.finish();

    let mut g = c.benchmark_group("icp");
    g.sample_size(10);
    let one = |c: IcpConfig| IcpConfig {
        max_iterations: 1,
        min_fitness: 0.0,
        ..c
    };
    // The first iteration is the slowest (no previous correspondences to hint the searches);
    // divide the 10-iteration figures by 10 for a mean per iteration.
    let p2p = one(IcpConfig::point_to_point());
    let p2p_target = Target::new(&target, &p2p).expect("target");
    g.bench_function("p2p_first_iteration_full_res", |b| {
        b.iter(|| take(register_to(&p2p_target, &source, start, &p2p)))
    });
    let p2p10 = IcpConfig {
        max_iterations: 10,
        ..p2p.clone()
    };
    g.bench_function("p2p_10_iterations_full_res", |b| {
        b.iter(|| take(register_to(&p2p_target, &source, start, &p2p10)))
    });
    let p2p_kd = IcpConfig {
        nn: NnBackend::KdTree,
        ..p2p10.clone()
    };
    let p2p_kd_target = Target::new(&target, &p2p_kd).expect("target");
    g.bench_function("p2p_10_iterations_full_res_kdtree", |b| {
        b.iter(|| take(register_to(&p2p_kd_target, &source, start, &p2p_kd)))
    });
    let p2plane = one(IcpConfig {
        method: Method::PointToPlane,
        source_voxel_m: None,
        ..IcpConfig::default()
    });
    let p2plane_target = Target::new(&target, &p2plane).expect("target");
    g.bench_function("p2plane_one_iteration_full_res_source", |b| {
        b.iter(|| take(register_to(&p2plane_target, &source, start, &p2plane)))
    });
    let gicp = IcpConfig {
        source_voxel_m: Some(0.05),
        target_voxel_m: Some(0.05),
        normal_voxel_m: 0.05,
        ..IcpConfig::default()
    };
    g.bench_function("gicp_prepare_target_5cm", |b| {
        b.iter(|| Target::new(&target, &gicp).expect("target"))
    });
    let gicp_target = Target::new(&target, &gicp).expect("target");
    g.bench_function("gicp_to_convergence_5cm", |b| {
        b.iter(|| take(register_to(&gicp_target, &source, start, &gicp)))
    });
    let default = IcpConfig::default();
    g.bench_function("register_defaults_total", |b| {
        b.iter(|| take(register(&source, &target, start, &default)))
    });
    g.finish();
}

criterion_group!(icp, benches);
criterion_main!(icp);
