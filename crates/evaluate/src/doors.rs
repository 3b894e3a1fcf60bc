//! Evaluation of door openings and leaves (see the crate docs).

use crate::config::EvalConfig;
use crate::score::ClassScore;
use crate::truth::Truth;
use crate::Evaluation;
use cloud::EntityClass;
use glam::DVec2;
use scanner::{Building, Hinge, Swing};
use semantic::Line2;
use semantic::{RelationType, SemanticMap, SwingSide};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// A matched door opening.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DoorMatch {
    /// The true door, e.g. `walls[4].doors[1]`.
    pub truth: String,
    /// The free-space entity.
    pub entity: u32,
    /// Distance between the opening centres.
    pub center_error_m: f64,
    /// Detected minus true width.
    pub width_error_m: f64,
    /// Detected minus true height.
    pub height_error_m: f64,
    /// Whether the building has a leaf there.
    pub leaf_truth: bool,
    /// Whether the map has a door (leaf) there.
    pub leaf_found: bool,
    /// For leaves open at least 10 degrees in truth and found: hinge at the right edge.
    pub hinge_correct: Option<bool>,
    /// ... and swinging to the right side.
    pub swing_correct: Option<bool>,
    /// ... and the opening angle error.
    pub open_angle_error_deg: Option<f64>,
}

/// An expected door opening, in the map frame.
struct TrueDoor {
    name: String,
    center: DVec2,
    width: f64,
    height: f64,
    leaf: Option<(DVec2, DVec2, f64)>, // hinge point, swing side normal, open angle
}

/// The expected door openings (see the crate docs).
fn expected_doors(building: &Building, t: &Truth, c: &EvalConfig) -> Vec<TrueDoor> {
    let mut doors = Vec::new();
    for (i, w) in building.walls.iter().enumerate() {
        let a = t.to_map(w.start_m[0], w.start_m[1], 0.0).truncate();
        let b = t.to_map(w.end_m[0], w.end_m[1], 0.0).truncate();
        let line = Line2::through(a, b);
        for (j, d) in w.doors.iter().enumerate() {
            let name = format!("walls[{i}].doors[{j}]");
            let points = t.count(&format!("{name}.lintel")) + t.count(&format!("{name}.leaf"));
            if t.observed && points < c.min_door_points {
                continue;
            }
            let leaf = d.leaf.as_ref().map(|l| {
                let hinge = line.at(if l.hinge == Hinge::Start {
                    d.offset_m
                } else {
                    d.offset_m + d.width_m
                });
                let side = if l.swing == Swing::Left {
                    line.normal()
                } else {
                    -line.normal()
                };
                (hinge, side, l.open_deg)
            });
            doors.push(TrueDoor {
                name,
                center: line.at(d.offset_m + d.width_m / 2.0),
                width: d.width_m,
                height: d.height_m,
                leaf,
            });
        }
    }
    doors
}

/// Matches the expected door openings with the map's free spaces for doors (greedy, nearest
/// first), and their leaves with the map's doors.
pub(crate) fn evaluate_doors(
    ev: &mut Evaluation,
    map: &SemanticMap,
    building: &Building,
    t: &Truth,
    c: &EvalConfig,
) {
    let doors = expected_doors(building, t, c);
    let free: Vec<_> = map.of_class(EntityClass::FreeSpaceForDoor).collect();
    let leaf_of: HashMap<u32, u32> = map
        .relations_of(RelationType::AvailableInside)
        .filter(|r| {
            map.entity(r.a)
                .is_some_and(|e| e.class == EntityClass::Door)
        })
        .map(|r| (r.b, r.a))
        .collect();
    let mut cands = Vec::new();
    for (ti, t) in doors.iter().enumerate() {
        for (fi, f) in free.iter().enumerate() {
            let dist =
                DVec2::new(f.geometry.center_m[0], f.geometry.center_m[1]).distance(t.center);
            if dist <= c.door_max_distance_m {
                cands.push((dist, ti, fi));
            }
        }
    }
    cands.sort_by(|x, y| x.0.total_cmp(&y.0));
    let (mut used_t, mut used_f) = (vec![false; doors.len()], vec![false; free.len()]);
    let mut leaves_matched = 0;
    for (dist, ti, fi) in cands {
        if used_t[ti] || used_f[fi] {
            continue;
        }
        used_t[ti] = true;
        used_f[fi] = true;
        let (t, f) = (&doors[ti], free[fi]);
        let door = leaf_of.get(&f.id).and_then(|id| map.entity(*id));
        let (mut hinge_ok, mut swing_ok, mut angle_err) = (None, None, None);
        if let (Some((hinge, side, open)), Some(door)) = (t.leaf, door) {
            leaves_matched += 1;
            if let (true, Some(info)) = (open >= 10.0, &door.door) {
                let h = DVec2::new(info.hinge_m[0], info.hinge_m[1]);
                hinge_ok = Some(h.distance(hinge) < t.width / 2.0);
                let dir = DVec2::from_angle(door.geometry.yaw_deg.to_radians());
                let n = if info.swing == SwingSide::Left {
                    dir.perp()
                } else {
                    -dir.perp()
                };
                swing_ok = Some(n.dot(side) > 0.0);
                angle_err = Some(info.observed_open_deg - open);
            }
        }
        let info = f.opening.as_ref();
        ev.door_matches.push(DoorMatch {
            truth: t.name.clone(),
            entity: f.id,
            center_error_m: dist,
            width_error_m: info.map_or(f64::NAN, |o| o.width_m) - t.width,
            height_error_m: info.map_or(f64::NAN, |o| o.height_m) - t.height,
            leaf_truth: t.leaf.is_some(),
            leaf_found: door.is_some(),
            hinge_correct: hinge_ok,
            swing_correct: swing_ok,
            open_angle_error_deg: angle_err,
        });
    }
    for (ti, t) in doors.iter().enumerate() {
        if !used_t[ti] {
            ev.missed.push(t.name.clone());
        }
    }
    for (fi, f) in free.iter().enumerate() {
        if !used_f[fi] {
            ev.spurious.push(f.id);
        }
    }
    ev.door_openings = ClassScore::new(doors.len(), free.len(), ev.door_matches.len());
    let true_leaves = doors.iter().filter(|d| d.leaf.is_some()).count();
    ev.doors = ClassScore::new(
        true_leaves,
        map.of_class(EntityClass::Door).count(),
        leaves_matched,
    );
}
