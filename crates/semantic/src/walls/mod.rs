//! Walls: every merged segment is a wall prerequisite (paper, 1.3.2: "for each line segment the
//! orthogonal plane ... is computed; all 3D points which satisfy the condition of distance to
//! [the plane] have the same label"). The vertical plane through the segment gathers the points
//! near it, and the wall is measured from them:
//!
//! 1. Faces: the histogram of the band points' distances to the plane has a peak per observed
//!    face. Each face's points are refitted (total least squares) to correct the Hough angle
//!    quantisation, three times.
//! 2. Free side: a face has free space (floor and ceiling points right in front of it) on one
//!    side and solid wall behind it. Two faces with free space outwards are both sides of one
//!    wall: centre between them, thickness measured. Otherwise only one face was seen: the
//!    centre lies half an assumed thickness behind it (the median measured thickness of the
//!    map's other walls, or `default_thickness_m`).
//! 3. Extent: the face points at every height form runs along the plane; the runs that overlap
//!    the segment (gaps up to `max_gap_m`) give the wall's ends. Where another surface crosses
//!    the plane (points off the faces spread over 15 cm or more across it, within 3 cm along
//!    it: the face of a wall meeting this one), the face points belong to the corner and do
//!    not extend the wall, so a wall ends at the face of the wall it meets.
//! 4. Height: robust z range of the face points, snapped to floor and ceiling; a prerequisite
//!    that does not come down to the floor (`max_bottom_above_floor_m`) or up to the ceiling
//!    (`max_top_below_ceiling_m`) along 30 % of its length is no wall (a beam, a pipe, a door
//!    leaf, a cupboard); one with no free side must reach it as densely as its face lower down
//!    ([`top`]: not through the mixed pixels over a top edge).
//! 5. Support ([`support`]): a wall's face is seen below head height, and nothing is seen
//!    through it there; a prerequisite open underneath along more of its length than it
//!    stands (a beam, a row of pillars, a beam over pillars) is no wall. A wall's end seen
//!    through below head height, its face not seen there but in stray returns, and no corner
//!    there, is cut off: its face ran on along a beam's underside over open floor. (All of a
//!    prerequisite's points near its faces are walked once per extent, [`measure`].)
//! 6. Orientation ([`orientation`]): below head height, the points near its face run along it
//!    in at least half of its 20 cm stretches; a line cut through the corner of a pillar, a
//!    cabinet or a car has the corner's sides crossing its face band instead; the one face a
//!    wall seen from one side keeps runs along it too (a line drawn between a row of pillars'
//!    two rows of faces keeps a face made of the pillars' sides, square to it).
//!
//! Duplicates (the same wall found twice) merge into the longer one. Collinear walls join
//! across a stretch of up to `max_join_gap_m` through which nothing was seen: a wall runs on
//! behind the partitions that meet it and the furniture that hid it ([`joins`]). A wall's
//! ends then move on to its face points glimpsed beyond a stretch of up to
//! `max_glimpse_gap_m` that nobody saw ([`glimpses`]: through the doorway of a room not
//! entered). A stretch no longer than a column is wide that stands free (the floor seen past
//! both ends; or past one, no wall meeting the other and its back seen: [`free_pier`]) is a
//! column, not a wall; so is a row of such stretches, cut where the floor is seen deep in the
//! wall's body with no face in front of it: pillars in a row ([`piers`]). A wall's end more
//! than 0.15 m short of the face of a wall it points at moves on to it across a stretch of up
//! to `max_glimpse_gap_m` nobody saw through ([`corners`]: the corner seen at a grazing angle).
//! Last, every wall must rest on points of its own, not claimed by a longer wall
//! ([`own_points`]: a line across the corner of two walls has none).

mod corners;
mod duplicates;
mod extent;
mod faces;
mod fit;
mod free_pier;
mod glimpses;
mod joins;
mod measure;
mod orientation;
mod own_points;
mod piers;
mod rests;
mod support;
mod top;

use crate::error::Result;
use crate::merge::Segment;
use crate::points::{median, undirected_angle_deg, Line2};
use crate::scene::Scene;
use cloud::check_range;
use corners::extend_to_corners;
use duplicates::merge_duplicates;
use free_pier::is_free_standing_pier;
use glam::DVec2;
use glimpses::extend_to_glimpses;
use joins::merge_through_gaps;
use own_points::retain_walls_with_own_points;
use piers::is_row_of_piers;
use rayon::prelude::*;
use rests::fit_walls_along;
use serde::{Deserialize, Serialize};

