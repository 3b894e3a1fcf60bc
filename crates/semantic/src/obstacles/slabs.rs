//! A partition with things standing against it (see the `obstacles` module, step 7): a desk
//! pushed against a partial-height partition, a chair's back touching it, a cabinet's end a
//! hand's width from it join it in one cluster, far thicker than a partition. The partition is
//! then the thin slab of the cluster's returns that holds the most of them: its two faces from
//! the floor to its top, where a desk holds a top and legs and a chair a seat and a back. What
//! lies on either side of the slab is fitted again as obstacles of their own (whether the slab
//! is a partition, and what lies beside it a desk rather than the rest of a block, is for
//! `partitions` to say).

use super::classify::fit_cluster;
use super::cluster::BandGrid;
use super::{DetectedObstacle, ObstacleConfig, ObstacleScene};
use crate::image_frame::{pixel_center, pixel_range, ImageFrame};
use crate::points::quantile;
use glam::DVec2;
use std::collections::HashSet;

/// The points (indices into the scene) of both bands in `o`'s box, up to its top: what
/// hangs over it in its cells, a beam or a duct, is no part of it.
pub(super) fn points_in_box(
    o: &DetectedObstacle,
    sc: &ObstacleScene,
    grids: [&BandGrid; 2],
    frame: &ImageFrame,
) -> Vec<u32> {
    let half = DVec2::new(o.size[0] / 2.0, o.size[1] / 2.0) + frame.resolution_m / 2.0;
    let reach = DVec2::splat(half.length());
    let Some((c0, c1, r0, r1)) = pixel_range(frame, o.center - reach, o.center + reach) else {
        return Vec::new();
    };
    let w = frame.width_px as usize;
    let mut out = Vec::new();
    for row in r0..=r1 {
        for col in c0..=c1 {
            let q = pixel_center(frame, col as f64, row as f64) - o.center;
            if q.dot(o.dir).abs() > half.x || q.dot(o.dir.perp()).abs() > half.y {
                continue;
            }
            for grid in grids {
                out.extend(grid.points(row * w + col).iter().copied().filter(|&i| {
                    let p = sc.points[i as usize];
                    let q = DVec2::new(p.x as f64, p.y as f64) - o.center;
                    q.dot(o.dir).abs() <= half.x
                        && q.dot(o.dir.perp()).abs() <= half.y
                        && p.z as f64 <= o.z_range.1
                }));
            }
        }
    }
    out
}

/// The slab of `o`'s returns `slab_m` thick (across its box) that holds the most of them,
/// fitted as a cluster of its own, and what lies beyond it on either side (mixed pixels
/// within a cell of its faces left out), each fitted if it holds `min_points`. `None` if the
/// slab holds too few points or `o` is thin already.
pub(super) fn thin_slab(
    o: &DetectedObstacle,
    sc: &ObstacleScene,
    grids: [&BandGrid; 2],
    frame: &ImageFrame,
    c: &ObstacleConfig,
) -> Option<(DetectedObstacle, Vec<DetectedObstacle>)> {
    let slab_m = c.partition_slab_m;
    if o.size[1] <= slab_m {
        return None;
    }
    // 1. The box's returns by their offset across it.
    let across = o.dir.perp();
    let offset = |i: u32| {
        let p = sc.points[i as usize];
        (DVec2::new(p.x as f64, p.y as f64) - o.center).dot(across)
    };
    let mut by_offset: Vec<(f64, u32)> = points_in_box(o, sc, grids, frame)
        .into_iter()
        .map(|i| (offset(i), i))
        .collect();
    by_offset.sort_by(|a, b| a.0.total_cmp(&b.0));
    // 2. The window `slab_m` wide holding the most of them (two pointers over the sorted
    //    offsets).
    let (mut best, mut j) = ((0, 0), 0);
    for i in 0..by_offset.len() {
        while by_offset[i].0 - by_offset[j].0 > slab_m {
            j += 1;
        }
        if i + 1 - j > best.1 - best.0 {
            best = (j, i + 1);
        }
    }
    if best.1 - best.0 < c.min_points {
        return None;
    }
    let (lo, hi) = (by_offset[best.0].0, by_offset[best.1 - 1].0);
    // 3. The slab, and the rest on either side beyond a cell's mixed pixels.
    let margin = frame.resolution_m;
    let slab: Vec<u32> = by_offset[best.0..best.1].iter().map(|p| p.1).collect();
    let below: Vec<u32> = by_offset
        .iter()
        .filter(|p| p.0 < lo - margin)
        .map(|p| p.1)
        .collect();
    let above: Vec<u32> = by_offset
        .iter()
        .filter(|p| p.0 > hi + margin)
        .map(|p| p.1)
        .collect();
    let fit = |members: &[u32]| -> Option<DetectedObstacle> {
        if members.len() < c.min_points {
            return None;
        }
        let cells: HashSet<(u32, u32)> = members
            .iter()
            .filter_map(|&i| {
                let p = sc.points[i as usize];
                frame.pixel_of(p.x as f64, p.y as f64)
            })
            .collect();
        let mut zs: Vec<f64> = members
            .iter()
            .map(|&i| sc.points[i as usize].z as f64)
            .collect();
        let top = zs.iter().copied().fold(f64::MIN, f64::max);
        let bottom = quantile(&mut zs, 0.01).unwrap_or(top);
        fit_cluster(sc, members, cells.len(), (bottom, top), false, frame, c)
    };
    let slab = fit(&slab)?;
    let rest = [below, above].iter().filter_map(|m| fit(m)).collect();
    Some((slab, rest))
}

