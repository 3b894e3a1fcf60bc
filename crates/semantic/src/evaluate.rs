//! Evaluation of a semantic map against the building it was scanned in.
//!
//! # What is expected
//! Without `observed`, every element of the building is expected. With `observed` (the
//! registered cloud carrying the virtual laser's ground-truth labels), only what the scans saw:
//!
//! - a wall is expected piecewise: its labelled points, projected on its centre line, in 10 cm
//!   stretches; a stretch with fewer than `min_bin_points` (5) points was only glimpsed and
//!   does not count. The counted stretches split where they leave a gap over `piece_gap_m`
//!   (1.5 m, wider than any door, so a door does not split a wall but an unvisited room between
//!   two visited ones does); each piece with at least `min_points` (50) points and
//!   `min_length_m` (0.5 m) is one expected wall, whose extent is the observed one (min to max
//!   of its points along the centre line). A wall seen only in part is thus compared with the
//!   part that was seen;
//! - a door opening is expected if its lintel and leaf together carry at least
//!   `min_door_points` (20) points (the opening itself has no surface);
//! - a staircase, the floor and the ceiling if they carry at least `min_points` points.
//!
//! # Matching
//! Greedy one-to-one, best first. Walls: directions within `wall_max_angle_deg`, the detected
//! centre line's midpoint within half the true thickness plus `wall_max_offset_m` of the true
//! centre line, and along-line intersection over union at least `wall_min_iou`. Door openings:
//! centres within `door_max_distance_m`. Staircases: footprint centres within
//! `stairs_max_distance_m`. Floor and ceiling: the entity's height within `max_height_error_m`.
//! Endpoint errors: the distance of each detected centre-line end from the stretch of the true
//! centre line between the observed piece's end and the wall's true end (a map may carry a wall
//! on behind what hid it from the scans, which is right; stopping short of what was seen, or
//! running past the wall's end, is not).

use crate::evaluate_doors::{evaluate_doors, DoorMatch};
use crate::evaluate_stairs::{evaluate_stairs, StairsMatch};
use crate::evaluate_walls::{evaluate_walls, WallMatch};
use crate::map::{EntityClass, SemanticMap};
use cloud::{Label, PointCloud, SurfaceClass};
use glam::{DAffine3, DVec3};
use scanner::{Building, BuildingGeometry};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// Thresholds of the evaluation (see the module docs).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct EvalConfig {
    /// Least labelled points of an expected wall piece, staircase, floor or ceiling.
    pub min_points: usize,
    /// Least observed length of an expected wall piece.
    pub min_length_m: f64,
    /// Gaps in a wall's labelled points wider than this split it into pieces.
    pub piece_gap_m: f64,
    /// Least labelled points in a 10 cm stretch of a wall for it to count as observed.
    pub min_bin_points: usize,
    /// Least labelled points (lintel and leaf) of an expected door opening.
    pub min_door_points: usize,
    /// Largest angle between matched walls.
    pub wall_max_angle_deg: f64,
    /// Largest offset of a matched wall beyond half the true thickness.
    pub wall_max_offset_m: f64,
    /// Least along-line intersection over union of matched walls.
    pub wall_min_iou: f64,
    /// Largest distance between matched door openings' centres.
    pub door_max_distance_m: f64,
    /// Largest distance between matched staircases' centres.
    pub stairs_max_distance_m: f64,
    /// Largest floor or ceiling height error of a match.
    pub max_height_error_m: f64,
}

impl Default for EvalConfig {
    fn default() -> Self {
        EvalConfig {
            min_points: 50,
            min_length_m: 0.5,
            piece_gap_m: 1.5,
            min_bin_points: 5,
            min_door_points: 20,
            wall_max_angle_deg: 5.0,
            wall_max_offset_m: 0.15,
            wall_min_iou: 0.5,
            door_max_distance_m: 0.3,
            stairs_max_distance_m: 1.0,
            max_height_error_m: 0.05,
        }
    }
}