/// Configuration of wall identification.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct WallConfig {
    /// Points this far either side of a prerequisite's plane are examined.
    pub search_half_width_m: f64,
    /// Points within this distance of a face lie on it.
    pub face_tolerance_m: f64,
    /// Two faces further apart than this are not one wall.
    pub max_thickness_m: f64,
    /// Two faces nearer than this are one face.
    pub min_thickness_m: f64,
    /// Thickness assumed for walls seen from one side when no wall of the map was measured.
    pub default_thickness_m: f64,
    /// Shorter walls are dropped.
    pub min_length_m: f64,
    /// Fewer face points and the prerequisite is dropped.
    pub min_face_points: usize,
    /// Largest gap between face points along one wall.
    pub max_gap_m: f64,
    /// Wall bottoms and tops this near the floor and ceiling are snapped to them.
    pub snap_m: f64,
    /// A wall must come down to this height above the floor.
    pub max_bottom_above_floor_m: f64,
    /// ... and reach up to this depth under the ceiling along 30 % of its length at least (a
    /// cupboard does not; a prerequisite that turns out to be a door leaf is dropped later).
    pub max_top_below_ceiling_m: f64,
    /// Collinear walls this far apart are one wall if nothing was seen through the gap.
    pub max_join_gap_m: f64,
    /// A wall's end moves on to its face points glimpsed beyond a gap this wide at most
    /// through which nothing was seen (e.g. through a doorway of a room not entered), and on to
    /// the face of the wall it points at across such a gap (a corner seen at a grazing angle).
    pub max_glimpse_gap_m: f64,
    /// Walls whose lines are this near (and directions within `merge.max_angle_deg`) and that
    /// overlap are one wall.
    pub duplicate_offset_m: f64,
}

impl Default for WallConfig {
    fn default() -> Self {
        WallConfig {
            search_half_width_m: 0.35,
            face_tolerance_m: 0.03,
            max_thickness_m: 0.5,
            min_thickness_m: 0.05,
            default_thickness_m: 0.2,
            min_length_m: 0.5,
            min_face_points: 30,
            max_gap_m: 0.35,
            snap_m: 0.15,
            max_bottom_above_floor_m: 1.5,
            max_top_below_ceiling_m: 0.3,
            max_join_gap_m: 2.0,
            max_glimpse_gap_m: 1.5,
            duplicate_offset_m: 0.15,
        }
    }
}

impl WallConfig {
    pub(crate) fn validate(&self) -> Result<()> {
        check_range(
            "walls.search_half_width_m",
            self.search_half_width_m,
            0.01,
            10.0,
            "within 0.01..10 m",
        )?;
        check_range(
            "walls.face_tolerance_m",
            self.face_tolerance_m,
            1e-3,
            1.0,
            "within 0.001..1 m",
        )?;
        check_range(
            "walls.max_thickness_m",
            self.max_thickness_m,
            0.01,
            10.0,
            "within 0.01..10 m",
        )?;
        check_range(
            "walls.min_thickness_m",
            self.min_thickness_m,
            0.0,
            self.max_thickness_m,
            "within 0..max_thickness_m",
        )?;
        check_range(
            "walls.default_thickness_m",
            self.default_thickness_m,
            0.01,
            10.0,
            "within 0.01..10 m",
        )?;
        check_range(
            "walls.min_length_m",
            self.min_length_m,
            0.0,
            1e4,
            "within 0..10 km",
        )?;
        check_range(
            "walls.max_gap_m",
            self.max_gap_m,
            0.0,
            100.0,
            "within 0..100 m",
        )?;
        check_range("walls.snap_m", self.snap_m, 0.0, 10.0, "within 0..10 m")?;
        check_range(
            "walls.max_bottom_above_floor_m",
            self.max_bottom_above_floor_m,
            0.0,
            100.0,
            "within 0..100 m",
        )?;
        check_range(
            "walls.max_top_below_ceiling_m",
            self.max_top_below_ceiling_m,
            0.0,
            100.0,
            "within 0..100 m",
        )?;
        check_range(
            "walls.max_join_gap_m",
            self.max_join_gap_m,
            0.0,
            100.0,
            "within 0..100 m",
        )?;
        check_range(
            "walls.max_glimpse_gap_m",
            self.max_glimpse_gap_m,
            0.0,
            100.0,
            "within 0..100 m",
        )?;
        check_range(
            "walls.duplicate_offset_m",
            self.duplicate_offset_m,
            0.0,
            10.0,
            "within 0..10 m",
        )?;
        Ok(())
    }
}

/// A measured wall.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct WallFit {
    /// Centre line; `origin` is the wall's start, `at(length)` its end.
    pub line: Line2,
    pub length: f64,
    pub thickness: f64,
    pub measured: bool,
    /// Observed faces' offsets from the centre line (left positive).
    pub faces: Vec<f64>,
    /// For a one-sided wall: the side (+1 left, -1 right) of the free space in front of its face.
    pub free_side: f64,
    pub z_range: (f64, f64),
    pub support: u64,
    pub coverage: f64,
    pub rules: Vec<String>,
}

impl WallFit {
    pub fn start(&self) -> DVec2 {
        self.line.origin
    }

