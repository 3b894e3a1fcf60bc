//! Obstacles, columns and beams scored against the building's boxes, and the walls a map puts
//! where only beams or pillars stand.
//!
//! Truth objects: the building's boxes, those of one non-empty name that touch joined (a table
//! and its legs are one object; their box is the smallest around all of them in the first box's
//! frame; boxes of one name apart are objects of their own, see `object_groups`). Counted as
//! expected: obstacles (classes furniture, obstacle and column) taller than
//! `obstacle_min_height_m` (0.3 m) and longer than `obstacle_min_across_m` (0.3 m) across;
//! beams and columns of any size; with an observed cloud only those with `min_bin_points` (5)
//! labelled points or more. Detected: the map's obstacles and columns passing the same size
//! test (smaller ones are clutter nobody scores), its columns, its beams.
//!
//! Matching: greedy one-to-one, largest footprint intersection over union first; a pair
//! matches if the footprints' intersection covers at least `obstacle_min_overlap` (0.5) of the
//! smaller footprint (a box fitted to the seen side of a car is smaller than the car, and a
//! car's box is larger than the seen part of it) and their z ranges overlap. The matches
//! record the footprint IoU and the top's height error.
//!
//! Walls on beams or columns: map walls whose centre line lies mostly (over half of it, 5 cm
//! samples) within the footprint, grown by 10 cm, of true beams and columns.

use crate::object_groups::object_groups;
use crate::score::ClassScore;
use crate::truth::Truth;
use crate::{EvalConfig, Evaluation};
use cloud::EntityClass;
use glam::DVec2;
use scanner::Building;
use semantic::{convex_intersection_area, OrientedBox, SemanticMap};
use serde::{Deserialize, Serialize};

/// A matched obstacle, column or beam.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ObstacleMatch {
    /// The truth object's name (or `boxes[i]` for an unnamed box).
    pub truth: String,
    /// Its class in the building.
    pub truth_class: EntityClass,
    /// The map entity's id.
    pub entity: u32,
    /// The map entity's class.
    pub class: EntityClass,
    /// Intersection over union of the footprints.
    pub footprint_iou: f64,
    /// Map top minus true top.
    pub height_error_m: f64,
}

/// A map obstacle or column (over the size limits) that matches no expected object, with what
/// the scans saw inside its box: tells a phantom (mixed pixels, a person's streak, a wall's
/// residue) from a thing split in two or a thing the truth does not count.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UnmatchedObstacle {
    /// The map entity's id.
    pub entity: u32,
    /// Its class.
    pub class: EntityClass,
    /// Its box's size (m).
    pub size_m: [f64; 3],
    /// Observed points inside its box (grown by 2 cm), by true entity name, most first (at
    /// most five); empty without an observed cloud.
    pub seen_inside: Vec<(String, usize)>,
}

/// One truth object: name, class, box, and its boxes' indices.
struct Object {
    name: String,
    class: EntityClass,
    geometry: OrientedBox,
    seen: bool,
}