/// Precision, recall and F1 of one class.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct ClassScore {
    /// Expected (ground truth) instances.
    pub expected: usize,
    /// Detected instances.
    pub detected: usize,
    /// Matched pairs.
    pub matched: usize,
    /// matched / detected (1 when nothing was detected and nothing expected).
    pub precision: f64,
    /// matched / expected (1 when nothing was expected).
    pub recall: f64,
    /// Harmonic mean of precision and recall.
    pub f1: f64,
}

impl ClassScore {
    pub(crate) fn new(expected: usize, detected: usize, matched: usize) -> ClassScore {
        let ratio = |a: usize, b: usize| {
            if b == 0 {
                if expected == 0 && detected == 0 {
                    1.0
                } else {
                    0.0
                }
            } else {
                a as f64 / b as f64
            }
        };
        let (precision, recall) = (ratio(matched, detected), ratio(matched, expected));
        let f1 = if precision + recall > 0.0 {
            2.0 * precision * recall / (precision + recall)
        } else {
            0.0
        };
        ClassScore {
            expected,
            detected,
            matched,
            precision,
            recall,
            f1,
        }
    }
}

/// The evaluation of a map (serialisable for `--json`).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Evaluation {
    /// Walls.
    pub walls: ClassScore,
    /// Door openings (free space for door).
    pub door_openings: ClassScore,
    /// Door leaves (expected: true leaves in expected openings).
    pub doors: ClassScore,
    /// Floor.
    pub floor: ClassScore,
    /// Ceiling.
    pub ceiling: ClassScore,
    /// Staircases.
    pub stairs: ClassScore,
    /// Mean distance of matched walls' ends from the observed ends.
    pub wall_endpoint_error_mean_m: f64,
    /// Largest such distance.
    pub wall_endpoint_error_max_m: f64,
    /// Floor height error, if found.
    pub floor_height_error_m: Option<f64>,
    /// Ceiling height error, if found.
    pub ceiling_height_error_m: Option<f64>,
    /// Matched walls.
    pub wall_matches: Vec<WallMatch>,
    /// Matched door openings.
    pub door_matches: Vec<DoorMatch>,
    /// Matched staircases.
    pub stairs_matches: Vec<StairsMatch>,
    /// Expected elements not found (names, walls with their piece).
    pub missed: Vec<String>,
    /// Map entities matching nothing expected (ids).
    pub spurious: Vec<u32>,
}

/// Evaluates `map` against `building` with the default thresholds (see the module docs).
pub fn evaluate(
    map: &SemanticMap,
    building: &Building,
    observed: Option<&PointCloud>,
) -> Evaluation {
    evaluate_with(map, building, observed, &EvalConfig::default())
}

/// Evaluates `map` against `building` with the given thresholds.
pub fn evaluate_with(
    map: &SemanticMap,
    building: &Building,
    observed: Option<&PointCloud>,
    c: &EvalConfig,
) -> Evaluation {
    let t = Truth::new(map, building, observed);
    let mut ev = Evaluation::default();
    evaluate_walls(&mut ev, map, building, &t, c);
    evaluate_doors(&mut ev, map, building, &t, c);
    evaluate_stairs(&mut ev, map, building, &t, c);
    let f = &building.floor;
    let (cx, cy) = (
        (f.min_m[0] + f.max_m[0]) / 2.0,
        (f.min_m[1] + f.max_m[1]) / 2.0,
    );
    for (class, name, z) in [
        (EntityClass::Floor, "floor", 0.0),
        (EntityClass::Ceiling, "ceiling", building.ceiling.height_m),
    ] {
        let want = usize::from(!t.observed || t.count(name) >= c.min_points);
        let found: Vec<_> = map.of_class(class).collect();
        let truth_z = t.to_map(cx, cy, z).z;
        let err = found
            .iter()
            .map(|e| {
                let [b, t] = e.geometry.z_range_m();
                (if class == EntityClass::Floor { t } else { b }) - truth_z
            })
            .min_by(|a, b| a.abs().total_cmp(&b.abs()));
        let ok = usize::from(want == 1 && err.is_some_and(|e| e.abs() <= c.max_height_error_m));
        let score = ClassScore::new(want, found.len(), ok);
        if class == EntityClass::Floor {
            ev.floor = score;
            ev.floor_height_error_m = err;
        } else {
            ev.ceiling = score;
            ev.ceiling_height_error_m = err;
        }
        if want == 1 && ok == 0 {
            ev.missed.push(name.into());
        }
    }
    ev
}

