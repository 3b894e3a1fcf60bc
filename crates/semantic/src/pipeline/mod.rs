//! The whole stage: a registered cloud in, the semantic map, per-point labels, the
//! intermediate images and per-stage timings out.

mod identified;
mod output;

pub use output::{MapOutput, StageTime};

use crate::dilation::{dilate_mask, DilationConfig};
use crate::doors::{find_doors, DoorConfig, Doorways, OpeningConfig};
use crate::error::{Result, SemanticError};
use crate::floor_ceiling::{
    find_levels, floor_footprint, level_transform, slab_extent, FloorCeilingConfig, Levels,
};
use crate::hough::{ppht, HoughConfig};
use crate::image_frame::{pixel_center, ImageFrame, Mask};
use crate::labels::{label_obstacles, LabelConfig};
use crate::map::SemanticMap;
use crate::merge::{merge_segments, MergeConfig, Segment};
use crate::net::{add_obstacles, Detections, NetConfig};
use crate::noise_filter::{filter_mask, NoiseFilterConfig};
use crate::obstacles::{find_obstacles, ObstacleConfig, ObstacleScene};
use crate::points::MapPoints;
use crate::projection::{frame_for, project, Projection, ProjectionConfig};
use crate::ramps::RampConfig;
use crate::scene::SceneIndexes;
use crate::skeleton::thin;
use crate::stairs::{find_stairs, DetectedStairs, StairsConfig};
use crate::walls::{identify_walls, WallConfig};
use cloud::{Label, PointCloud};
use identified::{identify_net_and_ramps, Identified};
use output::Clock;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// The most points a cloud may have (point indexes are `u32`, one value kept free).
const MAX_POINTS: usize = u32::MAX as usize - 1;

/// The configuration of every stage, one section each (TOML/JSON: `[projection]`, `[hough]`, ...).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SemanticConfig {
    /// Levelling, floor and ceiling.
    pub floor_ceiling: FloorCeilingConfig,
    /// The XY projection image.
    pub projection: ProjectionConfig,
    /// The 8-neighbour noise filter.
    pub noise_filter: NoiseFilterConfig,
    /// The dilation.
    pub dilation: DilationConfig,
    /// The progressive probabilistic Hough transform.
    pub hough: HoughConfig,
    /// Merging collinear segments.
    pub merge: MergeConfig,
    /// Walls.
    pub walls: WallConfig,
    /// Door openings and lintels.
    pub openings: OpeningConfig,
    /// Door leaves.
    pub doors: DoorConfig,
    /// Staircases.
    pub stairs: StairsConfig,
    /// The semantic net's relations.
    pub net: NetConfig,
    /// Per-point labels.
    pub labels: LabelConfig,
    /// Obstacles, columns and beams.
    pub obstacles: ObstacleConfig,
    /// Ramps.
    pub ramps: RampConfig,
}

impl SemanticConfig {
    /// Checks every stage's values.
    pub fn validate(&self) -> Result<()> {
        self.floor_ceiling.validate()?;
        self.projection.validate()?;
        self.noise_filter.validate()?;
        self.dilation.validate()?;
        self.hough.validate()?;
        self.merge.validate()?;
        self.walls.validate()?;
        self.openings.validate()?;
        self.doors.validate()?;
        self.stairs.validate()?;
        self.net.validate()?;
        self.labels.validate()?;
        self.obstacles.validate()?;
        self.ramps.validate()
    }
}

