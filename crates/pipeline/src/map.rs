//! The semantic-map stage of the chain: the map of a merged cloud, and its files (the map,
//! the labelled cloud and a picture of every stage).

use crate::error::Result;
use cloud::{EntityClass, PcdEncoding, PointCloud};
use semantic::{MapOutput, SemanticConfig, SemanticMap};
use std::path::Path;

/// The pictures [`write_map`] writes, in order.
pub const MAP_PICTURES: [&str; 8] = [
    "projection.png",
    "filtered.png",
    "dilated.png",
    "skeleton.png",
    "segments.png",
    "merged_segments.png",
    "top_view.png",
    "labels.png",
];

/// The classes a semantic map holds, in the order summaries list them.
const MAP_CLASSES: [EntityClass; 7] = [
    EntityClass::Floor,
    EntityClass::Ceiling,
    EntityClass::Wall,
    EntityClass::WallAboveDoor,
    EntityClass::Door,
    EntityClass::FreeSpaceForDoor,
    EntityClass::Stairs,
];

/// The colour of Hough segments drawn over the stage images.
const SEGMENT_RGB: [u8; 3] = [220, 30, 30];

/// Builds the semantic map of `cloud`.
pub fn build_map(cloud: &PointCloud, cfg: &SemanticConfig) -> Result<MapOutput> {
    Ok(semantic::build_semantic_map(cloud, cfg)?)
}

/// Writes `semantic_map.json`, `labels.pcd` (the cloud labelled by the map) and the pictures
/// of every stage ([`MAP_PICTURES`]) into `out` (which must exist).
pub fn write_map(output: &MapOutput, cloud: &PointCloud, out: &Path) -> Result<()> {
    use semantic::{render_labels, render_segments, render_top_view, save_png};
    output.map.save(&out.join("semantic_map.json"))?;
    cloud::io::pcd::write_pcd(
        &out.join("labels.pcd"),
        &output.labelled_cloud(cloud),
        PcdEncoding::Binary,
    )?;
    let o = output;
    let [projection, filtered, dilated, skeleton, segments, merged, top_view, labels] =
        MAP_PICTURES.map(|name| out.join(name));
    save_png(&projection, o.projection.clone())?;
    save_png(&filtered, o.filtered.clone())?;
    save_png(&dilated, o.dilated.clone())?;
    save_png(&skeleton, o.skeleton.clone())?;
    let red = SEGMENT_RGB;
    save_png(
        &segments,
        render_segments(&o.skeleton, &o.frame, &o.hough_segments, red),
    )?;
    save_png(
        &merged,
        render_segments(&o.projection, &o.frame, &o.merged_segments, red),
    )?;
    save_png(&top_view, render_top_view(&o.map, &o.frame))?;
    save_png(&labels, render_labels(cloud, &o.labels, &o.map, &o.frame))?;
    Ok(())
}

/// One line: the count of each class and the number of relations.
pub fn map_summary(map: &SemanticMap) -> String {
    let counts: Vec<String> = MAP_CLASSES
        .iter()
        .map(|c| format!("{} {}", map.of_class(*c).count(), c.name()))
        .collect();
    format!(
        "entities: {}; {} relations",
        counts.join(", "),
        map.relations.len()
    )
}
