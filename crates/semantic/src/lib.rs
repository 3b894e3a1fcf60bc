//! Semantic maps for semsim: from a registered point cloud of a building to walls, floor,
//! ceiling, doors and stairs with their relations (Będkowski & Masłowski 2009, section 1.3).
//! (Scoring such a map against the building it was scanned in is the `evaluate` crate's.)
//!
//! # Stages (one module each, one config section each in [`SemanticConfig`])
//! 1. Levelling, floor and ceiling ([`FloorCeilingConfig`]): the floor plane is fitted and
//!    levelled, floor and ceiling heights come from a z histogram.
//! 2. Localisation, as the paper's Fig. 3: the XY projection image of a height band under the
//!    ceiling ([`ProjectionConfig`]), the 8-neighbour noise filter ([`noise_filter`]),
//!    dilation ([`dilate`]), skeletonisation ([`skeletonize`], Zhang-Suen thinning), the
//!    progressive probabilistic Hough transform ([`hough_lines_p`], as OpenCV's `HoughLinesP`)
//!    and merging of collinear segments ([`MergeConfig`]): the wall prerequisites.
//! 3. Identification: walls from the points near each prerequisite's vertical plane
//!    ([`WallConfig`]); door openings, lintels ([`OpeningConfig`]) and leaves ([`DoorConfig`]);
//!    staircases from level regions of a height map ([`StairsConfig`]); per-point labels.
//! 4. The semantic net ([`NetConfig`]): entities with ids, oriented boxes, support, confidence
//!    and rules; relations (parallel, orthogonal, above, under, equal height, available inside,
//!    connected via joint, near) computed from the geometry.
//! 5. Ramps ([`RampConfig`]): sloped planes of the points no entity labelled that meet the
//!    floor; then obstacles, columns and beams ([`ObstacleConfig`]): what the points no entity
//!    labelled occupy, clustered on an XY grid per height band (below and above head height),
//!    each an oriented box; added to the net and the labels.
//!
//! [`build_semantic_map`] runs them all and returns a [`MapOutput`]: the [`SemanticMap`]
//! (versioned JSON, `schema/semantic_map.schema.json`), per-point labels, the intermediate
//! images and per-stage timings. Entity classes are the workspace's one vocabulary,
//! [`EntityClass`] (re-exported from `cloud`); a map holds the [`MAP_CLASSES`] only.
//!
//! # Confidence
//! Walls: the fraction of their length with face points (x 0.85 if only one face was seen).
//! Door openings and lintels: the fraction of the opening with a lintel above (times the
//! see-through fraction for one-sided walls). Doors: the leaf's covered fraction. Stairs: found
//! levels over steps. Floor and ceiling: 1. Obstacles, columns and beams: `n / (n + 50)` for
//! `n` points.
//!
//! ```
//! use cloud::PointCloud;
//! use glam::Vec3;
//! use semantic::{build_semantic_map, EntityClass, SemanticConfig};
//!
//! // A 6 m x 4 m room, 2.6 m high: floor, ceiling and four walls, points every 4 cm.
//! let mut pts = Vec::new();
//! let (w, d, h) = (6.0f32, 4.0f32, 2.6f32);
//! let step = 0.04f32;
//! for i in 0..=(w / step) as i32 {
//!     for j in 0..=(d / step) as i32 {
//!         let (x, y) = (i as f32 * step, j as f32 * step);
//!         pts.push(Vec3::new(x, y, 0.0));
//!         pts.push(Vec3::new(x, y, h));
//!     }
//! }
//! for k in 0..=(h / step) as i32 {
//!     let z = k as f32 * step;
//!     for i in 0..=(w / step) as i32 {
//!         pts.push(Vec3::new(i as f32 * step, 0.0, z));
//!         pts.push(Vec3::new(i as f32 * step, d, z));
//!     }
//!     for j in 0..=(d / step) as i32 {
//!         pts.push(Vec3::new(0.0, j as f32 * step, z));
//!         pts.push(Vec3::new(w, j as f32 * step, z));
//!     }
//! }
//! let out = build_semantic_map(&PointCloud::from_points(pts), &SemanticConfig::default()).unwrap();
//! assert_eq!(out.map.of_class(EntityClass::Wall).count(), 4);
//! assert_eq!(out.map.of_class(EntityClass::Floor).count(), 1);
//! assert!((out.ceiling_z_m.unwrap() - 2.6).abs() < 0.01);
//! let text = out.map.to_json_string();
//! assert!(text.contains("\"format\": \"semsim.semantic_map\""));
//! ```

#![warn(missing_docs)]

mod dilation;
mod doors;
mod error;
mod floor_ceiling;
mod hough;
mod image_frame;
mod labels;
mod map;
mod merge;
mod net;
mod noise_filter;
mod obstacles;
mod pipeline;
mod points;
mod projection;
mod ramps;
mod render;
mod scene;
mod skeleton;
mod stairs;
#[cfg(test)]
mod test_rng;
mod walls;

pub use cloud::EntityClass;
pub use dilation::{dilate, DilationConfig};
pub use doors::{DoorConfig, OpeningConfig};
pub use error::{Result, SemanticError};
pub use floor_ceiling::FloorCeilingConfig;
pub use hough::{hough_lines_p, HoughConfig, HoughParams, PixelSegment, Unvote};
pub use image_frame::ImageFrame;
pub use labels::LabelConfig;
pub use map::{
    DoorInfo, Entity, FloorInfo, HingeEdge, ObstacleInfo, OpeningInfo, OrientedBox, Relation,
    RelationType, SemanticMap, StairsInfo, SwingSide, WallInfo, MAP_CLASSES, MAP_CLASSES_V1,
    MAP_FORMAT, MAP_VERSION, READ_VERSIONS,
};
pub use merge::{MergeConfig, Segment};
pub use net::NetConfig;
pub use noise_filter::{noise_filter, NoiseFilterConfig};
pub use obstacles::{convex_intersection_area, ObstacleConfig};
pub use pipeline::{build_semantic_map, MapOutput, SemanticConfig, StageTime};
pub use points::{undirected_angle_deg, Line2};
pub use projection::{HeightBand, ProjectionConfig, ProjectionValue};
pub use ramps::RampConfig;
pub use render::{class_color, render_labels, render_segments, render_top_view, save_png};
pub use skeleton::skeletonize;
pub use stairs::StairsConfig;
pub use walls::WallConfig;
