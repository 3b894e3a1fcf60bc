//! Regressions of clutter read as structure, on parts of the bench's registered maps run
//! through the whole stage (`build_semantic_map`): what a part needs of the map around it
//! (its floor, ceiling and grid) is in its data file.

use cloud::PointCloud;
use glam::Vec3;
use semantic::{build_semantic_map, EntityClass, SemanticConfig};

/// The points of a data file: `x y z` per line, `#` comments.
fn read_points(text: &str) -> Vec<Vec3> {
    text.lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| {
            let v: Vec<f32> = l
                .split_whitespace()
                .map(|t| t.parse().expect("a number"))
                .collect();
            Vec3::new(v[0], v[1], v[2])
        })
        .collect()
}

/// Regression: fresh hall-391's crate (1.0 x 0.77 m, 1.04 m high) was a partial-height wall
/// 1.27 m long. Too thick for a partition, its front face was looked at as a thin slab; the
/// crate's body beside it, whose highest return was a stray one 0.12 m over its top, was not
/// level with the slab and so no face of its block. What lies beside the slab is as high as
/// where its returns end along most of it.
#[test]
fn stray_returns_over_a_crate_leave_its_front_no_partition() {
    let points = read_points(include_str!("data/hall391_crate_beside_stray_returns.txt"));
    assert_eq!(points.len(), 7084);
    let out = build_semantic_map(&PointCloud::from_points(points), &SemanticConfig::default())
        .expect("map");
    let walls: Vec<_> = out.map.of_class(EntityClass::Wall).collect();
    assert!(walls.is_empty(), "{walls:?}");
    // The crate is an obstacle over its footprint.
    let crate_box = out.map.of_class(EntityClass::Obstacle).find(|e| {
        let [x, y, _] = e.geometry.center_m;
        (x - 8.76).abs() < 0.2 && (y - 15.21).abs() < 0.2 && e.geometry.size_m[0] > 0.9
    });
    assert!(crate_box.is_some(), "{:?}", out.map.entities);
}
