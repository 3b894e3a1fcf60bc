//! Ramps: sloped floors a robot drives up (car-park ramps, wheelchair ramps), found among the
//! points no wall, door or staircase explains, before the obstacles (a ramp is floor to a
//! robot, not something in its way; a slope must be neither an obstacle nor a staircase).
//!
//! 1. The unexplained points between `min_above_floor_m` and `head_height_m` above the floor,
//!    off the walls' slabs, door leaves' swings and staircases' boxes (grown by
//!    `wall_margin_m`: a wall face's noise beside a ramp along it stands over the ramp's
//!    line), in an XY grid of `cell_m` cells; occupied cells (`min_cell_points`) up to `reach_cells`
//!    apart whose tops differ by at most `max_top_step_m` plus the steepest ramp's rise over
//!    the distance form a cluster (a laser's lines on a shallow slope seen from its foot are
//!    decimetres apart).
//! 2. A cluster is a ramp ([`fit::ramp_plane`]) if, uphill on the plane through most of its
//!    cells' tops (RANSAC; snapped onto its footprint rectangle's nearest axis within 10
//!    degrees) or else along one of those axes, its upper profile ([`profile`]: the highest return per bin) rises in a straight line
//!    from near the floor: the ramp's top, or where the top was seen too obliquely to return
//!    (a laser low over a shallow ramp), the top edge of its side face. The line holds most
//!    bins (what stands on the ramp lifts some off it), is as steep as ramps are and no
//!    steeper, and the ramp is long, wide and high enough. A flight of stairs steps off any
//!    line, a car's profile bends, a table's starts high.
//! 3. The ramp's plane runs through that line, level across; its footprint from the floor line
//!    to its highest bin, across the returns on or under the plane. Its points are the
//!    cluster's on or under the plane (within `surface_tolerance_m`) over its footprint (a bin
//!    beyond its head: the head's face); what stands on it, and what the cluster holds beyond
//!    it, is left to the obstacles.

mod config;
mod fit;
mod profile;

pub use config::RampConfig;
use fit::{ramp_plane, RampPlane};

use crate::image_frame::{pixel_center, ImageFrame};
use crate::map::OrientedBox;
use crate::obstacles::{
    components, exclude_boxes, rect_corners, wall_cells, BandGrid, DetectedObstacle,
};
use crate::walls::WallFit;
use cloud::EntityClass;
use glam::{DVec2, Vec3};

/// A ramp found in the cloud.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct DetectedRamp {
    /// Footprint centre, uphill direction and full size along and across it (m).
    pub center: DVec2,
    pub dir: DVec2,
    pub size: [f64; 2],
    /// Floor (at the foot) and head heights.
    pub z_range: (f64, f64),
    /// The fraction of the profile's bins on the ramp's line.
    pub fill: f64,
    /// The ramp's points (indexes into the scene's points).
    pub points: Vec<u32>,
    pub rules: Vec<String>,
}

impl DetectedRamp {
    /// The ramp as the net's obstacles are: class `ramp`, its box rising along `dir`.
    pub fn as_obstacle(&self) -> DetectedObstacle {
        DetectedObstacle {
            class: EntityClass::Ramp,
            center: self.center,
            dir: self.dir,
            size: self.size,
            z_range: self.z_range,
            hull: rect_corners(self.center, self.dir, self.size).to_vec(),
            fill: self.fill,
            support: self.points.len() as u64,
            overhead: false,
            beside_top: false,
            rules: self.rules.clone(),
        }
    }
}

/// Where the stage looks.
pub(crate) struct RampScene<'a> {
    pub points: &'a [Vec3],
    /// Per point: labelled by another entity.
    pub explained: &'a [bool],
    pub floor: f64,
    pub image: &'a ImageFrame,
    pub walls: &'a [WallFit],
    /// Boxes of entities that are no ramp: door leaves' swings and staircases.
    pub keep_out: &'a [OrientedBox],
}

