//! Ramps scored against the building's: expected are the building's ramps (with an observed
//! cloud, those with `min_bin_points` labelled returns or more); detected, the map's `ramp`
//! entities. Matching: greedy one-to-one, largest footprint IoU first; a pair matches if the
//! footprints' intersection covers at least `obstacle_min_overlap` (0.5) of the smaller one
//! and the map's ramp rises the same way (its uphill direction within 45 degrees of the
//! true one). The matches record the footprint IoU and the pitch and rise errors.

use crate::obstacles::{area, corners};
use crate::score::ClassScore;
use crate::truth::Truth;
use crate::{EvalConfig, Evaluation};
use cloud::EntityClass;
use glam::DVec2;
use scanner::Building;
use semantic::{convex_intersection_area, OrientedBox, SemanticMap};
use serde::{Deserialize, Serialize};

/// A matched ramp.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RampMatch {
    /// The building's ramp (`ramps[i]`, or its name).
    pub truth: String,
    /// The map entity's id.
    pub entity: u32,
    /// Intersection over union of the footprints.
    pub footprint_iou: f64,
    /// Map pitch minus true pitch (degrees).
    pub pitch_error_deg: f64,
    /// Map rise (head above foot) minus true rise (m).
    pub rise_error_m: f64,
}

/// A true ramp in the map frame: its box (rising along its x axis) and pitch.
struct TrueRamp {
    name: String,
    geometry: OrientedBox,
    pitch_deg: f64,
    seen: bool,
}

/// Scores the map's ramps.
pub(crate) fn evaluate_ramps(
    ev: &mut Evaluation,
    map: &SemanticMap,
    building: &Building,
    t: &Truth,
    c: &EvalConfig,
) {
    let truth: Vec<TrueRamp> = building
        .ramps
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let key = format!("ramps[{i}]");
            let d = DVec2::from_array(r.direction());
            let mid = DVec2::from_array(r.start_m) + d * (r.length_m / 2.0);
            let cm = t.to_map(mid.x, mid.y, r.rise_m / 2.0);
            let dm = t.to_map(mid.x + d.x, mid.y + d.y, r.rise_m / 2.0) - cm;
            TrueRamp {
                name: if r.name.is_empty() {
                    key.clone()
                } else {
                    r.name.clone()
                },
                geometry: OrientedBox {
                    center_m: cm.to_array(),
                    size_m: [r.length_m, r.width_m, r.rise_m],
                    yaw_deg: dm.y.atan2(dm.x).to_degrees(),
                },
                pitch_deg: r.pitch_rad().to_degrees(),
                seen: !t.observed || t.count(&key) >= c.min_bin_points,
            }
        })
        .filter(|r| r.seen)
        .collect();
    let found: Vec<&semantic::Entity> = map.of_class(EntityClass::Ramp).collect();
    let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
    for (i, r) in truth.iter().enumerate() {
        let ta = corners(&r.geometry);
        for (j, e) in found.iter().enumerate() {
            let fa = corners(&e.geometry);
            let inter = convex_intersection_area(&ta, &fa);
            let (a1, a2) = (area(&ta), area(&fa));
            let same_way = (r.geometry.yaw_deg - e.geometry.yaw_deg).to_radians().cos()
                >= 45f64.to_radians().cos();
            if same_way && inter > 0.0 && inter >= c.obstacle_min_overlap * a1.min(a2) {
                pairs.push((inter / (a1 + a2 - inter).max(1e-12), i, j));
            }
        }
    }
    pairs.sort_by(|a, b| b.0.total_cmp(&a.0));
    let (mut t_used, mut f_used) = (vec![false; truth.len()], vec![false; found.len()]);
    for (iou, i, j) in pairs {
        if t_used[i] || f_used[j] {
            continue;
        }
        (t_used[i], f_used[j]) = (true, true);
        let g = &found[j].geometry;
        ev.ramp_matches.push(RampMatch {
            truth: truth[i].name.clone(),
            entity: found[j].id,
            footprint_iou: iou,
            pitch_error_deg: g.size_m[2].atan2(g.size_m[0]).to_degrees() - truth[i].pitch_deg,
            rise_error_m: g.size_m[2] - truth[i].geometry.size_m[2],
        });
    }
    ev.missed.extend(
        truth
            .iter()
            .zip(&t_used)
            .filter(|(_, u)| !**u)
            .map(|(r, _)| r.name.clone()),
    );
    ev.ramps = ClassScore::new(truth.len(), found.len(), ev.ramp_matches.len());
}
