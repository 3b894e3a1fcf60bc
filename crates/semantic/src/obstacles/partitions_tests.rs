//! Tests of partial-height walls (`partitions`).

use super::super::{find_obstacles, test_points, test_scene, test_shifted_frame};
use super::*;
use crate::image_frame::ImageFrame;
use glam::Vec3;

/// Both faces of a slab 0.08 m thick along x from `x0` to `x1` at `y`, sampled every 2 cm
/// from `z0` to `z1`.
pub(crate) fn slab(x0: f32, x1: f32, y: f32, z0: f32, z1: f32) -> Vec<Vec3> {
    let mut out = Vec::new();
    let (nx, nz) = (((x1 - x0) / 0.02) as usize, ((z1 - z0) / 0.02) as usize);
    for i in 0..=nx {
        for k in 0..=nz {
            for face in [-0.04, 0.04] {
                out.push(Vec3::new(
                    x0 + i as f32 * 0.02,
                    y + face,
                    z0 + k as f32 * 0.02,
                ));
            }
        }
    }
    out
}

/// The floor of the 8 x 8 m test area sampled every 5 cm, but where `hidden` (x0, y0, x1,
/// y1) covers it.
pub(crate) fn floor_points(hidden: Option<[f32; 4]>) -> Vec<Vec3> {
    let mut out = Vec::new();
    for i in 0..160 {
        for j in 0..160 {
            let (x, y) = (i as f32 * 0.05, j as f32 * 0.05);
            if hidden.is_some_and(|[x0, y0, x1, y1]| x >= x0 && x <= x1 && y >= y0 && y <= y1) {
                continue;
            }
            out.push(Vec3::new(x, y, 0.0));
        }
    }
    out
}

pub(crate) fn classes(points: &[Vec3]) -> Vec<(EntityClass, String)> {
    classes_with_walls(points, &[])
}

/// The classes of what `points` (and the whole floor) hold, with `walls`.
fn classes_with_walls(
    points: &[Vec3],
    walls: &[crate::walls::WallFit],
) -> Vec<(EntityClass, String)> {
    let mut all = floor_points(None);
    all.extend_from_slice(points);
    classes_in(&all, walls)
}

pub(crate) fn classes_in(
    points: &[Vec3],
    walls: &[crate::walls::WallFit],
) -> Vec<(EntityClass, String)> {
    found_in(points, walls)
        .into_iter()
        .map(|o| (o.class, o.rules.last().cloned().unwrap_or_default()))
        .collect()
}

/// What the obstacle stage finds in `points` with `walls`.
fn found_in(points: &[Vec3], walls: &[crate::walls::WallFit]) -> Vec<DetectedObstacle> {
    let explained = vec![false; points.len()];
    let image = ImageFrame {
        origin_m: [0.0, 8.0],
        resolution_m: 0.05,
        width_px: 160,
        height_px: 160,
    };
    let scene = test_scene(points, &explained, 3.0, &image, walls);
    find_obstacles(&scene, &ObstacleConfig::default(), 1 << 20)
}

#[test]
fn a_thin_slab_standing_on_the_floor_is_a_partial_height_wall() {
    let found = classes(&slab(1.0, 3.0, 2.0, 0.09, 1.4));
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].0, EntityClass::Wall, "{found:?}");
    assert!(found[0].1.contains("partial-height wall"), "{found:?}");
}

#[test]
fn a_thin_slab_clear_of_the_floor_or_low_or_short_stays_an_obstacle() {
    for (what, points) in [
        // A car's side: its body 0.25 m above the floor between the wheels.
        ("clear of the floor", slab(1.0, 4.0, 2.0, 0.25, 1.3)),
        // A bench back or a kerb: under the partition height.
        ("low", slab(1.0, 3.0, 2.0, 0.09, 0.8)),
        // As long as it is thick: a post.
        ("short", slab(1.0, 1.3, 2.0, 0.09, 1.4)),
    ] {
        let found = classes(&points);
        assert_eq!(found.len(), 1, "{what}: {found:?}");
        assert_eq!(found[0].0, EntityClass::Obstacle, "{what}: {found:?}");
    }
}

