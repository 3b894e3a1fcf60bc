//! Regressions of clutter read as structure, on parts of the bench's registered maps run
//! through the whole stage (`build_semantic_map`): what a part needs of the map around it
//! (its floor, ceiling and grid) is in its data file (`x y z` lines, read as an XYZ cloud).

use semantic::{build_semantic_map, EntityClass, SemanticConfig};
use std::path::Path;

/// Regression: fresh hall-391's crate (1.0 x 0.77 m, 1.04 m high) was a partial-height wall
/// 1.27 m long. Too thick for a partition, its front face was looked at as a thin slab; the
/// crate's body beside it, whose highest return was a stray one 0.12 m over its top, was not
/// level with the slab and so no face of its block. What lies beside the slab is as high as
/// where its returns end along most of it.
#[test]
fn stray_returns_over_a_crate_leave_its_front_no_partition() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/hall391_crate_beside_stray_returns.txt");
    let cloud = cloud::read_cloud(&data).expect("the part's returns");
    assert_eq!(cloud.len(), 7084);
    let out = build_semantic_map(&cloud, &SemanticConfig::default()).expect("map");
    let walls: Vec<_> = out.map.of_class(EntityClass::Wall).collect();
    assert!(walls.is_empty(), "{walls:?}");
    // The crate is an obstacle over its footprint.
    let crate_box = out.map.of_class(EntityClass::Obstacle).find(|e| {
        let [x, y, _] = e.geometry.center_m;
        (x - 8.76).abs() < 0.2 && (y - 15.21).abs() < 0.2 && e.geometry.size_m[0] > 0.9
    });
    assert!(crate_box.is_some(), "{:?}", out.map.entities);
}