/// The ground truth in the map frame: true entity ids by name and their observed points.
pub(crate) struct Truth {
    map_from_input: DAffine3,
    id_of: HashMap<String, u32>,
    seen: HashMap<u32, Vec<DVec3>>,
    /// True if an observed (labelled) cloud was given.
    pub observed: bool,
}

impl Truth {
    fn new(map: &SemanticMap, building: &Building, observed: Option<&PointCloud>) -> Truth {
        let geometry = BuildingGeometry::new(building);
        let mut t = Truth {
            map_from_input: map.input_from_map().inverse(),
            id_of: geometry
                .entities()
                .iter()
                .map(|e| (e.name.clone(), e.id))
                .collect(),
            seen: HashMap::new(),
            observed: observed.is_some(),
        };
        if let Some((cloud, labels)) = observed.and_then(|c| c.labels.as_ref().map(|l| (c, l))) {
            for (p, l) in cloud.points.iter().zip(labels) {
                if p.is_finite() && l.entity != 0 {
                    let q = t.to_map(p.x as f64, p.y as f64, p.z as f64);
                    t.seen.entry(l.entity).or_default().push(q);
                }
            }
        }
        t
    }

    /// A point of the building (input frame) in the map frame.
    pub fn to_map(&self, x: f64, y: f64, z: f64) -> DVec3 {
        self.map_from_input.transform_point3(DVec3::new(x, y, z))
    }

    /// The observed points of the true entity `name` (e.g. `walls[2]`), map frame.
    pub fn points(&self, name: &str) -> Option<&Vec<DVec3>> {
        self.id_of.get(name).and_then(|id| self.seen.get(id))
    }

    /// How many observed points the true entity `name` has.
    pub fn count(&self, name: &str) -> usize {
        self.points(name).map_or(0, Vec::len)
    }
}

/// Point-level agreement of predicted labels with the ground truth, by surface class.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct LabelEvaluation {
    /// Points compared (finite, both labels present).
    pub points: usize,
    /// Fraction of them whose class agrees.
    pub accuracy: f64,
    /// Per class (by name): expected = true points of the class, detected = predicted, matched = both.
    pub classes: Vec<(String, ClassScore)>,
}

/// Compares predicted per-point classes with the truth (same order, e.g. `MapOutput::labels`
/// and the input cloud's ground-truth labels). Furniture counts as unknown.
pub fn evaluate_labels(predicted: &[Label], truth: &[Label]) -> LabelEvaluation {
    let norm = |c: SurfaceClass| {
        if c == SurfaceClass::Furniture {
            SurfaceClass::Unknown
        } else {
            c
        }
    };
    let mut tally: HashMap<SurfaceClass, (usize, usize, usize)> = HashMap::new();
    let mut agree = 0;
    let n = predicted.len().min(truth.len());
    for (p, t) in predicted.iter().zip(truth) {
        let (p, t) = (norm(p.class), norm(t.class));
        tally.entry(t).or_default().0 += 1;
        tally.entry(p).or_default().1 += 1;
        if p == t {
            tally.entry(t).or_default().2 += 1;
            agree += 1;
        }
    }
    let mut classes: Vec<(String, ClassScore)> = SurfaceClass::ALL
        .iter()
        .filter_map(|c| {
            tally
                .get(c)
                .map(|&(e, d, m)| (c.name().to_string(), ClassScore::new(e, d, m)))
        })
        .collect();
    classes.sort_by(|a, b| a.0.cmp(&b.0));
    LabelEvaluation {
        points: n,
        accuracy: if n == 0 { 1.0 } else { agree as f64 / n as f64 },
        classes,
    }
}
