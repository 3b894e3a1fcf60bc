//! Helpers shared by the map-file tests (`map_file.rs`, `map_file_versions.rs`): the semantic
//! map of the built-in default building, built once per test binary.

use semantic::{build_semantic_map, SemanticConfig, SemanticMap};
use std::sync::OnceLock;

/// The map of the built-in default building (walls, doors, lintels, free space, stairs).
pub fn default_map() -> &'static SemanticMap {
    static MAP: OnceLock<SemanticMap> = OnceLock::new();
    MAP.get_or_init(|| {
        let b = scanner::Building::default_building().expect("built-in building");
        let g = scanner::BuildingGeometry::new(&b);
        let cloud = fixtures::scan_building(
            &b,
            &fixtures::survey_poses(&b, &g),
            &fixtures::test_laser(),
            0.03,
        );
        build_semantic_map(&cloud, &SemanticConfig::default())
            .expect("map")
            .map
    })
}