#[cfg(test)]
mod tests {
    use super::super::backing::floor_seen;
    use super::super::partitions::classify_partition;
    use super::super::{test_cluster, test_scene};
    use super::*;
    use cloud::EntityClass;
    use glam::Vec3;

    /// A vertical face along x from `x0` to `x1` at `y`, from `z0` to `z1`, every 2 cm.
    fn face(x0: f32, x1: f32, y: f32, z0: f32, z1: f32) -> Vec<Vec3> {
        let (nx, nz) = (((x1 - x0) / 0.02) as usize, ((z1 - z0) / 0.02) as usize);
        (0..=nx)
            .flat_map(|i| {
                (0..=nz).map(move |k| Vec3::new(x0 + 0.02 * i as f32, y, z0 + 0.02 * k as f32))
            })
            .collect()
    }

    /// A 6 x 6 m floor every 5 cm; a partition 0.08 m thick and 1.4 m high along x from 1 to
    /// 3 m at y = 2 (both faces); a desk 0.75 m deep against its +y face (its top 0.72 m high
    /// from x `x0` to `x1`, on four legs).
    fn partition_and_desk(x0: f32, x1: f32) -> Vec<Vec3> {
        let mut points: Vec<Vec3> = (0..120)
            .flat_map(|i| (0..120).map(move |j| Vec3::new(0.05 * i as f32, 0.05 * j as f32, 0.0)))
            .collect();
        points.extend(face(1.0, 3.0, 1.96, 0.09, 1.4));
        points.extend(face(1.0, 3.0, 2.04, 0.09, 1.4));
        for i in 0..((x1 - x0) / 0.02) as usize {
            for j in 0..37 {
                points.push(Vec3::new(
                    x0 + 0.02 * i as f32,
                    2.06 + 0.02 * j as f32,
                    0.72,
                ));
            }
        }
        let (l, r) = (x0 + 0.02, x1 - 0.04);
        for (x, y) in [(l, 2.1), (r, 2.1), (l, 2.78), (r, 2.78)] {
            points.extend(face(x, x + 0.04, y, 0.09, 0.7));
        }
        points
    }

    /// The cluster `o` over `points` classified as the stage does (nothing here is above head
    /// height), and what stood against a partition in it.
    fn classified(
        points: &[Vec3],
        mut o: DetectedObstacle,
    ) -> (DetectedObstacle, Vec<DetectedObstacle>) {
        let explained = vec![false; points.len()];
        let image = ImageFrame {
            origin_m: [0.0, 6.0],
            resolution_m: 0.1,
            width_px: 60,
            height_px: 60,
        };
        let sc = test_scene(points, &explained, 3.0, &image, &[]);
        let c = ObstacleConfig::default();
        let mut cell_of = vec![u32::MAX; points.len()];
        let mut low = Vec::new();
        for (i, p) in points.iter().enumerate() {
            if let Some((col, row)) = image.pixel_of(p.x as f64, p.y as f64) {
                if p.z as f64 >= c.min_above_floor_m {
                    cell_of[i] = row * 60 + col;
                    low.push(i as u32);
                }
            }
        }
        let (low_grid, high_grid) = (
            BandGrid::new(&image, &low, &cell_of),
            BandGrid::new(&image, &[], &cell_of),
        );
        let seen = floor_seen(&image, points, 0.0, c.min_above_floor_m);
        let ps = super::super::PartitionScene {
            sc: &sc,
            grids: [&low_grid, &high_grid],
            floor_seen: &seen,
            frame: &image,
            c: &c,
        };
        let rest = classify_partition(&mut o, ps);
        (o, rest)
    }