/// Builds the semantic map of a registered cloud (metres, z up; missing returns allowed).
///
/// Errors: an invalid configuration, a cloud without finite points, or one too wide for the
/// image cap ([`SemanticError::ImageTooLarge`]). A cloud without walls gives a map without walls.
pub fn build_semantic_map(cloud: &PointCloud, config: &SemanticConfig) -> Result<MapOutput> {
    config.validate()?;
    check_size(cloud)?;
    let mut clock = Clock::start();
    // 1. Levelling: the finite points turned so that the floor is level; floor and ceiling
    //    heights from the z histogram.
    let (mp, levels) = level(cloud, &config.floor_ceiling)?;
    clock.lap("levelling");
    // 2. Localisation (the paper's Fig. 3): projection image, noise filter, dilation,
    //    skeleton, Hough segments, merged into the wall prerequisites.
    let loc = localise(&mp.points, &levels, config, &mut clock)?;
    // 3. Identification, in the scene of the indexed points: walls, then door openings and
    //    leaves, then staircases.
    let indexes = SceneIndexes::build(
        &mp.points,
        &loc.frame,
        levels.floor_ref_m,
        levels.ceiling_ref_m,
        loc.band,
    );
    let scene = indexes.scene(&mp.points);
    let walls = identify_walls(
        &loc.merged_segments,
        &scene,
        &config.walls,
        config.merge.max_angle_deg,
    );
    clock.lap("walls");
    let face_tol = config.walls.face_tolerance_m;
    let doorways = find_doors(walls, &scene, &config.openings, &config.doors, face_tol);
    clock.lap("openings");
    let pc = &config.projection;
    let stairs = find_stairs(
        &scene,
        &loc.frame,
        &doorways.walls,
        &config.stairs,
        pc.max_pixels,
    );
    clock.lap("stairs");
    // 4-6a. The semantic net, the labels and the ramps; a staircase on a ramp is dropped
    //    (the ramp's side face read as steps) and they are made again without it.
    let mut det = detections(&mp.points, levels, doorways, stairs, config);
    let Identified {
        mut map,
        ids,
        mut map_labels,
        keep_out,
        ramps,
    } = identify_net_and_ramps(
        &mut det,
        &mp.points,
        &indexes.index,
        &loc.frame,
        config,
        &mut clock,
    );
    // 6b. Obstacles, columns and beams: what the points no entity labelled occupy; added to
    //    the net (with their relations) and to the labels.
    let mut explained: Vec<bool> = map_labels.iter().map(|l| l.entity != 0).collect();
    for r in &ramps {
        for &i in &r.points {
            explained[i as usize] = true;
        }
    }
    let (floor_z, ceiling_z) = (det.levels.floor_ref_m, det.levels.ceiling_ref_m);
    let obstacle_scene = ObstacleScene {
        points: &mp.points,
        explained: &explained,
        floor: floor_z,
        ceiling: ceiling_z,
        image: &loc.frame,
        walls: &det.walls,
        keep_out: &keep_out,
    };
    let obstacles = find_obstacles(&obstacle_scene, &config.obstacles, pc.max_pixels);
    let ramp_boxes: Vec<_> = ramps.iter().map(|r| r.as_obstacle()).collect();
    let ramp_ids = add_obstacles(&mut map, &ids, floor_z, &ramp_boxes, &config.net);
    for (r, &id) in ramps.iter().zip(&ramp_ids) {
        for &i in &r.points {
            map_labels[i as usize] = Label {
                entity: id,
                class: cloud::EntityClass::Ramp,
            };
        }
    }
    let obstacle_ids = add_obstacles(&mut map, &ids, floor_z, &obstacles, &config.net);
    label_obstacles(
        &indexes.index,
        &obstacles,
        &obstacle_ids,
        &mut map_labels,
        &config.labels,
    );
    clock.lap("obstacles");
    // 7. Labels in input order, and each entity's support.
    let labels = label_input(cloud, &mp, &map_labels, &mut map);
    Ok(MapOutput {
        map,
        labels,
        projection: loc.projection.to_gray(&loc.frame),
        filtered: loc.filtered.to_gray(),
        dilated: loc.dilated.to_gray(),
        skeleton: loc.skeleton.to_gray(),
        frame: loc.frame,
        hough_segments: loc.hough_segments,
        merged_segments: loc.merged_segments,
        floor_z_m: det.levels.floor.map(|f| f.0),
        ceiling_z_m: det.levels.ceiling.map(|c| c.0),
        tilt_deg: det.levels.tilt_deg,
        timings: clock.times,
    })
}

/// A cloud's points are indexed by `u32`: at most [`MAX_POINTS`].
fn check_size(cloud: &PointCloud) -> Result<()> {
    if cloud.len() > MAX_POINTS {
        return Err(cloud::InvalidParameter {
            name: "cloud length".into(),
            value: cloud.len() as f64,
            msg: "at most 4 294 967 294 points".into(),
        }
        .into());
    }
    Ok(())
}

/// The finite points of `cloud` levelled into the map frame, and the floor and ceiling.
fn level(cloud: &PointCloud, c: &FloorCeilingConfig) -> Result<(MapPoints, Levels)> {
    let finite: Vec<u32> = (0..cloud.len() as u32)
        .filter(|&i| cloud.points[i as usize].is_finite())
        .collect();
    if finite.is_empty() {
        return Err(SemanticError::EmptyCloud { total: cloud.len() });
    }
    let input: Vec<glam::Vec3> = finite.iter().map(|&i| cloud.points[i as usize]).collect();
    let (map_from_input, tilt_deg) = level_transform(&input, c);
    let rot = glam::Affine3A::from_mat4(glam::DMat4::from(map_from_input).as_mat4());
    let mp = MapPoints {
        points: input.par_iter().map(|p| rot.transform_point3(*p)).collect(),
        input_index: finite,
    };
    let levels = find_levels(&mp, map_from_input, tilt_deg, c);
    Ok((mp, levels))
}

