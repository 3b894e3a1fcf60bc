//! The obstacles, columns and beams in the semantic net: one entity each (the box fitted to its
//! points, its hull and clearance; a partial-height wall found among them is a wall of one
//! solid box), and their relations: every one `available_inside` the floor
//! (the floor's space holds it); an obstacle or column `above` the floor (and the floor `under`
//! it), a beam `under` the ceiling (and the ceiling `above` it); and `near` every door's free
//! space whose footprint lies within `near_m` of its own.

use super::{Ids, NetConfig};
use crate::map::{
    Entity, ObstacleInfo, OrientedBox, Relation, RelationType, SemanticMap, WallInfo,
};
use crate::obstacles::DetectedObstacle;
use cloud::EntityClass;
use glam::DVec2;

/// Adds the obstacles to `map` (ids after the largest one there) with their relations, and
/// returns their ids in order.
pub(crate) fn add_obstacles(
    map: &mut SemanticMap,
    ids: &Ids,
    floor_z: f64,
    obstacles: &[DetectedObstacle],
    c: &NetConfig,
) -> Vec<u32> {
    let first = map.entities.iter().map(|e| e.id).max().unwrap_or(0) + 1;
    let openings: Vec<(u32, [[f64; 2]; 4])> = ids
        .openings
        .iter()
        .filter_map(|o| map.entity(o.0).map(|e| (o.0, e.geometry.corners_xy())))
        .collect();
    let mut out = Vec::new();
    for (id, o) in (first..).zip(obstacles) {
        let geometry = box_of(o);
        let support = o.support as f64;
        // A partial-height wall is a wall (one solid box); the rest carry their hull.
        let is_wall = o.class == EntityClass::Wall;
        let half = o.dir * (o.size[0] / 2.0);
        map.entities.push(Entity {
            id,
            class: o.class,
            geometry,
            support_points: 0,
            // More points, more certainty: half at 50 points, 0.95 at ~1000.
            confidence: (support / (support + 50.0)).clamp(0.0, 1.0),
            rules: o.rules.clone(),
            wall: is_wall.then(|| WallInfo {
                segment_m: [(o.center - half).to_array(), (o.center + half).to_array()],
                thickness_m: o.size[1],
                thickness_measured: true,
                z_range_m: [o.z_range.0, o.z_range.1],
                solid_boxes: vec![geometry],
            }),
            door: None,
            opening: None,
            stairs: None,
            obstacle: (!is_wall).then(|| ObstacleInfo {
                z_range_m: [o.z_range.0, o.z_range.1],
                clearance_m: o.z_range.0 - floor_z,
                hull_m: o.hull.iter().map(|q| q.to_array()).collect(),
                fill: o.fill.clamp(0.0, 1.0),
            }),
            floor: None,
        });
        let mut relate = |kind, a, b| {
            if a != 0 && b != 0 {
                map.relations.push(Relation { kind, a, b });
            }
        };
        relate(RelationType::AvailableInside, id, ids.floor);
        if o.class == EntityClass::Beam {
            relate(RelationType::Under, id, ids.ceiling);
            relate(RelationType::Above, ids.ceiling, id);
        } else {
            relate(RelationType::Above, id, ids.floor);
            relate(RelationType::Under, ids.floor, id);
        }
        let corners = geometry.corners_xy();
        for (free, fc) in &openings {
            if footprint_distance(&corners, fc) <= c.near_m {
                relate(RelationType::Near, id, *free);
            }
        }
        out.push(id);
    }
    out
}

/// The box of a detected obstacle.
pub(crate) fn box_of(o: &DetectedObstacle) -> OrientedBox {
    let (z0, z1) = o.z_range;
    OrientedBox {
        center_m: [o.center.x, o.center.y, (z0 + z1) / 2.0],
        size_m: [o.size[0], o.size[1], (z1 - z0).max(0.0)],
        yaw_deg: o.dir.y.atan2(o.dir.x).to_degrees(),
    }
}

/// The distance between two convex footprints (0 if they overlap): the least distance of a
/// corner of one from an edge of the other.
fn footprint_distance(a: &[[f64; 2]; 4], b: &[[f64; 2]; 4]) -> f64 {
    let pa: Vec<DVec2> = a.iter().map(|p| DVec2::from_array(*p)).collect();
    let pb: Vec<DVec2> = b.iter().map(|p| DVec2::from_array(*p)).collect();
    if pa.iter().any(|p| inside(*p, &pb)) || pb.iter().any(|p| inside(*p, &pa)) {
        return 0.0;
    }
    let mut d = f64::INFINITY;
    for (pts, poly) in [(&pa, &pb), (&pb, &pa)] {
        for p in pts.iter() {
            for k in 0..poly.len() {
                d = d.min(segment_distance(*p, poly[k], poly[(k + 1) % poly.len()]));
            }
        }
    }
    d
}

/// Whether `p` lies inside the convex polygon `poly` (counter-clockwise).
fn inside(p: DVec2, poly: &[DVec2]) -> bool {
    (0..poly.len()).all(|k| (poly[(k + 1) % poly.len()] - poly[k]).perp_dot(p - poly[k]) >= 0.0)
}

fn segment_distance(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + ab * t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn footprint_distance_of_apart_and_overlapping_boxes() {
        let a = OrientedBox::along([0.0, 0.0], [1.0, 0.0], 1.0, [0.0, 1.0]).corners_xy();
        let b = OrientedBox::along([2.5, 0.0], [3.0, 0.0], 1.0, [0.0, 1.0]).corners_xy();
        assert!((footprint_distance(&a, &b) - 1.5).abs() < 1e-9);
        let c = OrientedBox::along([0.5, 0.0], [3.0, 0.0], 0.2, [0.0, 1.0]).corners_xy();
        assert_eq!(footprint_distance(&a, &c), 0.0);
    }
}
