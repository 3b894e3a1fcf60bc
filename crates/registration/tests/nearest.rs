//! The bucket grid against the k-d tree and brute force on a virtual-laser scan.

mod common;

use common::*;
use glam::{Affine3A, DMat4, Vec3};
use registration::*;

/// `n` deterministic random points in the cube `[0, scale)^3`.
fn points(seed: u64, n: usize, scale: f32) -> Vec<Vec3> {
    let mut rng = Rng(seed);
    (0..n)
        .map(|_| {
            Vec3::new(
                rng.next_f64() as f32,
                rng.next_f64() as f32,
                rng.next_f64() as f32,
            ) * scale
        })
        .collect()
}

fn brute(points: &[Vec3], q: Vec3) -> f32 {
    points
        .iter()
        .map(|p| (*p - q).length_squared())
        .fold(f32::INFINITY, f32::min)
}

#[test]
fn grid_matches_brute_force_and_kdtree_within_a_bucket() {
    // Sparse buckets, dense (sub-divided) buckets, and a dense plane.
    let plane: Vec<Vec3> = points(3, 20_000, 1.0)
        .into_iter()
        .map(|p| Vec3::new(p.x, p.y, 0.3 + 0.01 * p.z))
        .collect();
    for (pts, bucket) in [
        (points(7, 3000, 2.0), 0.2f32),
        (points(8, 20_000, 0.5), 0.25),
        (plane, 0.3),
    ] {
        let grid = BucketGrid::new(&pts, bucket as f64).expect("grid");
        let tree = KdTree::new(&pts);
        assert_eq!(grid.len(), pts.len());
        let (lo, hi) = pts
            .iter()
            .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(l, h), p| {
                (l.min(*p), h.max(*p))
            });
        let mut checked = 0;
        for q in points(99, 2000, 1.0) {
            let q = lo - Vec3::splat(0.1) + q * (hi - lo + Vec3::splat(0.2));
            let truth = brute(&pts, q);
            let g = grid.nearest(q, bucket);
            // A hint (any point, with its true distance) never changes the answer.
            let h = q.x.to_bits() % pts.len() as u32;
            let hinted = grid.nearest_with_hint(
                q,
                bucket,
                Some((h, (pts[h as usize] - q).length_squared())),
            );
            assert_eq!(hinted.map(|r| r.1), g.map(|r| r.1));
            let t = tree.nearest(q, bucket);
            if truth < bucket * bucket * 0.999 {
                let (gi, gd) = g.expect("grid finds a neighbour within a bucket");
                let (ti, td) = t.expect("tree finds it too");
                assert!((gd - truth).abs() < 1e-6 && (td - truth).abs() < 1e-6);
                assert!(((pts[gi as usize] - q).length_squared() - gd).abs() < 1e-6);
                assert!(((pts[ti as usize] - q).length_squared() - td).abs() < 1e-6);
                checked += 1;
            } else if truth > bucket * bucket * 1.001 {
                assert!(g.is_none() && t.is_none());
            }
        }
        assert!(checked > 1000, "{checked}");
        assert!(
            grid.subdivided_buckets() > 0 || bucket < 0.25,
            "dense buckets are cut"
        );
    }
}

#[test]
fn grid_skips_non_finite_points_and_far_queries() {
    let pts = vec![Vec3::ZERO, Vec3::NAN, Vec3::new(1.0, 0.0, 0.0)];
    let grid = BucketGrid::new(&pts, 0.5).expect("grid");
    assert_eq!(grid.len(), 2);
    assert_eq!(
        grid.nearest(Vec3::new(0.9, 0.1, 0.0), 0.5).map(|r| r.0),
        Some(2)
    );
    assert_eq!(grid.nearest(Vec3::new(100.0, 0.0, 0.0), 0.5), None);
    assert_eq!(grid.nearest(Vec3::NAN, 0.5), None);
    let empty = BucketGrid::new(&[], 0.5).expect("empty grid");
    assert!(empty.is_empty());
    assert_eq!(empty.nearest(Vec3::ZERO, 1.0), None);
}

#[test]
fn wide_cloud_is_sparse_but_tiny_buckets_are_refused() {
    // 10 km x 10 km x 20 m in 0.25 m buckets: 1.3e11 buckets in the key space, 2 occupied.
    let pts = vec![Vec3::ZERO, Vec3::new(10_000.0, 10_000.0, 20.0)];
    let grid = BucketGrid::new(&pts, 0.25).expect("10 km wide cloud");
    assert_eq!(grid.occupied_buckets(), 2);
    assert!(matches!(
        BucketGrid::new(&pts, 0.001),
        Err(RegistrationError::InvalidParameter(p)) if p.name == "bucket_size_m"
    ));
    assert!(BucketGrid::new(&pts, 0.0).is_err());
}

#[test]
fn grid_equals_kdtree_within_the_bucket_on_a_laser_scan() {
    let (target, source, truth) = scan_pair(181, 91);
    let start = standard_start(&truth);
    let a = Affine3A::from_mat4(DMat4::from(start).as_mat4());
    let tgt: Vec<Vec3> = target
        .points
        .iter()
        .copied()
        .filter(|p| p.is_finite())
        .collect();
    let queries: Vec<Vec3> = source
        .points
        .iter()
        .filter(|p| p.is_finite())
        .map(|p| a.transform_point3(*p))
        .collect();
    let tree = KdTree::new(&tgt);
    for bucket in [0.1f32, 0.3, 0.5] {
        let grid = BucketGrid::new(&tgt, bucket as f64).expect("grid");
        assert_eq!(grid.len(), tgt.len());
        let mut within = 0;
        let mut last: Option<u32> = None;
        for (k, q) in queries.iter().enumerate() {
            let t = tree.nearest(*q, bucket);
            let g = grid.nearest(*q, bucket);
            // The hinted search (as the registration does it) agrees too.
            let hint = last.map(|j| (j, (tgt[j as usize] - *q).length_squared()));
            let h = grid.nearest_with_hint(*q, bucket, hint);
            match t {
                Some((_, td)) => {
                    within += 1;
                    let (gi, gd) = g.expect("grid finds what the tree finds within a bucket");
                    assert!((gd - td).abs() < 1e-6, "query {k}: grid {gd} tree {td}");
                    assert!(((tgt[gi as usize] - *q).length_squared() - gd).abs() < 1e-6);
                    assert!((h.expect("hinted").1 - td).abs() < 1e-6);
                    last = h.map(|r| r.0);
                }
                None => assert!(g.is_none() && h.is_none()),
            }
        }
        assert!(within > queries.len() / 3, "{within} of {}", queries.len());
    }
    // Brute force on a subset.
    let grid = BucketGrid::new(&tgt, 0.3).expect("grid");
    for q in queries.iter().step_by(97) {
        let brute = tgt
            .iter()
            .map(|p| (*p - *q).length_squared())
            .fold(f32::INFINITY, f32::min);
        if brute < 0.09 {
            let (_, gd) = grid.nearest(*q, 0.3).expect("found");
            assert!((gd - brute).abs() < 1e-6);
        }
    }
}