/// What the localisation found: the images of each step and the wall prerequisites.
struct Localisation {
    frame: ImageFrame,
    /// The projection band (z range, map frame).
    band: (f64, f64),
    projection: Projection,
    filtered: Mask,
    dilated: Mask,
    skeleton: Mask,
    hough_segments: Vec<Segment>,
    merged_segments: Vec<Segment>,
}

/// The localisation of the paper's Fig. 3, one lap of `clock` per step.
fn localise(
    points: &[glam::Vec3],
    levels: &Levels,
    config: &SemanticConfig,
    clock: &mut Clock,
) -> Result<Localisation> {
    let pc = &config.projection;
    let frame = frame_for(points, pc)?;
    let band = pc.band_z(levels.floor_ref_m, levels.ceiling_ref_m);
    let proj = project(points, &frame, band, pc);
    clock.lap("projection");
    let filtered = filter_mask(&proj.binary, config.noise_filter.min_neighbours);
    clock.lap("noise_filter");
    let dilated = dilate_mask(&filtered, config.dilation.radius_px(pc.resolution_m));
    clock.lap("dilation");
    let skeleton = thin(&dilated);
    clock.lap("skeleton");
    let params = config.hough.params(pc.resolution_m);
    let mask: Vec<u8> = skeleton.data.iter().map(|&v| u8::from(v)).collect();
    let pixel_segments = ppht(mask, skeleton.width, skeleton.height, &params);
    let hough_segments: Vec<Segment> = pixel_segments
        .iter()
        .map(|s| Segment {
            a_m: pixel_center(&frame, s.a[0] as f64, s.a[1] as f64).to_array(),
            b_m: pixel_center(&frame, s.b[0] as f64, s.b[1] as f64).to_array(),
        })
        .collect();
    clock.lap("hough");
    let merged_segments = merge_segments(&hough_segments, &config.merge);
    clock.lap("merge");
    Ok(Localisation {
        projection: proj,
        frame,
        band,
        filtered,
        dilated,
        skeleton,
        hough_segments,
        merged_segments,
    })
}

/// Everything identified, with the floor's footprint and the ceiling's extent (turned along the
/// longest wall).
fn detections(
    points: &[glam::Vec3],
    levels: Levels,
    doorways: Doorways,
    stairs: Vec<DetectedStairs>,
    config: &SemanticConfig,
) -> Detections {
    let Doorways {
        walls,
        openings,
        leaves,
    } = doorways;
    let slab_yaw = walls
        .iter()
        .max_by(|a, b| a.length.total_cmp(&b.length))
        .map(|w| w.line.angle())
        .unwrap_or(0.0);
    let tol = config.floor_ceiling.surface_tolerance_m;
    let floor_footprint = levels
        .floor
        .and_then(|(z, _)| floor_footprint(points, z, slab_yaw, &config.floor_ceiling));
    let ceiling_extent = levels
        .ceiling
        .and_then(|(z, _)| slab_extent(points, z, tol, slab_yaw));
    Detections {
        levels,
        floor_footprint,
        ceiling_extent,
        slab_yaw,
        slab_thickness: config.floor_ceiling.slab_thickness_m,
        walls,
        openings,
        leaves,
        stairs,
        leaf_thickness: config.doors.leaf_thickness_m,
    }
}

/// One label per input point (the map points' `map_labels`, the rest `Label::default()`), and
/// each entity's support: how many points carry its id.
fn label_input(
    cloud: &PointCloud,
    mp: &MapPoints,
    map_labels: &[Label],
    map: &mut SemanticMap,
) -> Vec<Label> {
    let mut labels = vec![Label::default(); cloud.len()];
    let mut support = std::collections::HashMap::<u32, u64>::new();
    for (l, &i) in map_labels.iter().zip(&mp.input_index) {
        labels[i as usize] = *l;
        if l.entity != 0 {
            *support.entry(l.entity).or_default() += 1;
        }
    }
    for e in &mut map.entities {
        e.support_points = support.get(&e.id).copied().unwrap_or(0);
    }
    labels
}