#[test]
fn a_slab_with_gaps_at_the_floor_is_no_wall() {
    // A row of shelves on legs: the face comes down to the floor only at the legs.
    let mut points = slab(1.0, 3.0, 2.0, 0.3, 1.6);
    for x in [1.0, 1.5, 2.0, 2.5, 3.0] {
        points.extend(slab(x, x + 0.04, 2.0, 0.09, 0.3));
    }
    let found = classes(&points);
    assert!(
        found.iter().all(|(c, _)| *c != EntityClass::Wall),
        "{found:?}"
    );
}

#[test]
fn a_slab_along_a_wall_nearer_than_a_passage_is_a_cabinet_front() {
    // A wall along y = 3 (0.15 m thick), x 0..6.
    let wall = |y: f64| crate::walls::WallFit {
        line: crate::points::Line2 {
            origin: DVec2::new(0.0, y),
            dir: DVec2::X,
        },
        length: 6.0,
        thickness: 0.15,
        measured: true,
        faces: vec![-0.075, 0.075],
        free_side: -1.0,
        z_range: (0.0, 3.0),
        support: 1000,
        coverage: 1.0,
        rules: Vec::new(),
    };
    // The front of a 0.45 m deep cabinet against it, and a partition 1.5 m from it.
    let front = slab(1.0, 3.0, 2.5, 0.09, 1.4);
    let found = classes_with_walls(&front, &[wall(3.0)]);
    assert_eq!(found[0].0, EntityClass::Obstacle, "{found:?}");
    let found = classes_with_walls(&front, &[wall(4.0)]);
    assert_eq!(found[0].0, EntityClass::Wall, "{found:?}");
}

#[test]
fn what_hangs_over_a_low_streak_does_not_raise_its_face_to_a_wall() {
    // garage-64 (seeds 61-65): the foot of a person's streak left by the transients filter
    // (0.09-0.4 m along 1.6 m), a few returns up to 1.3 m at one end, under a beam's
    // returns at 2.4-2.6 m. The beam stands in the same cells, over the streak's top: it
    // is no part of the streak's face.
    let mut points = slab(1.0, 2.6, 2.0, 0.09, 0.4);
    points.extend(slab(2.5, 2.56, 2.0, 1.2, 1.3));
    points.extend(slab(1.0, 2.6, 2.0, 2.4, 2.6));
    let found = classes(&points);
    assert!(
        found.iter().all(|(c, _)| *c != EntityClass::Wall),
        "{found:?}"
    );
}

#[test]
fn the_face_of_a_block_is_no_wall() {
    // A crate 1.5 m high seen from its south side only: the floor behind its face, under
    // the crate, was never seen.
    let mut points = floor_points(Some([1.0, 2.0, 3.0, 3.8]));
    points.extend(slab(1.0, 3.0, 2.0, 0.09, 1.5));
    let found = classes_in(&points, &[]);
    assert!(
        found.iter().all(|(c, _)| *c != EntityClass::Wall),
        "{found:?}"
    );
}

#[test]
fn a_panel_seen_from_one_side_and_round_its_free_end_is_a_wall_and_a_block_is_not() {
    // office-107 (seeds 106-110): a partial partition 1.6 m long from a room's far wall,
    // scanned from one side only: the floor behind it lies in its shadow, but round its
    // free end the laser sees it right behind the panel's face.
    let panel = slab(1.0, 3.0, 2.0, 0.09, 1.4);
    let mut points = floor_points(Some([1.0, 2.05, 2.75, 4.0]));
    points.extend_from_slice(&panel);
    let found = classes_in(&points, &[]);
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].0, EntityClass::Wall, "{found:?}");
    assert!(found[0].1.contains("seen from one side"), "{found:?}");
    // office-108: a desk stands beside its free end, on the shadowed side; the floor is seen
    // under the desk's top, between its legs, and nothing stands on it there.
    let mut with_desk = points.clone();
    for i in 0..=40 {
        for j in 0..=35 {
            let (x, y) = (2.6 + i as f32 * 0.02, 2.08 + j as f32 * 0.02);
            with_desk.push(Vec3::new(x, y, 0.73));
            if x >= 2.75 {
                with_desk.push(Vec3::new(x, y, 0.0));
            }
        }
    }
    let found = classes_in(&with_desk, &[]);
    assert!(
        found
            .iter()
            .any(|(c, why)| *c == EntityClass::Wall && why.contains("one side")),
        "{found:?}"
    );
    // A cabinet 0.4 m deep seen from the same side: round its end the floor is seen only
    // beyond its back.
    let mut points = floor_points(Some([1.0, 2.05, 3.05, 2.45]));
    points.retain(|p| !(p.x <= 2.75 && p.y >= 2.45 && p.y <= 4.0));
    points.extend_from_slice(&panel);
    let found = classes_in(&points, &[]);
    assert!(
        found.iter().all(|(c, _)| *c != EntityClass::Wall),
        "{found:?}"
    );
    // A car 1.8 m deep seen from the same side and round its end (the walls_clutter car
    // park): the foot of its end face is seen as low as the floor right behind its side.
    let mut points = floor_points(Some([1.0, 2.05, 3.04, 3.8]));
    points.extend_from_slice(&panel);
    // (The laser's noise spreads the end face 2-3 cm about its plane, and the side's box
    // reaches as far.)
    for j in 0..=85 {
        for k in 0..=70 {
            let x = if (j + k) % 2 == 0 { 2.99 } else { 3.04 };
            points.push(Vec3::new(x, 2.05 + j as f32 * 0.02, k as f32 * 0.02));
        }
    }
    points.extend(slab(3.0, 3.04, 2.0, 0.09, 1.4));
    let found = classes_in(&points, &[]);
    assert!(
        found.iter().all(|(c, _)| *c != EntityClass::Wall),
        "{found:?}"
    );
}

