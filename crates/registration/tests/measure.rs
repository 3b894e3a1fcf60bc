//! The measurements behind the defaults and the figures in the crate documentation. Not a
//! pass/fail test; run it in release on an otherwise idle machine:
//!
//! `cargo test --release -p registration --test measure -- --ignored --nocapture`
//!
//! Two 541 x 301 virtual-laser scans (162,841 points, 1 cm noise) of the default building's
//! corridor, 1 m and 5 degrees apart; registrations start 0.3 m / 5 degrees off the truth.

mod common;

use cloud::pose_error;
use common::*;
use glam::{Affine3A, DMat4, Vec3};
use registration::*;
use std::time::Instant;

/// CPU time of the calling thread (ns), robust against other load on the machine.
fn cpu_ns() -> u64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next().and_then(|v| v.parse().ok()))
        .unwrap_or(0)
}

/// CPU time of the whole process (all threads), ms, 10 ms resolution.
fn process_cpu_ms() -> f64 {
    std::fs::read_to_string("/proc/self/stat")
        .ok()
        .and_then(|s| {
            let rest = s.rsplit_once(')')?.1.split_whitespace().collect::<Vec<_>>();
            let utime: f64 = rest.get(11)?.parse().ok()?;
            let stime: f64 = rest.get(12)?.parse().ok()?;
            Some((utime + stime) * 10.0)
        })
        .unwrap_or(0.0)
}

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

/// One-thread CPU time of a pass of nearest-neighbour queries (0.5 m gate), each hinted with
/// the previous query's neighbour as the registration does; the best of 5.
fn nn_pass(nn: &dyn NearestNeighbors, target: &[Vec3], queries: &[Vec3]) -> (f64, usize) {
    let mut best = (f64::MAX, 0);
    for _ in 0..5 {
        let t = cpu_ns();
        let mut last: Option<u32> = None;
        let mut found = 0;
        for q in queries {
            let hint = last.map(|j| (j, (target[j as usize] - *q).length_squared()));
            if let Some((j, _)) = nn.nearest_with_hint(*q, 0.5, hint) {
                last = Some(j);
                found += 1;
            }
        }
        let took = (cpu_ns() - t) as f64 / 1e6;
        if took < best.0 {
            best = (took, found);
        }
    }
    best
}

