//! The bucket grid against the k-d tree and brute force on a virtual-laser scan.

mod common;

use common::*;
use glam::{Affine3A, DMat4, Vec3};
use registration::*;

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
