//! Tests of the mixed pixels' search (`mixed_pixels`).

use super::*;
use cloud::{Organized, Rng};

/// Angular step between beams and between rotation steps (about a SICK LMS's 0.33 deg).
const STEP_RAD: f32 = 0.0058;

/// The unit beam at yaw `yaw` and elevation `el` (radians), x forward, z up.
fn beam(yaw: f32, el: f32) -> Vec3 {
    Vec3::new(el.cos() * yaw.cos(), el.cos() * yaw.sin(), el.sin())
}

/// An organised scan of `rows` rotation steps (yaw from 0) by `cols` beams (elevation from
/// `el0`), each beam's range `range(yaw, el)`, with 1 cm of range noise.
fn scan(rows: usize, cols: usize, el0: f32, range: impl Fn(f32, f32) -> f32) -> PointCloud {
    let mut rng = Rng::new(3);
    let mut points = Vec::new();
    for j in 0..rows {
        for i in 0..cols {
            let (yaw, el) = (j as f32 * STEP_RAD, el0 + i as f32 * STEP_RAD);
            let noise = 0.01 * rng.gaussian() as f32;
            points.push(beam(yaw, el) * (range(yaw, el) + noise));
        }
    }
    let mut cloud = PointCloud::from_points(points);
    cloud.organized = Some(Organized { rows, cols });
    cloud
}

/// A riser 2 m ahead whose top edge is 0.1 m above the sensor, and a wall 4 m ahead.
fn riser_before_wall(_: f32, el: f32) -> f32 {
    let to_riser = 2.0 / el.cos();
    if to_riser * el.sin() < 0.1 {
        to_riser
    } else {
        4.0 / el.cos()
    }
}

/// The riser and the wall in a 5 x 40 grid from 0.05 rad below the sensor's level, one
/// line scan's first beam over the riser's edge coming back from 3 m (between the two
/// surfaces); and that beam's index.
fn riser_scan_with_a_mixed_pixel() -> (PointCloud, usize) {
    let (cols, el0) = (40, -0.05);
    let mut s = scan(5, cols, el0, riser_before_wall);
    let over_edge = (0..cols)
        .find(|&i| 2.0 * (el0 + i as f32 * STEP_RAD).tan() >= 0.1)
        .expect("the edge is in view");
    let k = 2 * cols + over_edge;
    s.points[k] = s.points[k].normalize() * 3.0;
    (s, k)
}

#[test]
fn a_return_between_a_raised_edge_and_the_wall_behind_is_a_mixed_pixel() {
    let (s, k) = riser_scan_with_a_mixed_pixel();
    assert_eq!(find_mixed_pixels(&s, &MixedPixelConfig::default()), vec![k]);
    // Without it, the edge's last and first samples on either surface are no mixed pixels.
    let clean = scan(5, 40, -0.05, riser_before_wall);
    assert!(find_mixed_pixels(&clean, &MixedPixelConfig::default()).is_empty());
    // Filtered, it is a missing return: the grid keeps its shape.
    let (kept, removed) = remove_mixed_pixels(&s, &MixedPixelConfig::default());
    assert_eq!(
        (removed, kept.organized, kept.valid_count()),
        (1, s.organized, s.len() - 1)
    );
}

#[test]
fn a_floor_seen_at_grazing_incidence_is_no_mixed_pixel() {
    // The floor 0.5 m below the sensor from 2.5 m out to 25 m: range steps between beams
    // from 0.07 m to several metres, each sample between its neighbours.
    let (el0, el1) = (-0.2f32, -0.02f32);
    let cols = ((el1 - el0) / STEP_RAD) as usize;
    let s = scan(5, cols, el0, |_, el| 0.5 / (-el).sin());
    assert!(find_mixed_pixels(&s, &MixedPixelConfig::default()).is_empty());
}

#[test]
fn a_thin_pole_in_front_of_a_wall_is_no_mixed_pixel() {
    // One rotation step sees a pole 2 m ahead, its neighbours the wall 4 m ahead.
    let s = scan(5, 20, -0.05, |yaw, el| {
        let pole = (yaw - 2.0 * STEP_RAD).abs() < STEP_RAD / 2.0;
        if pole {
            2.0
        } else {
            4.0 / el.cos()
        }
    });
    assert!(find_mixed_pixels(&s, &MixedPixelConfig::default()).is_empty());
}

#[test]
fn a_grid_too_coarse_for_a_narrow_surface_to_hold_two_samples_is_not_looked_at() {
    let (s, k) = riser_scan_with_a_mixed_pixel();
    assert_eq!(find_mixed_pixels(&s, &MixedPixelConfig::default()), vec![k]);
    // The same grid read as if its beams were 0.1 degree apart at most: neither axis.
    let coarse = MixedPixelConfig {
        max_step_deg: 0.1,
        ..Default::default()
    };
    assert!(find_mixed_pixels(&s, &coarse).is_empty());
}

#[test]
fn an_unorganised_scan_or_a_disabled_filter_finds_none() {
    let (mut s, _) = riser_scan_with_a_mixed_pixel();
    let off = MixedPixelConfig {
        enabled: false,
        ..Default::default()
    };
    assert!(find_mixed_pixels(&s, &off).is_empty());
    s.organized = None;
    assert!(find_mixed_pixels(&s, &MixedPixelConfig::default()).is_empty());
}

#[test]
fn bad_parameters_are_named() {
    for (c, name) in [
        (
            MixedPixelConfig {
                min_gap_m: 0.0,
                ..Default::default()
            },
            "min_gap_m",
        ),
        (
            MixedPixelConfig {
                min_jump_ratio: 0.5,
                ..Default::default()
            },
            "min_jump_ratio",
        ),
        (
            MixedPixelConfig {
                line_tolerance_m: -1.0,
                ..Default::default()
            },
            "line_tolerance_m",
        ),
        (
            MixedPixelConfig {
                line_tolerance_ratio: f64::NAN,
                ..Default::default()
            },
            "line_tolerance_ratio",
        ),
        (
            MixedPixelConfig {
                max_step_deg: 0.0,
                ..Default::default()
            },
            "max_step_deg",
        ),
    ] {
        let e = c.validate().expect_err(name);
        assert!(e.to_string().contains(name), "{e}");
    }
    assert!(MixedPixelConfig::default().validate().is_ok());
}
