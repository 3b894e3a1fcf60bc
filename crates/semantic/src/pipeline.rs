//! The whole stage: a registered cloud in, the semantic map, per-point labels, the
//! intermediate images and per-stage timings out.

use crate::dilation::{dilate_mask, DilationConfig};
use crate::doors::{find_leaf, DoorConfig};
use crate::error::{Result, SemanticError};
use crate::floor_ceiling::{find_levels, slab_extent, FloorCeilingConfig};
use crate::hough::HoughConfig;
use crate::image_frame::{pixel_center, ImageFrame};
use crate::labels::{label_points, LabelConfig};
use crate::levelling::level_transform;
use crate::map::SemanticMap;
use crate::merge::{merge_segments, MergeConfig, Segment};
use crate::net::{assemble, Detections, NetConfig};
use crate::noise_filter::{filter_mask, NoiseFilterConfig};
use crate::openings::{find_openings, OpeningConfig};
use crate::points::{MapPoints, XyIndex};
use crate::ppht::ppht;
use crate::projection::{frame_for, project, ProjectionConfig};
use crate::skeleton::thin;
use crate::stairs::{find_stairs, StairsConfig};
use crate::walls::{identify_walls, Scene, WallConfig};
use cloud::{Label, PointCloud};
use glam::{DVec2, Vec3};
use image::GrayImage;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::time::Instant;

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
        self.labels.validate()
    }
}

/// How long one stage took.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StageTime {
    /// Stage name (`levelling`, `projection`, `noise_filter`, `dilation`, `skeleton`, `hough`,
    /// `merge`, `walls`, `openings`, `stairs`, `net`, `labels`).
    pub stage: String,
    /// Wall time in milliseconds.
    pub ms: f64,
}

/// Everything [`build_semantic_map`] produces.
#[derive(Debug, Clone)]
pub struct MapOutput {
    /// The semantic map.
    pub map: SemanticMap,
    /// One label per input point (same order; missing returns and points outside the image
    /// are `Label::default()`); `entity` is a map entity id.
    pub labels: Vec<Label>,
    /// Where the images lie in the map frame.
    pub frame: ImageFrame,
    /// The projection image (values 0..1 as 0..255).
    pub projection: GrayImage,
    /// The binary image after the noise filter.
    pub filtered: GrayImage,
    /// ... after the dilation.
    pub dilated: GrayImage,
    /// ... after the skeletonisation.
    pub skeleton: GrayImage,
    /// The Hough segments (map frame).
    pub hough_segments: Vec<Segment>,
    /// The segments after merging (the wall prerequisites).
    pub merged_segments: Vec<Segment>,
    /// Floor height in the map frame, if found.
    pub floor_z_m: Option<f64>,
    /// Ceiling height in the map frame, if found.
    pub ceiling_z_m: Option<f64>,
    /// Tilt of the input's floor plane (levelled away if above `floor_ceiling.min_tilt_deg`).
    pub tilt_deg: f64,
    /// Per-stage wall times.
    pub timings: Vec<StageTime>,
}

impl MapOutput {
    /// Sum of the stage times in milliseconds.
    pub fn total_ms(&self) -> f64 {
        self.timings.iter().map(|t| t.ms).sum()
    }

    /// A copy of `input` carrying the computed labels (replacing any it had).
    pub fn labelled_cloud(&self, input: &PointCloud) -> PointCloud {
        let mut out = input.clone();
        if self.labels.len() == out.len() {
            out.labels = Some(self.labels.clone());
        }
        out
    }
}