    pub fn end(&self) -> DVec2 {
        self.line.at(self.length)
    }
}

/// Floor points (z = 0) at the centres of a 5 cm grid of `cells.0` x `cells.1` cells from `min`,
/// where `solid` is false (the stage's tests).
#[cfg(test)]
pub(crate) fn test_floor(
    min: (f64, f64),
    cells: (usize, usize),
    solid: impl Fn(f64, f64) -> bool,
) -> Vec<glam::Vec3> {
    let mut points = Vec::new();
    for i in 0..cells.0 {
        for j in 0..cells.1 {
            let (x, y) = (
                min.0 + i as f64 * 0.05 + 0.025,
                min.1 + j as f64 * 0.05 + 0.025,
            );
            if !solid(x, y) {
                points.push(glam::Vec3::new(x as f32, y as f32, 0.0));
            }
        }
    }
    points
}

#[cfg(test)]
impl WallFit {
    /// A wall seen from one side (thickness not yet resolved), its face from `from` to `to`,
    /// the free space on `free_side` (+1 left, -1 right), 3 m tall (tests).
    pub fn one_sided(from: DVec2, to: DVec2, free_side: f64) -> WallFit {
        WallFit {
            line: Line2::through(from, to),
            length: from.distance(to),
            thickness: 0.0,
            measured: false,
            faces: Vec::new(),
            free_side,
            z_range: (0.0, 3.0),
            support: 100,
            coverage: 1.0,
            rules: Vec::new(),
        }
    }
}

/// Measures every prerequisite and returns the walls, duplicates merged, thickness of
/// one-sided walls resolved.
pub(crate) fn identify_walls(
    segments: &[Segment],
    sc: &Scene,
    c: &WallConfig,
    max_angle_deg: f64,
) -> Vec<WallFit> {
    // A prerequisite lying inside a longer one's slab (a wall's other face, a skeleton spur) would
    // only find the same wall again: skip it.
    let mut order: Vec<&Segment> = segments.iter().collect();
    order.sort_by(|a, b| b.length_m().total_cmp(&a.length_m()));
    let mut unique: Vec<&Segment> = Vec::new();
    for s in order {
        let inside = unique.iter().any(|u| {
            let line = u.line();
            let reach = c.duplicate_offset_m + c.max_thickness_m / 2.0;
            undirected_angle_deg(line.dir, s.line().dir) <= max_angle_deg
                && [s.a(), s.b()].iter().all(|p| {
                    let (t, d) = line.coords(*p);
                    d.abs() <= reach && t >= -0.3 && t <= u.length_m() + 0.3
                })
        });
        if !inside {
            unique.push(s);
        }
    }
    let walls: Vec<WallFit> = unique
        .par_iter()
        .flat_map_iter(|s| fit_walls_along(s, sc, c))
        .collect();
    let mut kept = merge_duplicates(walls, c, max_angle_deg, "a duplicate prerequisite");
    merge_through_gaps(&mut kept, sc, c, max_angle_deg);
    extend_to_glimpses(&mut kept, sc, c);
    // Two pieces of one wall whose ends moved on to the same glimpsed face points overlap now.
    let mut kept = merge_duplicates(kept, c, max_angle_deg, "the collinear wall its end reached");
    // A pillar's face standing free (the floor seen past both ends, or past one with its back
    // seen and no wall meeting the other) is a column.
    let piers: Vec<bool> = kept
        .iter()
        .map(|w| is_free_standing_pier(w, &kept, sc, c.face_tolerance_m))
        .collect();
    let mut pier = piers.into_iter();
    kept.retain(|_| !pier.next().unwrap_or(false));
    // Pillars in a row, the floor seen between them where a wall's body would hide it, too.
    kept.retain(|w| !is_row_of_piers(w, sc, c.face_tolerance_m));
    let mut measured: Vec<f64> = kept
        .iter()
        .filter(|w| w.measured)
        .map(|w| w.thickness)
        .collect();
    let assumed = median(&mut measured).unwrap_or(c.default_thickness_m);
    // A wall ending short of the wall it runs into, the stretch between unseen, meets it.
    extend_to_corners(&mut kept, sc, c, assumed);
    for w in &mut kept {
        if !w.measured {
            // The line is the face; the centre lies half a thickness behind it.
            w.line = w.line.shifted(-w.free_side * assumed / 2.0);
            w.faces = vec![w.free_side * assumed / 2.0];
            w.thickness = assumed;
            w.rules.push(format!(
                "one face seen: centre {:.3} m behind it (assumed thickness {:.3} m, the median of the measured walls or the default)",
                assumed / 2.0,
                assumed
            ));
        }
    }
    kept.retain(|w| w.length >= c.min_length_m);
    // Every wall rests on points of its own (not a line across two walls' corner).
    retain_walls_with_own_points(&mut kept, sc, c.face_tolerance_m);
    kept
}