    #[test]
    fn a_partition_and_the_desk_against_it_in_one_cluster_are_a_wall_and_an_obstacle() {
        // One cluster over both, as the mixed pixels between them joined them on office-2,
        // -62, -73 and -78 (seeds 1-80): 0.9 m thick, no partition.
        let cluster = test_cluster([2.0, 2.4], DVec2::X, [2.1, 0.9], (0.0, 1.4), false);
        let (o, rest) = classified(&partition_and_desk(1.3, 2.5), cluster);
        assert_eq!(o.class, EntityClass::Wall, "{o:?}");
        assert!((o.center.y - 2.0).abs() < 0.03 && o.size[1] < 0.16, "{o:?}");
        assert!((o.size[0] - 2.0).abs() < 0.15, "{o:?}");
        assert_eq!(rest.len(), 1, "{rest:?}");
        let desk = &rest[0];
        assert_eq!(desk.class, EntityClass::Obstacle, "{desk:?}");
        // (Its edge within a cell of the partition's face is left to the mixed pixels.)
        let (near, far) = (
            desk.center.y - desk.size[1] / 2.0,
            desk.center.y + desk.size[1] / 2.0,
        );
        assert!(near < 2.06 + 0.15 && (far - 2.78).abs() < 0.03, "{desk:?}");
        assert!((desk.z_range.1 - 0.72).abs() < 0.03, "{desk:?}");
    }

    /// Regression (office-9 of seeds 1-10: a desk 1.30 m long against a partition 1.56 m
    /// long ran along more of it than what stands against a partition was allowed to, and the
    /// partition was lost as the face of a block). A block's faces end at its top; a desk
    /// ends far below the partition's.
    #[test]
    fn a_desk_nearly_as_long_as_its_partition_is_no_face_of_a_block() {
        let cluster = test_cluster([2.0, 2.4], DVec2::X, [2.1, 0.9], (0.0, 1.4), false);
        let (o, rest) = classified(&partition_and_desk(1.15, 2.85), cluster);
        assert_eq!(o.class, EntityClass::Wall, "{o:?}");
        assert!((o.center.y - 2.0).abs() < 0.03 && o.size[1] < 0.16, "{o:?}");
        assert_eq!(rest.len(), 1, "{rest:?}");
        assert!((rest[0].z_range.1 - 0.72).abs() < 0.03, "{rest:?}");
        assert!(rest[0].size[0] > 0.8 * o.size[0], "{rest:?} {o:?}");
    }

    #[test]
    fn a_person_walking_along_a_partition_is_no_face_of_its_block() {
        // office-175 (seeds 171-175): returns up to 1.75 m that no object of the building
        // explains (a person who walked along it, most likely; the transients filter kept
        // them) ran along all of a partition 1.37 m high, 0.15-0.45 m off it. They and the
        // partition were one cluster 0.56 m thick: taken for the rest of a block, as a crate's
        // other face is, though they rose 0.3 m over the slab's top, where no face of its
        // block reaches.
        let mut points: Vec<Vec3> = (0..120)
            .flat_map(|i| (0..120).map(move |j| Vec3::new(0.05 * i as f32, 0.05 * j as f32, 0.0)))
            .collect();
        points.extend(face(1.0, 3.0, 1.96, 0.09, 1.4));
        points.extend(face(1.0, 3.0, 2.04, 0.09, 1.4));
        points.extend(face(1.0, 3.0, 2.3, 0.09, 1.74));
        let cluster = test_cluster([2.0, 2.13], DVec2::X, [2.0, 0.34], (0.0, 1.74), false);
        let (o, rest) = classified(&points, cluster);
        assert_eq!(o.class, EntityClass::Wall, "{o:?}");
        assert!((o.z_range.1 - 1.4).abs() < 0.03, "{o:?}");
        assert_eq!(rest.len(), 1, "{rest:?}");
        assert!((rest[0].z_range.1 - 1.74).abs() < 0.03, "{rest:?}");
    }

    #[test]
    fn a_crate_is_not_cut_into_a_partition() {
        // hall-2 (seeds 1-10): a crate 1.2 m long, 0.45 m deep and 1.2 m high, its four sides
        // seen, the floor seen all round it (within the half metre a partition's sides are
        // looked at) but not under it. Its long face is a slab standing on the floor, but its
        // other long face runs along all of it: a block, not a partition with a desk.
        let mut points: Vec<Vec3> = (0..120)
            .flat_map(|i| (0..120).map(move |j| Vec3::new(0.05 * i as f32, 0.05 * j as f32, 0.0)))
            .filter(|p| !(p.x > 1.0 && p.x < 2.2 && p.y > 2.0 && p.y < 2.45))
            .collect();
        points.extend(face(1.0, 2.2, 2.0, 0.09, 1.2));
        points.extend(face(1.0, 2.2, 2.45, 0.09, 1.2));
        for x in [1.0, 2.2] {
            for k in 0..=22 {
                for j in 0..=55 {
                    points.push(Vec3::new(x, 2.0 + 0.02 * k as f32, 0.09 + 0.02 * j as f32));
                }
            }
        }
        let cluster = test_cluster([1.6, 2.225], DVec2::X, [1.2, 0.45], (0.0, 1.2), false);
        let (o, rest) = classified(&points, cluster);
        assert_eq!(o.class, EntityClass::Obstacle, "{o:?}");
        assert!(rest.is_empty(), "{rest:?}");
    }
}