#[test]
fn a_foot_seen_in_every_other_bin_still_stands_on_the_floor() {
    // At range the laser's rows leave 10 cm stretches of a partition's foot without a
    // return here and there: its face stands on the floor all the same.
    let mut points = slab(1.0, 3.0, 2.0, 0.16, 1.4);
    for k in 0..10 {
        let x = 1.0 + 0.2 * k as f32;
        points.extend(slab(x, x + 0.06, 2.0, 0.09, 0.16));
    }
    let found = classes(&points);
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].0, EntityClass::Wall, "{found:?}");
}

/// Regression (office-221 of the styles bench, seeds 221-225): a partition 1.81 m long and
/// 1.29 m high met the room's wall at one end, and 16 mixed pixels between its top edge and
/// that wall, up to 1.75 m, lifted the cluster's top: its face, seen up to 1.29 m, was then
/// nowhere within `max_vertical_gap_m` of "its top", and it stayed an obstacle box 1.73 m
/// high. Its top is where its face ends along most of it.
#[test]
fn a_few_returns_over_a_partitions_end_do_not_lift_its_top() {
    let mut points = slab(1.0, 2.8, 2.0, 0.09, 1.3);
    for k in 0..16 {
        let z = 1.35 + 0.025 * k as f32;
        points.push(Vec3::new(2.75 + 0.003 * (k % 3) as f32, 2.0, z));
    }
    let found = found_in(
        &{
            let mut all = floor_points(None);
            all.extend_from_slice(&points);
            all
        },
        &[],
    );
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].class, EntityClass::Wall, "{found:?}");
    assert!((found[0].z_range.1 - 1.3).abs() < 0.05, "{found:?}");
}

/// A face at `x` across y from `y0` to `y1`, sampled every 2 cm from 0.09 m to `top`.
fn end_at(x: f32, (y0, y1): (f32, f32), top: f32) -> Vec<Vec3> {
    let (ny, nz) = (((y1 - y0) / 0.02) as usize, ((top - 0.09) / 0.02) as usize);
    (0..=ny)
        .flat_map(|j| {
            (0..=nz).map(move |k| Vec3::new(x, y0 + j as f32 * 0.02, 0.09 + k as f32 * 0.02))
        })
        .collect()
}