/// Finds the ramps (see the module docs).
pub(crate) fn find_ramps(sc: &RampScene, c: &RampConfig, max_pixels: u64) -> Vec<DetectedRamp> {
    let frame = sc.image.at_cell(c.cell_m, max_pixels);
    // 1. The unexplained points of the band, by cell, and their clusters.
    let (z_lo, z_hi) = (
        (sc.floor + c.min_above_floor_m) as f32,
        (sc.floor + c.head_height_m) as f32,
    );
    let mut excluded = wall_cells(&frame, sc.walls, c.wall_margin_m);
    exclude_boxes(&frame, sc.keep_out, c.wall_margin_m, &mut excluded);
    let mut cell_of = vec![u32::MAX; sc.points.len()];
    let mut members = Vec::new();
    for (i, p) in sc.points.iter().enumerate() {
        if sc.explained[i] || p.z < z_lo || p.z > z_hi {
            continue;
        }
        if let Some((col, row)) = frame.pixel_of(p.x as f64, p.y as f64) {
            let k = row * frame.width_px + col;
            if excluded[k as usize] {
                continue;
            }
            cell_of[i] = k;
            members.push(i as u32);
        }
    }
    let grid = BandGrid::new(&frame, &members, &cell_of);
    let tops = grid.tops(|i| sc.points[i as usize].z);
    // Cells up to `reach_cells` apart join if their tops differ by at most the step plus the
    // steepest ramp's rise over the distance between them.
    let (step, rise_per_cell) = (
        c.max_top_step_m as f32,
        (c.max_pitch_deg.to_radians().tan() * frame.resolution_m) as f32,
    );
    let w = grid.width;
    let occupied = |k: usize| grid.count(k) >= c.min_cell_points;
    let clusters = components(grid.width, grid.height, c.reach_cells, occupied, |a, b| {
        let cells = (a % w).abs_diff(b % w).max((a / w).abs_diff(b / w)) as f32;
        (tops[a] - tops[b]).abs() <= step + rise_per_cell * cells
    });
    // 2-3. The clusters long enough to be ramps, and the ramps among them.
    let mut out = Vec::new();
    for cells in clusters {
        let tops: Vec<(DVec2, f64)> = cells
            .iter()
            .map(|&k| {
                let q = pixel_center(&frame, (k % grid.width) as f64, (k / grid.width) as f64);
                (q, tops[k] as f64)
            })
            .collect();
        let (lo, hi) = tops.iter().fold(
            (DVec2::splat(f64::MAX), DVec2::splat(f64::MIN)),
            |(lo, hi), (q, _)| (lo.min(*q), hi.max(*q)),
        );
        if (hi - lo).length() < c.min_length_m {
            continue;
        }
        let ids: Vec<u32> = cells
            .iter()
            .flat_map(|&k| grid.points(k).iter().copied())
            .collect();
        let pts: Vec<(DVec2, f64)> = ids
            .iter()
            .map(|&i| {
                let p = sc.points[i as usize];
                (DVec2::new(p.x as f64, p.y as f64), p.z as f64)
            })
            .collect();
        if let Some(plane) = ramp_plane(&pts, &tops, sc.floor, c) {
            out.push(ramp_of(&plane, &ids, &pts, c));
        }
    }
    out
}