#[test]
#[ignore = "measurement report; run in release with --ignored --nocapture"]
fn measure() {
    let t0 = Instant::now();
    let (target, source, truth) = scan_pair(541, 301);
    let start = standard_start(&truth);
    println!(
        "scans: {} + {} valid points in {:.0} ms; {} threads",
        target.valid_count(),
        source.valid_count(),
        ms(t0),
        rayon::current_num_threads()
    );
    let finite = |c: &cloud::PointCloud| -> Vec<Vec3> {
        c.points.iter().copied().filter(|p| p.is_finite()).collect()
    };
    let (src, tgt) = (finite(&source), finite(&target));
    let moved = |t: &glam::DAffine3| -> Vec<Vec3> {
        let a = Affine3A::from_mat4(DMat4::from(*t).as_mat4());
        src.iter().map(|p| a.transform_point3(*p)).collect()
    };
    let (from_start, at_truth) = (moved(&start), moved(&truth));

    println!("\n-- one nearest-neighbour pass, 1 thread CPU time (4 ms resolution)");
    let t = Instant::now();
    let tree = KdTree::new(&tgt);
    let build = ms(t);
    let (a, fa) = nn_pass(&tree, &tgt, &from_start);
    let (b, fb) = nn_pass(&tree, &tgt, &at_truth);
    println!("kdtree: build {build:.1} ms; from start {a:.0} ms ({fa} found), at truth {b:.0} ms ({fb} found)");
    for bucket in [0.15, 0.25, 0.3, 0.5] {
        let t = Instant::now();
        let grid = BucketGrid::new(&tgt, bucket).expect("grid");
        let build = ms(t);
        let (a, fa) = nn_pass(&grid, &tgt, &from_start);
        let (b, fb) = nn_pass(&grid, &tgt, &at_truth);
        println!(
            "grid {bucket} m ({} buckets): build {build:.1} ms; from start {a:.0} ms ({fa} found), at truth {b:.0} ms ({fb} found)",
            grid.occupied_buckets()
        );
    }

    let run = |name: &str, c: &IcpConfig| {
        let mut best: Option<(f64, f64, IcpResult)> = None;
        let mut best_cpu = f64::MAX;
        for _ in 0..3 {
            let t = Instant::now();
            let prepared = Target::new(&target, c).expect("target");
            let prep = ms(t);
            let cpu = process_cpu_ms();
            let r = register_to(&prepared, &source, start, c);
            best_cpu = best_cpu.min(process_cpu_ms() - cpu);
            let r = match r {
                Ok(r) => r,
                Err(RegistrationError::NotConverged { result, .. }) => *result,
                Err(e) => panic!("{name}: {e}"),
            };
            let total = prep + r.total_ms;
            if best.as_ref().is_none_or(|b| total < b.0 + b.1) {
                best = Some((prep, r.total_ms, r));
            }
        }
        let Some((prep, reg, r)) = best else { return };
        let (et, er) = pose_error(&r.target_from_source, &truth);
        let n = r.iterations.len();
        let mean = r.iterations.iter().map(|i| i.time_ms).sum::<f64>() / n as f64;
        let threads = rayon::current_num_threads() as f64;
        println!(
            "{name}: {:.0} ms (target {prep:.0} + register {reg:.0}), {n} it at {mean:.1} ms (CPU time / {threads} threads: {:.1} ms), error {:.1} mm {:.3} deg, converged {}",
            prep + reg,
            best_cpu / threads / n as f64,
            et * 1e3,
            er,
            r.converged
        );
    };
    println!("\n-- one point-to-point iteration at full resolution from the start (best of 5)");
    let one = IcpConfig {
        max_iterations: 1,
        ..IcpConfig::point_to_point()
    };
    let prepared = Target::new(&target, &one).expect("target");
    let mut best = (f64::MAX, 0.0);
    for _ in 0..5 {
        let t = Instant::now();
        let r = match register_to(&prepared, &source, start, &one) {
            Err(RegistrationError::NotConverged { result, .. }) => *result,
            other => panic!("{other:?}"),
        };
        if ms(t) < best.0 {
            best = (ms(t), r.iterations[0].time_ms);
        }
    }
    println!(
        "register_to: {:.1} ms, of which the iteration {:.1} ms",
        best.0, best.1
    );

    println!(
        "\n-- point-to-point at full resolution, 0.5 m gate, 10 iterations (best of 3, 2 threads)"
    );
    let p2p = IcpConfig {
        max_iterations: 10,
        ..IcpConfig::point_to_point()
    };
    for bucket in [0.3, 0.5] {
        run(
            &format!("p2p grid {bucket} m"),
            &IcpConfig {
                bucket_size_m: bucket,
                ..p2p.clone()
            },
        );
    }
    run(
        "p2p kdtree",
        &IcpConfig {
            nn: NnBackend::KdTree,
            ..p2p.clone()
        },
    );
    run(
        "p2p grid, 5 cm voxels",
        &IcpConfig {
            source_voxel_m: Some(0.05),
            target_voxel_m: Some(0.05),
            ..p2p.clone()
        },
    );
    run(
        "p2p grid, to convergence",
        &IcpConfig {
            max_iterations: 300,
            ..IcpConfig::point_to_point()
        },
    );

    println!("\n-- point-to-plane and GICP on voxel-downsampled clouds, to convergence");
    for method in [Method::PointToPlane, Method::Gicp] {
        for voxel in [0.05, 0.1, 0.2] {
            let c = IcpConfig {
                method,
                source_voxel_m: Some(voxel),
                target_voxel_m: Some(voxel),
                normal_voxel_m: voxel,
                ..IcpConfig::default()
            };
            run(&format!("{method} {voxel} m voxels"), &c);
        }
    }
    run("defaults", &IcpConfig::default());
    for bucket in [0.3, 0.5] {
        run(
            &format!("defaults, grid {bucket} m"),
            &IcpConfig {
                bucket_size_m: bucket,
                ..IcpConfig::default()
            },
        );
    }
    run(
        "defaults, kdtree",
        &IcpConfig {
            nn: NnBackend::KdTree,
            ..IcpConfig::default()
        },
    );
}