/// Scores obstacles, columns and beams and counts the walls on beams or columns.
pub(crate) fn evaluate_obstacles(
    ev: &mut Evaluation,
    map: &SemanticMap,
    building: &Building,
    t: &Truth,
    c: &EvalConfig,
) {
    let objects = objects(building, t, c);
    let big = |g: &OrientedBox| {
        g.size_m[2] > c.obstacle_min_height_m
            && g.size_m[0].max(g.size_m[1]) > c.obstacle_min_across_m
    };
    let is_obstacle = |k: EntityClass| {
        matches!(
            k,
            EntityClass::Furniture | EntityClass::Obstacle | EntityClass::Column
        )
    };
    // Obstacles (columns included), then columns and beams on their own.
    let truth: Vec<&Object> = objects
        .iter()
        .filter(|o| o.seen && is_obstacle(o.class) && big(&o.geometry))
        .collect();
    let found: Vec<&semantic::Entity> = map
        .entities
        .iter()
        .filter(|e| matches!(e.class, EntityClass::Obstacle | EntityClass::Column))
        .filter(|e| big(&e.geometry))
        .collect();
    let (score, matches, missed) = match_boxes(&truth, &found, c);
    ev.obstacles_unmatched = found
        .iter()
        .filter(|e| !matches.iter().any(|m| m.entity == e.id))
        .map(|e| UnmatchedObstacle {
            entity: e.id,
            class: e.class,
            size_m: e.geometry.size_m,
            seen_inside: seen_inside(&e.geometry, building, t),
        })
        .collect();
    ev.obstacles = score;
    ev.obstacle_matches = matches;
    ev.missed.extend(missed);
    for (class, slot) in [
        (EntityClass::Column, &mut ev.columns),
        (EntityClass::Beam, &mut ev.beams),
    ] {
        let truth: Vec<&Object> = objects
            .iter()
            .filter(|o| o.seen && o.class == class)
            .collect();
        let found: Vec<&semantic::Entity> = map.of_class(class).collect();
        let (score, matches, missed) = match_boxes(&truth, &found, c);
        *slot = score;
        if class == EntityClass::Beam {
            ev.obstacle_matches.extend(matches);
            ev.missed.extend(missed);
        }
    }
    // Walls where only beams or columns stand.
    let holders: Vec<[DVec2; 4]> = objects
        .iter()
        .filter(|o| matches!(o.class, EntityClass::Beam | EntityClass::Column))
        .map(|o| corners(&grown(&o.geometry, 0.1)))
        .collect();
    ev.walls_on_beams_or_columns = map
        .of_class(EntityClass::Wall)
        .filter(|w| {
            let Some(info) = &w.wall else { return false };
            let (a, b) = (
                DVec2::from_array(info.segment_m[0]),
                DVec2::from_array(info.segment_m[1]),
            );
            let n = ((a.distance(b) / 0.05).ceil() as usize).clamp(1, 100_000);
            let on = (0..=n)
                .filter(|&k| {
                    let q = a.lerp(b, k as f64 / n as f64);
                    holders.iter().any(|h| inside(q, h))
                })
                .count();
            2 * on > n + 1
        })
        .count();
}

/// The observed points inside `b` (grown by 2 cm) by true entity name (a named box's parts
/// under its object's name), most first, at most five.
fn seen_inside(b: &OrientedBox, building: &Building, t: &Truth) -> Vec<(String, usize)> {
    let footprint = corners(&grown(b, 0.02));
    let [z0, z1] = b.z_range_m();
    let object_name = |name: &str| {
        name.strip_prefix("boxes[")
            .and_then(|r| r.strip_suffix(']'))
            .and_then(|i| i.parse::<usize>().ok())
            .and_then(|i| building.boxes.get(i))
            .filter(|b| !b.name.is_empty())
            .map_or_else(|| name.to_string(), |b| b.name.clone())
    };
    let mut counts: Vec<(String, usize)> = Vec::new();
    for (name, points) in t.seen_by_name() {
        let n = points
            .iter()
            .filter(|p| p.z >= z0 - 0.02 && p.z <= z1 + 0.02 && inside(p.truncate(), &footprint))
            .count();
        if n == 0 {
            continue;
        }
        let name = object_name(name);
        match counts.iter_mut().find(|(k, _)| *k == name) {
            Some((_, m)) => *m += n,
            None => counts.push((name, n)),
        }
    }
    counts.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
    counts.truncate(5);
    counts
}

/// The building's boxes as objects (boxes of one name that touch joined, see `object_groups`),
/// in the map frame.
fn objects(building: &Building, t: &Truth, c: &EvalConfig) -> Vec<Object> {
    object_groups(&building.boxes)
        .into_iter()
        .map(|(name, members)| {
            // The box around all members, in the first one's frame, then into the map frame.
            let yaw = building.boxes[members[0]].yaw_deg.to_radians();
            let (d, n) = (DVec2::from_angle(yaw), DVec2::from_angle(yaw).perp());
            let (mut u, mut v, mut z) = (
                [f64::MAX, f64::MIN],
                [f64::MAX, f64::MIN],
                [f64::MAX, f64::MIN],
            );
            for &i in &members {
                let b = &building.boxes[i];
                let g = OrientedBox {
                    center_m: b.center_m,
                    size_m: b.size_m,
                    yaw_deg: b.yaw_deg,
                };
                for p in g.corners_xy() {
                    let q = DVec2::from_array(p);
                    u = [u[0].min(q.dot(d)), u[1].max(q.dot(d))];
                    v = [v[0].min(q.dot(n)), v[1].max(q.dot(n))];
                }
                let [z0, z1] = g.z_range_m();
                z = [z[0].min(z0), z[1].max(z1)];
            }
            let centre = d * (u[0] + u[1]) / 2.0 + n * (v[0] + v[1]) / 2.0;
            let cm = t.to_map(centre.x, centre.y, (z[0] + z[1]) / 2.0);
            let dm = t.to_map(centre.x + d.x, centre.y + d.y, (z[0] + z[1]) / 2.0) - cm;
            let seen = !t.observed || {
                let points: usize = members
                    .iter()
                    .map(|i| t.count(&format!("boxes[{i}]")))
                    .sum();
                points >= c.min_bin_points
            };
            Object {
                name,
                class: building.boxes[members[0]].class,
                geometry: OrientedBox {
                    center_m: cm.to_array(),
                    size_m: [u[1] - u[0], v[1] - v[0], z[1] - z[0]],
                    yaw_deg: dm.y.atan2(dm.x).to_degrees(),
                },
                seen,
            }
        })
        .collect()
}