/// The ramp of a plane: its box, and the cluster's points (`ids`, at `pts`) on or under it.
fn ramp_of(p: &RampPlane, ids: &[u32], pts: &[(DVec2, f64)], c: &RampConfig) -> DetectedRamp {
    let (u0, u1) = p.u_range;
    let (v0, v1) = p.v_range;
    // On or under the plane, and over the footprint (grown by a bin along the slope: the
    // head's face stands at the last bin's end).
    let over = |q: DVec2| {
        let (u, v) = (q.dot(p.dir), q.dot(p.dir.perp()));
        u >= u0 - c.cell_m && u <= u1 + c.cell_m && v >= v0 && v <= v1
    };
    let points: Vec<u32> = ids
        .iter()
        .zip(pts)
        .filter(|(_, (q, z))| *z <= p.z_at(*q) + c.surface_tolerance_m && over(*q))
        .map(|(&i, _)| i)
        .collect();
    let center = p.dir * ((u0 + u1) / 2.0) + p.dir.perp() * ((v0 + v1) / 2.0);
    DetectedRamp {
        center,
        dir: p.dir,
        size: [u1 - u0, v1 - v0],
        z_range: (p.floor, p.floor + p.rise()),
        fill: p.inliers as f64 / p.filled.max(1) as f64,
        rules: vec![format!(
            "ramp: its profile rises {:.1} degrees in a line from the floor ({} of {} bins \
             within {:.1} cm RMS)",
            p.pitch_deg(),
            p.inliers,
            p.filled,
            100.0 * p.rms_m
        )],
        points,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The scene of `points` over a 20 x 12 m image, nothing explained, the floor at 0.
    fn ramps_of(points: &[Vec3]) -> Vec<DetectedRamp> {
        ramps_beside(points, &[])
    }

    /// [`ramps_of`] with `walls`.
    fn ramps_beside(points: &[Vec3], walls: &[WallFit]) -> Vec<DetectedRamp> {
        let explained = vec![false; points.len()];
        let image = ImageFrame {
            origin_m: [-2.0, 10.0],
            resolution_m: 0.05,
            width_px: 400,
            height_px: 240,
        };
        let scene = RampScene {
            points,
            explained: &explained,
            floor: 0.0,
            image: &image,
            walls,
            keep_out: &[],
        };
        find_ramps(&scene, &RampConfig::default(), 1 << 24)
    }

    /// A vertical face under `top(s)` along `a` to `b`, returns every 3 cm.
    fn face(a: DVec2, b: DVec2, top: impl Fn(f64) -> f64) -> Vec<Vec3> {
        let n = (a.distance(b) / 0.03).ceil() as usize;
        let mut out = Vec::new();
        for k in 0..=n {
            let s = k as f64 / n as f64;
            let q = a.lerp(b, s);
            let mut z = 0.0;
            while z <= top(s) {
                out.push(Vec3::new(q.x as f32, q.y as f32, z as f32));
                z += 0.03;
            }
        }
        out
    }

    /// A ramp rising 0.8 m northwards (`0.1 y`) over 8 m from y = 0, 3 m wide (x 4..7), seen
    /// as a low laser sees it: its west side face and its head's face, its top only in a few
    /// rows near its foot.
    fn seen_ramp() -> Vec<Vec3> {
        let mut pts = face(DVec2::new(4.0, 0.0), DVec2::new(4.0, 8.0), |s| 0.8 * s);
        pts.extend(face(DVec2::new(4.0, 8.0), DVec2::new(7.0, 8.0), |_| 0.8));
        for y in [1.0, 1.4, 1.8] {
            for k in 0..100 {
                let x = 4.0 + 0.03 * k as f64;
                pts.push(Vec3::new(x as f32, y as f32, (0.1 * y) as f32));
            }
        }
        pts
    }

    /// [`seen_ramp`] with a crate standing on it.
    #[test]
    fn a_ramp_seen_as_its_side_and_head_faces_is_one_ramp_rising_its_way() {
        let rise = |y: f64| 0.1 * y;
        let mut pts = seen_ramp();
        let crate_top = |_: f64| rise(5.0) + 0.5;
        pts.extend(face(DVec2::new(5.0, 5.0), DVec2::new(5.5, 5.0), crate_top));
        let ramps = ramps_of(&pts);
        assert_eq!(ramps.len(), 1, "{ramps:#?}");
        let r = &ramps[0];
        assert!(r.dir.angle_to(DVec2::Y).abs().to_degrees() < 2.0, "{r:#?}");
        let pitch = (r.z_range.1 - r.z_range.0).atan2(r.size[0]).to_degrees();
        assert!((pitch - 0.1f64.atan().to_degrees()).abs() < 0.3, "{pitch}");
        assert!((r.z_range.1 - 0.8).abs() < 0.04, "{r:#?}");
        assert!(
            (r.size[0] - 8.0).abs() < 0.3 && (r.size[1] - 3.0).abs() < 0.15,
            "{r:#?}"
        );
        // The crate's top is not the ramp's.
        assert!(r
            .points
            .iter()
            .all(|&i| pts[i as usize].z as f64 <= rise(pts[i as usize].y as f64) + 0.1));
    }

    /// Regression (garage-2 of the styles bench): a wall face's noise (returns 4-6 cm off
    /// the face) beside a ramp along the wall joined the ramp's cluster and stood over its
    /// line near the head: there the head was cut 0.3 m short and the ramp widened to the
    /// wall; here, without the wall's margin, no ramp is found at all. Cells within
    /// `wall_margin_m` of a wall's slab are no part of a ramp.
    #[test]
    fn a_wall_faces_noise_beside_a_ramp_does_not_cut_its_head_short() {
        let rise = |y: f64| 0.1 * y;
        let mut pts = seen_ramp();
        // The wall: its face at x = 7.3, 0.3 m east of the ramp; its noise 4-6 cm off it
        // along the ramp's upper 1.5 m and past its head, every 5 cm along, 8-16 cm over the
        // ramp's line (so that its cells join the head's).
        for k in 0..40 {
            let y = 6.5 + 0.05 * k as f64;
            let (x, z) = (
                7.24 + 0.01 * (k % 3) as f64,
                rise(y) + 0.08 + 0.04 * (k % 3) as f64,
            );
            pts.push(Vec3::new(x as f32, y as f32, z as f32));
        }
        let wall = WallFit {
            thickness: 0.2,
            z_range: (0.0, 2.5),
            ..WallFit::one_sided(DVec2::new(7.4, -1.0), DVec2::new(7.4, 10.0), -1.0)
        };
        let ramps = ramps_beside(&pts, &[wall]);
        assert_eq!(ramps.len(), 1, "{ramps:#?}");
        let r = &ramps[0];
        let head = r.center.y + r.size[0] / 2.0;
        assert!((head - 8.0).abs() < 0.15, "head at {head}: {r:#?}");
        assert!((r.z_range.1 - 0.8).abs() < 0.04, "{r:#?}");
        assert!(r.size[1] < 3.15, "{r:#?}");
    }

    /// Regression (garage-224 of the styles bench, seeds 221-225): a ramp along a wall, rising
    /// 1.3 m over 8.4 m, seen by the survey's lasers (0.5 m above the floor) only from 0.44 m
    /// up, over its upper 5.5 m: its line started 0.44 m above the floor, over the 0.4 m a
    /// seat's or a bonnet's edge is told from a ramp's foot by, and the ramp became obstacles.
    /// Here: a ramp rising 0.15 m per metre from y = 0 (8.5 degrees), its side face and top
    /// seen from y = 3.2 on (0.48 m up, over 4.8 m), its head's face at y = 8.
    #[test]
    fn a_long_ramp_seen_only_above_a_low_lasers_height_is_one_ramp_from_its_foot() {
        let rise = |y: f64| 0.15 * y;
        let mut pts = face(DVec2::new(4.0, 3.2), DVec2::new(4.0, 8.0), |s| {
            rise(3.2 + 4.8 * s)
        });
        pts.extend(face(DVec2::new(4.0, 8.0), DVec2::new(7.0, 8.0), |_| 1.2));
        for y in [3.6, 4.4, 5.2, 6.0, 6.8, 7.6] {
            for k in 0..100 {
                let x = 4.0 + 0.03 * k as f64;
                pts.push(Vec3::new(x as f32, y as f32, rise(y) as f32));
            }
        }
        let ramps = ramps_of(&pts);
        assert_eq!(ramps.len(), 1, "{ramps:#?}");
        let r = &ramps[0];
        let foot = r.center.y - r.size[0] / 2.0;
        assert!(foot.abs() < 0.2, "foot at {foot}: {r:#?}");
        assert!((r.z_range.1 - 1.2).abs() < 0.04, "{r:#?}");
    }

    /// A slope as steep as a ramp starting 0.5 m up, seen over 2.5 m (less than
    /// `min_length_high_foot_m`): a thing's sloping top, no ramp, though it rises more than its
    /// start's height.
    #[test]
    fn a_short_slope_starting_high_is_no_ramp() {
        let top = |y: f64| 0.5 + 0.27 * (y - 2.0);
        let mut pts = face(DVec2::new(4.0, 2.0), DVec2::new(4.0, 4.5), |s| {
            top(2.0 + 2.5 * s)
        });
        for y in [2.3, 2.9, 3.5, 4.1] {
            for k in 0..40 {
                let x = 4.0 + 0.03 * k as f64;
                pts.push(Vec3::new(x as f32, y as f32, top(y) as f32));
            }
        }
        let ramps = ramps_of(&pts);
        assert!(ramps.is_empty(), "{ramps:#?}");
    }

    /// A flight of stairs' side face (0.17 m risers, 0.28 m treads), a car's side (bumper,
    /// bonnet, windscreen, roof) and a table's sloping edge 0.7 m up: no ramp.
    #[test]
    fn a_flights_side_a_cars_side_and_a_tables_edge_are_no_ramp() {
        let mut pts = face(DVec2::new(0.0, 0.0), DVec2::new(0.0, 3.0), |s| {
            0.17 * (1.0 + (3.0 * s / 0.28).floor())
        });
        pts.extend(face(DVec2::new(6.0, 0.0), DVec2::new(10.4, 0.0), |s| {
            let x = 4.4 * s;
            match x {
                x if x < 1.0 => 0.6 + 0.15 * x,
                x if x < 1.8 => 0.75 + 0.8 * (x - 1.0),
                x if x < 3.6 => 1.4,
                x => 1.4 - 0.6 * (x - 3.6),
            }
        }));
        pts.extend(face(DVec2::new(6.0, 5.0), DVec2::new(8.0, 5.0), |s| {
            0.7 + 0.1 * s
        }));
        let ramps = ramps_of(&pts);
        assert!(ramps.is_empty(), "{ramps:#?}");
    }
}