/// Drops the wall prerequisites that are door leaves found in an opening (an open leaf stands
/// as tall as a wall in the projection band when the door is nearly as high as the ceiling):
/// those within 10 degrees of the leaf's direction, both ends within 15 cm of its line and no
/// longer than the opening plus 30 cm. Openings are re-indexed.
#[allow(clippy::type_complexity)]
fn drop_leaf_walls(
    walls: Vec<crate::walls::WallFit>,
    openings: Vec<crate::openings::Opening>,
    leaves: Vec<Option<crate::doors::Leaf>>,
) -> (
    Vec<crate::walls::WallFit>,
    Vec<crate::openings::Opening>,
    Vec<Option<crate::doors::Leaf>>,
) {
    let mut drop = vec![false; walls.len()];
    for (o, leaf) in openings.iter().zip(&leaves) {
        let Some(leaf) = leaf else { continue };
        let w = &walls[o.wall];
        let (hinge, into) = if leaf.hinge_start {
            (w.line.at(o.s0), w.line.dir)
        } else {
            (w.line.at(o.s1), -w.line.dir)
        };
        let left = leaf.swing_left == leaf.hinge_start;
        let dir = DVec2::from_angle(leaf.open_deg.to_radians() * if left { 1.0 } else { -1.0 })
            .rotate(into);
        let line = crate::points::Line2 { origin: hinge, dir };
        let width = o.s1 - o.s0;
        for (k, v) in walls.iter().enumerate() {
            let near = [v.start(), v.end()]
                .iter()
                .all(|p| line.coords(*p).1.abs() <= 0.15);
            if k != o.wall
                && near
                && crate::points::undirected_angle_deg(v.line.dir, dir) <= 10.0
                && v.length <= width + 0.3
            {
                drop[k] = true;
            }
        }
    }
    if !drop.iter().any(|&d| d) {
        return (walls, openings, leaves);
    }
    let mut new_index = vec![usize::MAX; walls.len()];
    let mut kept = Vec::new();
    for (k, w) in walls.into_iter().enumerate() {
        if !drop[k] {
            new_index[k] = kept.len();
            kept.push(w);
        }
    }
    let (openings, leaves): (Vec<_>, Vec<_>) = openings
        .into_iter()
        .zip(leaves)
        .filter(|(o, _)| new_index[o.wall] != usize::MAX)
        .map(|(mut o, l)| {
            o.wall = new_index[o.wall];
            (o, l)
        })
        .unzip();
    (kept, openings, leaves)
}

struct Clock {
    t: Instant,
    times: Vec<StageTime>,
}

impl Clock {
    fn lap(&mut self, stage: &str) {
        let now = Instant::now();
        self.times.push(StageTime {
            stage: stage.into(),
            ms: (now - self.t).as_secs_f64() * 1e3,
        });
        self.t = now;
    }
}

