//! Tests of the semantic map file (`map`).

use super::*;
use std::path::Path;

#[test]
fn box_along_a_segment() {
    let b = OrientedBox::along([0.0, 0.0], [0.0, 2.0], 0.2, [0.0, 2.5]);
    assert!((b.yaw_deg - 90.0).abs() < 1e-9);
    assert_eq!(b.size_m, [2.0, 0.2, 2.5]);
    let c = b.corners_xy();
    assert!((c[0][0] - 0.1).abs() < 1e-9 && c[0][1].abs() < 1e-9);
    assert_eq!(b.z_range_m(), [0.0, 2.5]);
}

#[test]
fn default_map_round_trips_and_its_frame_is_identity() {
    let m = SemanticMap::default();
    let back = SemanticMap::from_json_str(&m.to_json_string(), Path::new("x")).expect("valid");
    assert_eq!(back, m);
    assert_eq!(m.input_from_map(), DAffine3::IDENTITY);
}