/// Regression: mixed-344 (seeds 341-345) and mixed-284 (281-285): a tall crate (1.3 m long,
/// 0.4 m deep, 1.45 m high, turned 40 degrees) seen from its front and one end was a
/// partial-height wall: its front the thin slab of a thicker cluster, the seen part of its end
/// what stood against it, and the floor seen behind its back within 0.5 m of the slab. An end
/// face level with the slab's top, across it at its end, is its block's; a desk's side panel
/// across a partition's end is lower.
#[test]
fn a_tall_crate_seen_from_its_front_and_one_end_is_no_wall() {
    // (turned 40 degrees about (3, 3); its front along local x at y = 0, its back at 0.4)
    let (sin, cos) = 40f32.to_radians().sin_cos();
    let turn = |p: Vec3| {
        Vec3::new(
            3.0 + cos * p.x - sin * p.y,
            3.0 + sin * p.x + cos * p.y,
            p.z,
        )
    };
    let under = |p: &Vec3, depth: f32| {
        let q = (p.x - 3.0, p.y - 3.0);
        let (x, y) = (cos * q.0 + sin * q.1, -sin * q.0 + cos * q.1);
        (-0.05..=1.35).contains(&x) && (-0.05..=depth).contains(&y)
    };
    let with = |end_top: f32, depth: f32| -> Vec<(EntityClass, String)> {
        let mut points: Vec<Vec3> = floor_points(None)
            .into_iter()
            .filter(|p| !under(p, depth))
            .collect();
        // (its front: one face, the range noise spreading its returns over 2 cm)
        let front = slab(0.0, 1.3, 0.04, 0.09, 1.45)
            .into_iter()
            .filter(|p| p.y < 0.02);
        points.extend(
            front
                .enumerate()
                .map(|(i, p)| turn(p + Vec3::Y * 0.01 * (i % 3) as f32)),
        );
        points.extend(end_at(0.0, (0.03, 0.39), end_top).into_iter().map(turn));
        classes_in(&points, &[])
    };
    let found = with(1.45, 0.4);
    assert!(
        found.iter().all(|(c, _)| *c != EntityClass::Wall),
        "{found:?}"
    );
    // A partition there with a desk's side panel (0.75 m high) across its end.
    let found = with(0.75, 0.05);
    assert!(
        found.iter().any(|(c, _)| *c == EntityClass::Wall),
        "{found:?}"
    );
}

/// Regression: office-373 (seeds 371-375): a partition 1.36 m high and 1.88 m long with a
/// shelf 1.99 m high across its end, 6 cm from its face, was left an obstacle: the shelf's end
/// face fell in the partition's slab (its other face was seen less) and lifted the slab's top
/// over head height, as an open door leaf's would (on 4 of the 25 grids here; the map's grid was
/// one). The slab's top is where its face ends along most of it.
#[test]
fn a_tall_shelf_across_a_partitions_end_leaves_it_a_wall() {
    let points = test_points(include_str!(
        "../../tests/data/office373_partition_beside_a_shelf.txt"
    ));
    let explained = vec![false; points.len()];
    // Where the grid's cells fall decides which returns a cell holds: the part is mapped on
    // 25 grids, shifted by 1 cm steps.
    for shift in 0..25 {
        let image = test_shifted_frame(shift, 0.01);
        let scene = test_scene(&points, &explained, 2.77, &image, &[]);
        let found = find_obstacles(&scene, &ObstacleConfig::default(), 1 << 20);
        let wall = found
            .iter()
            .find(|o| o.class == EntityClass::Wall)
            .unwrap_or_else(|| panic!("shift {shift}: no partition: {found:?}"));
        // Along the partition (x = 1.39 m, y from 0.37 m), up to its top.
        assert!((wall.center.x - 1.39).abs() < 0.1, "{wall:?}");
        assert!(wall.size[0] > 1.2, "{wall:?}");
        assert!((wall.z_range.1 - 1.36).abs() < 0.08, "{wall:?}");
        // The shelf stays an obstacle of its own.
        assert!(
            found
                .iter()
                .any(|o| o.class == EntityClass::Obstacle && o.z_range.1 > 1.9),
            "{found:?}"
        );
    }
}

/// Regression (office-524 of seeds 521-525, see `MAX_SPARSE_FOOT_BINS`): runs of up to three
/// bins whose foot went unseen where the face is seen sparsely stand with their neighbours; a
/// longer run, one seen densely, or one at an end does not.
#[test]
fn a_sparsely_seen_foot_missing_in_a_short_run_still_stands() {
    let bins = |s: &str| s.chars().map(|c| c == '#').collect::<Vec<bool>>();
    let filled = |s: &str, sparse: bool| fill_foot_gaps(&bins(s), |_| sparse);
    assert_eq!(filled("#.#", false), bins("###"));
    assert_eq!(filled("#...#..#", true), bins("########"));
    assert_eq!(filled("#...#", false), bins("#...#"));
    assert_eq!(filled("#....#", true), bins("#....#"));
    assert_eq!(filled("..##.", true), bins("..##."));
}
