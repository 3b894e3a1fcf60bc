//! Tests of `divides`: whether the floor is seen beside a face, going out from it cell by cell,
//! and round a panel's free end.

use super::super::partitions::tests::{classes_in, floor_points, slab};
use super::*;
use cloud::EntityClass;

/// Regression (mixed-462 of seeds 461-465, hall-424 of 421-425): a crate's front (0.55 and
/// 0.78 m deep) read as a partition, the floor seen past the crate's far face counting as seen
/// behind the front, within the half metre looked at. Whoever saw that floor saw the far face
/// first. Here a front along x at y = 2 (0.08 m thick), its far face 0.45 m behind it, the
/// floor seen in front of the front and past the far face only.
#[test]
fn the_floor_seen_past_a_blocks_far_face_is_not_behind_its_front() {
    let frame = ImageFrame {
        origin_m: [0.0, 4.0],
        resolution_m: 0.05,
        width_px: 80,
        height_px: 80,
    };
    let centre =
        |k: usize| crate::image_frame::pixel_center(&frame, (k % 80) as f64, (k / 80) as f64);
    let floor_seen = |k: usize| !(1.95..=2.5).contains(&centre(k).y);
    let far_face = |k: usize| (2.41..=2.5).contains(&centre(k).y);
    let front = DetectedObstacle {
        class: EntityClass::Obstacle,
        center: DVec2::new(2.0, 2.0),
        dir: DVec2::X,
        size: [2.0, 0.08],
        z_range: (0.0, 1.5),
        hull: Vec::new(),
        fill: 1.0,
        support: 500,
        overhead: false,
        beside_top: false,
        rules: Vec::new(),
    };
    let along = bin_centres(&front);
    let beside = |stands: &dyn Fn(usize) -> bool| {
        floor_beside(
            &front,
            |k, j| floor_first(floor_seen(k), stands(k), j),
            &frame,
            BESIDE_M,
            &along,
        )
    };
    // The floor in front (south, the first side) is seen; behind it, the far face stands first.
    assert!(beside(&far_face).iter().all(|s| *s == [true, false]));
    // With nothing standing between, the floor seen 0.45 m behind a panel's face counts.
    assert!(beside(&|_| false).iter().all(|s| *s == [true, true]));
}

/// Regression (office-514 of seeds 511-515): a partition 1.5 m long seen from one side only,
/// from 3 m beyond its free end, was no wall: before its end the floor, far off and at a
/// grazing angle, held too few returns to be seen in every cell. Behind the panel's end the
/// floor is seen (round its end); before it nothing stands. A cabinet's face seen so stays an
/// obstacle: behind its end its body hides the floor.
#[test]
fn a_panel_whose_floor_before_its_end_is_unseen_is_still_a_wall() {
    let panel = slab(1.0, 3.0, 2.0, 0.09, 1.4);
    // The floor hidden behind the panel but round its end, and before its end.
    let unseen = |p: &glam::Vec3, cabinet: bool| {
        let behind = p.x <= if cabinet { 3.05 } else { 2.75 } && (2.05..=4.0).contains(&p.y);
        let before = (2.6..=3.1).contains(&p.x) && (1.65..=1.95).contains(&p.y);
        behind || before
    };
    let found = |cabinet: bool| {
        let mut points = floor_points(None);
        points.retain(|p| !(p.x >= 1.0 && unseen(p, cabinet)));
        points.extend_from_slice(&panel);
        classes_in(&points, &[])
    };
    let panel_found = found(false);
    assert!(
        panel_found
            .iter()
            .any(|(c, why)| *c == EntityClass::Wall && why.contains("seen from one side")),
        "{panel_found:?}"
    );
    let cabinet_found = found(true);
    assert!(
        cabinet_found.iter().all(|(c, _)| *c != EntityClass::Wall),
        "{cabinet_found:?}"
    );
}