/// Greedy one-to-one matching by footprint IoU (see the module docs): the score, the matches
/// and the names of the truth objects missed.
fn match_boxes(
    truth: &[&Object],
    found: &[&semantic::Entity],
    c: &EvalConfig,
) -> (ClassScore, Vec<ObstacleMatch>, Vec<String>) {
    let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
    for (i, o) in truth.iter().enumerate() {
        let (ta, tz) = (corners(&o.geometry), o.geometry.z_range_m());
        for (j, e) in found.iter().enumerate() {
            let (fa, fz) = (corners(&e.geometry), e.geometry.z_range_m());
            if tz[0].max(fz[0]) >= tz[1].min(fz[1]) {
                continue;
            }
            let inter = convex_intersection_area(&ta, &fa);
            let (a1, a2) = (area(&ta), area(&fa));
            if inter >= c.obstacle_min_overlap * a1.min(a2) && inter > 0.0 {
                pairs.push((inter / (a1 + a2 - inter).max(1e-12), i, j));
            }
        }
    }
    pairs.sort_by(|a, b| b.0.total_cmp(&a.0));
    let (mut t_used, mut f_used) = (vec![false; truth.len()], vec![false; found.len()]);
    let mut matches = Vec::new();
    for (iou, i, j) in pairs {
        if t_used[i] || f_used[j] {
            continue;
        }
        t_used[i] = true;
        f_used[j] = true;
        matches.push(ObstacleMatch {
            truth: truth[i].name.clone(),
            truth_class: truth[i].class,
            entity: found[j].id,
            class: found[j].class,
            footprint_iou: iou,
            height_error_m: found[j].geometry.z_range_m()[1] - truth[i].geometry.z_range_m()[1],
        });
    }
    let missed = truth
        .iter()
        .zip(&t_used)
        .filter(|(_, u)| !**u)
        .map(|(o, _)| o.name.clone())
        .collect();
    (
        ClassScore::new(truth.len(), found.len(), matches.len()),
        matches,
        missed,
    )
}

fn grown(b: &OrientedBox, by: f64) -> OrientedBox {
    OrientedBox {
        size_m: [b.size_m[0] + 2.0 * by, b.size_m[1] + 2.0 * by, b.size_m[2]],
        ..*b
    }
}

/// The footprint corners of a box (counter-clockwise).
pub(crate) fn corners(b: &OrientedBox) -> [DVec2; 4] {
    b.corners_xy().map(DVec2::from_array)
}

/// The area of a polygon.
pub(crate) fn area(p: &[DVec2]) -> f64 {
    (0..p.len())
        .map(|k| p[k].perp_dot(p[(k + 1) % p.len()]))
        .sum::<f64>()
        .abs()
        / 2.0
}

/// Whether `q` lies inside the convex polygon `p` (counter-clockwise).
fn inside(q: DVec2, p: &[DVec2]) -> bool {
    (0..p.len()).all(|k| (p[(k + 1) % p.len()] - p[k]).perp_dot(q - p[k]) >= 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn intersection_of_overlapping_and_turned_squares() {
        let sq = |c: [f64; 2], s: f64, yaw: f64| {
            corners(&OrientedBox {
                center_m: [c[0], c[1], 0.0],
                size_m: [s, s, 1.0],
                yaw_deg: yaw,
            })
        };
        let (a, b) = (sq([0.0, 0.0], 2.0, 0.0), sq([1.0, 1.0], 2.0, 0.0));
        assert!((convex_intersection_area(&a, &b) - 1.0).abs() < 1e-9);
        assert_eq!(convex_intersection_area(&a, &sq([5.0, 0.0], 1.0, 0.0)), 0.0);
        // A square turned 45 degrees inside a larger one: its whole area.
        let d = sq([0.0, 0.0], 1.0, 45.0);
        assert!((convex_intersection_area(&a, &d) - 1.0).abs() < 1e-9);
    }
}
