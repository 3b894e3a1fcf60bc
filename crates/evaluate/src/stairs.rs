//! Evaluation of staircases (see the crate docs).

use crate::config::EvalConfig;
use crate::score::ClassScore;
use crate::truth::Truth;
use crate::Evaluation;
use cloud::EntityClass;
use glam::{DVec2, DVec3};
use scanner::{Building, Staircase};
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

/// How much of a true staircase the scans saw: the steps with at least `min_step_points`
/// labelled returns on their tread, their riser, or the top edge of their side (a flight seen
/// from the side shows its steps' heights in the top edge of its side faces). A step nobody
/// saw cannot be counted by any map, so a flight with `steps_seen < steps` tells a miscount
/// the scans caused from one the map made.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StairsSeen {
    /// The true staircase, e.g. `stairs[0]`.
    pub truth: String,
    /// True step count.
    pub steps: u32,
    /// Steps the scans saw.
    pub steps_seen: u32,
}

/// How far a return may lie from a tread's or riser's true plane and still be on it (m): the
/// realistic laser's range noise and mixed pixels at a step's nose.
const ON_STEP_M: f64 = 0.04;
/// How far below a step's tread a return on its side face still shows the step's height (m).
const SIDE_TOP_M: f64 = 0.08;

/// The steps of `s` with at least `min_points` of `points` (building frame) on them: within
/// [`ON_STEP_M`] of riser `k`'s plane, above tread `k - 1` and up to tread `k`; within
/// [`ON_STEP_M`] of tread `k`'s height, from riser `k` to riser `k + 1`; or on the flight's side
/// face there, up to [`SIDE_TOP_M`] under tread `k`.
pub(crate) fn steps_seen(s: &Staircase, points: &[DVec3], min_points: usize) -> u32 {
    let (sin, cos) = s.direction_deg.to_radians().sin_cos();
    let steps = s.steps as usize;
    let tread = |k: usize| (k + 1) as f64 * s.rise_m;
    let mut on_step = vec![0usize; steps];
    for p in points {
        let (dx, dy) = (p.x - s.start_m[0], p.y - s.start_m[1]);
        let along = dx * cos + dy * sin;
        let across = (-dx * sin + dy * cos).abs();
        let up = p.z - s.base_m;
        if across > s.width_m / 2.0 + ON_STEP_M || along < -ON_STEP_M {
            continue;
        }
        let k = (along / s.run_m).floor().max(0.0) as usize;
        let step = if across > s.width_m / 2.0 - ON_STEP_M {
            // On the side face: its top edge over step k.
            (k < steps && up <= tread(k) + ON_STEP_M && up >= tread(k) - SIDE_TOP_M).then_some(k)
        } else {
            // On riser k (or k + 1, just in front of it), or on tread k.
            let riser = [k, k + 1].into_iter().find(|&r| {
                (along - r as f64 * s.run_m).abs() <= ON_STEP_M
                    && up > r as f64 * s.rise_m + ON_STEP_M
                    && up <= tread(r) + ON_STEP_M
            });
            riser.or((k < steps && (up - tread(k)).abs() <= ON_STEP_M).then_some(k))
        };
        if let Some(i) = step.filter(|&i| i < steps) {
            on_step[i] += 1;
        }
    }
    on_step.iter().filter(|&&n| n >= min_points).count() as u32
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
        if t.observed {
            let seen: Vec<DVec3> = t
                .points(&name)
                .map(|ps| ps.iter().map(|&p| t.to_building(p)).collect())
                .unwrap_or_default();
            ev.stairs_seen.push(StairsSeen {
                truth: name.clone(),
                steps: s.steps,
                steps_seen: steps_seen(s, &seen, c.min_step_points),
            });
        }
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A 4-step flight along +y from (1, 2), 0.18 m rise, 0.3 m run, 1 m wide, on a 0.5 m
    /// landing.
    fn flight() -> Staircase {
        Staircase {
            name: String::new(),
            start_m: [1.0, 2.0],
            direction_deg: 90.0,
            steps: 4,
            rise_m: 0.18,
            run_m: 0.3,
            width_m: 1.0,
            landing_m: 0.5,
            base_m: 0.5,
        }
    }

    /// `n` returns at `(across, along, up)` of the flight (building frame).
    fn at(s: &Staircase, across: f64, along: f64, up: f64, n: usize) -> Vec<DVec3> {
        let p = DVec3::new(s.start_m[0] - across, s.start_m[1] + along, s.base_m + up);
        vec![p; n]
    }

    #[test]
    fn steps_are_seen_on_their_treads_risers_and_the_top_edge_of_their_sides() {
        let s = flight();
        let mut points = Vec::new();
        // Step 0: its tread; step 1: its riser, 2 cm of noise in front of it; step 3: its
        // tread only at its back edge.
        points.extend(at(&s, 0.2, 0.15, 0.18, 5));
        points.extend(at(&s, -0.3, 0.28, 0.3, 5));
        points.extend(at(&s, 0.0, 1.19, 0.72, 5));
        // Step 2: its side face low down (which step's height it shows is unknown), and too
        // few on its tread.
        points.extend(at(&s, 0.5, 0.75, 0.2, 50));
        points.extend(at(&s, 0.1, 0.75, 0.54, 4));
        assert_eq!(steps_seen(&s, &points, 5), 3);
        // Four returns on tread 2 are glimpses; five are a step seen.
        points.extend(at(&s, 0.1, 0.75, 0.55, 1));
        assert_eq!(steps_seen(&s, &points, 5), 4);
        // The top edge of step 2's side face (5 cm under its tread) shows it too.
        let mut side = points[..15].to_vec();
        assert_eq!(steps_seen(&s, &side, 5), 3);
        side.extend(at(&s, -0.51, 0.8, 0.49, 5));
        assert_eq!(steps_seen(&s, &side, 5), 4);
    }

    #[test]
    fn a_return_on_the_tread_below_a_riser_is_not_on_the_riser() {
        let s = flight();
        // At the foot of riser 2: on tread 1 (0.36 m up), not on riser 2 (0.36 to 0.54 m).
        let points = at(&s, 0.0, 0.59, 0.37, 10);
        assert_eq!(steps_seen(&s, &points, 5), 1);
        let on_riser = at(&s, 0.0, 0.6, 0.45, 10);
        assert_eq!(steps_seen(&s, &on_riser, 5), 1);
        // Beyond the last step (the landing) and in front of the first: no step.
        let off = [at(&s, 0.0, 1.5, 0.72, 10), at(&s, 0.0, -0.3, 0.0, 10)].concat();
        assert_eq!(steps_seen(&s, &off, 5), 0);
    }
}
