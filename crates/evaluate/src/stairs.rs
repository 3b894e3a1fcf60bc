//! Evaluation of staircases (see the crate docs).

use crate::config::EvalConfig;
use crate::score::ClassScore;
use crate::truth::Truth;
use crate::Evaluation;
use cloud::EntityClass;
use glam::DVec2;
use scanner::Building;
use semantic::SemanticMap;
use serde::{Deserialize, Serialize};

/// A matched staircase.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StairsMatch {
    /// The true staircase, e.g. `stairs[0]`.
    pub truth: String,
    /// The map entity.
    pub entity: u32,
    /// True step count.
    pub steps_truth: u32,
    /// Detected step count.
    pub steps: u32,
    /// Detected minus true rise.
    pub rise_error_m: f64,
    /// Detected minus true run.
    pub run_error_m: f64,
    /// Detected minus true width.
    pub width_error_m: f64,
    /// Angle between the directions of ascent.
    pub direction_error_deg: f64,
    /// Distance between the first steps' front-edge centres (in plan).
    pub start_error_m: f64,
    /// Detected minus true height of the flight's foot (a flight starting on a mid landing
    /// stands `base_m` above the floor).
    #[serde(default)]
    pub base_error_m: f64,
}

pub(crate) fn evaluate_stairs(
    ev: &mut Evaluation,
    map: &SemanticMap,
    building: &Building,
    t: &Truth,
    c: &EvalConfig,
) {
    let stairs: Vec<_> = map
        .of_class(EntityClass::Stairs)
        .filter_map(|e| e.stairs.as_ref().map(|s| (e, s)))
        .collect();
    let mut expected = 0;
    let mut used_s = vec![false; stairs.len()];
    for (k, s) in building.stairs.iter().enumerate() {
        let name = format!("stairs[{k}]");
        if t.observed && t.count(&name) < c.min_points {
            continue;
        }
        expected += 1;
        let dir = DVec2::from_angle(s.direction_deg.to_radians());
        let start = t.to_map(s.start_m[0], s.start_m[1], 0.0).truncate();
        let dir_map = (t
            .to_map(s.start_m[0] + dir.x, s.start_m[1] + dir.y, 0.0)
            .truncate()
            - start)
            .normalize_or_zero();
        let centre = start + dir_map * (s.steps as f64 * s.run_m + s.landing_m) / 2.0;
        let best = stairs
            .iter()
            .enumerate()
            .filter(|(i, _)| !used_s[*i])
            .map(|(i, (e, _))| {
                (
                    i,
                    DVec2::new(e.geometry.center_m[0], e.geometry.center_m[1]).distance(centre),
                )
            })
            .filter(|(_, d)| *d <= c.stairs_max_distance_m)
            .min_by(|a, b| a.1.total_cmp(&b.1));
        let Some((i, _)) = best else {
            ev.missed.push(name);
            continue;
        };
        used_s[i] = true;
        let (e, d) = stairs[i];
        ev.stairs_matches.push(StairsMatch {
            truth: name,
            entity: e.id,
            steps_truth: s.steps,
            steps: d.step_count,
            rise_error_m: d.rise_m - s.rise_m,
            run_error_m: d.run_m - s.run_m,
            width_error_m: d.width_m - s.width_m,
            direction_error_deg: DVec2::from_angle(d.direction_deg.to_radians())
                .angle_to(dir_map)
                .abs()
                .to_degrees(),
            start_error_m: DVec2::new(d.start_m[0], d.start_m[1]).distance(start),
            base_error_m: d.start_m[2] - t.to_map(s.start_m[0], s.start_m[1], s.base_m).z,
        });
    }
    for (i, (e, _)) in stairs.iter().enumerate() {
        if !used_s[i] {
            ev.spurious.push(e.id);
        }
    }
    ev.stairs = ClassScore::new(expected, stairs.len(), ev.stairs_matches.len());
}