/// Builds the semantic map of a registered cloud (metres, z up; missing returns allowed).
///
/// Errors: an invalid configuration, a cloud without finite points, or one too wide for the
/// image cap ([`SemanticError::ImageTooLarge`]). A cloud without walls gives a map without walls.
pub fn build_semantic_map(cloud: &PointCloud, config: &SemanticConfig) -> Result<MapOutput> {
    config.validate()?;
    if cloud.len() >= u32::MAX as usize {
        return Err(SemanticError::InvalidParameter {
            name: "cloud length",
            value: cloud.len() as f64,
            msg: "at most 4 294 967 294 points",
        });
    }
    let mut clock = Clock {
        t: Instant::now(),
        times: Vec::new(),
    };
    let finite: Vec<u32> = (0..cloud.len() as u32)
        .filter(|&i| cloud.points[i as usize].is_finite())
        .collect();
    if finite.is_empty() {
        return Err(SemanticError::EmptyCloud { total: cloud.len() });
    }
    let input: Vec<Vec3> = finite.iter().map(|&i| cloud.points[i as usize]).collect();
    let (map_from_input, tilt_deg) = level_transform(&input, &config.floor_ceiling);
    let rot = glam::Affine3A::from_mat4(glam::DMat4::from(map_from_input).as_mat4());
    let mp = MapPoints {
        points: input.par_iter().map(|p| rot.transform_point3(*p)).collect(),
        input_index: finite,
    };
    let levels = find_levels(&mp, map_from_input, tilt_deg, &config.floor_ceiling);
    clock.lap("levelling");

    let pc = &config.projection;
    let frame = frame_for(&mp.points, pc)?;
    let band = pc.band_z(levels.floor_ref_m, levels.ceiling_ref_m);
    let proj = project(&mp.points, &frame, band, pc);
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

    let lo = DVec2::from_array(frame.to_map(0.0, frame.height_px as f64));
    let hi = DVec2::from_array(frame.to_map(frame.width_px as f64, 0.0));
    let cell = 0.25f64.max((hi - lo).max_element() / 4096.0);
    let (floor_z, ceiling_z) = (levels.floor_ref_m as f32, levels.ceiling_ref_m as f32);
    let (index, (upright, band_index)) = rayon::join(
        || XyIndex::new(&mp.points, lo, hi, cell),
        || {
            rayon::join(
                || {
                    XyIndex::filtered(&mp.points, lo, hi, cell, |p| {
                        (p.z - floor_z).abs() > 0.05 && (p.z - ceiling_z).abs() > 0.05
                    })
                },
                || {
                    XyIndex::filtered(&mp.points, lo, hi, cell, |p| {
                        p.z as f64 >= band.0 && p.z as f64 <= band.1
                    })
                },
            )
        },
    );
    let scene = Scene {
        points: &mp.points,
        index: &index,
        upright: &upright,
        band_index: &band_index,
        floor: levels.floor_ref_m,
        ceiling: levels.ceiling_ref_m,
        band,
        middle: (lo + hi) / 2.0,
    };
    let walls = identify_walls(
        &merged_segments,
        &scene,
        &config.walls,
        config.merge.max_angle_deg,
    );
    clock.lap("walls");
    let face_tol = config.walls.face_tolerance_m;
    let openings: Vec<_> = walls
        .par_iter()
        .enumerate()
        .flat_map_iter(|(i, w)| find_openings(i, w, &scene, &config.openings, face_tol))
        .collect();
    let leaves: Vec<_> = openings
        .par_iter()
        .map(|o| find_leaf(o, &walls[o.wall], &scene, &config.doors, face_tol))
        .collect();
    let (walls, openings, leaves) = drop_leaf_walls(walls, openings, leaves);
    clock.lap("openings");
    let stairs = find_stairs(&scene, &frame, &walls, &config.stairs, pc.max_pixels);
    clock.lap("stairs");

    let slab_yaw = walls
        .iter()
        .max_by(|a, b| a.length.total_cmp(&b.length))
        .map(|w| w.line.angle())
        .unwrap_or(0.0);
    let tol = config.floor_ceiling.surface_tolerance_m;
    let floor_extent = levels
        .floor
        .and_then(|(z, _)| slab_extent(&mp.points, z, tol, slab_yaw));
    let ceiling_extent = levels
        .ceiling
        .and_then(|(z, _)| slab_extent(&mp.points, z, tol, slab_yaw));
    let det = Detections {
        levels,
        floor_extent,
        ceiling_extent,
        slab_yaw,
        slab_thickness: config.floor_ceiling.slab_thickness_m,
        walls,
        openings,
        leaves,
        stairs,
        leaf_thickness: config.doors.leaf_thickness_m,
    };
    let (mut map, ids) = assemble(&det, &config.net);
    clock.lap("net");
    let map_labels = label_points(&mp.points, &index, &det, &ids, &config.labels);
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
    clock.lap("labels");
    Ok(MapOutput {
        map,
        labels,
        frame,
        projection: proj.to_gray(&frame),
        filtered: filtered.to_gray(),
        dilated: dilated.to_gray(),
        skeleton: skeleton.to_gray(),
        hough_segments,
        merged_segments,
        floor_z_m: det.levels.floor.map(|f| f.0),
        ceiling_z_m: det.levels.ceiling.map(|c| c.0),
        tilt_deg: det.levels.tilt_deg,
        timings: clock.times,
    })
}
