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

use crate::map::{EntityClass, RelationType, SemanticMap, SwingSide};
use crate::points::{undirected_angle_deg, Line2};
use cloud::{Label, PointCloud, SurfaceClass};
use glam::{DAffine3, DVec2, DVec3};
use scanner::{Building, BuildingGeometry, Hinge, Swing};
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
    fn new(expected: usize, detected: usize, matched: usize) -> ClassScore {
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

/// A matched wall.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WallMatch {
    /// The true wall, e.g. `walls[3]`, and the observed piece `[from, to]` along it (metres).
    pub truth: String,
    /// Observed piece along the true centre line.
    pub piece_m: [f64; 2],
    /// The map entity.
    pub entity: u32,
    /// Distance of each detected end from the stretch between the piece's end and the wall's.
    pub endpoint_errors_m: [f64; 2],
    /// Distance of the detected midpoint from the true centre line.
    pub offset_m: f64,
    /// Detected minus true thickness.
    pub thickness_error_m: f64,
    /// Angle between the lines.
    pub angle_deg: f64,
}

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
    /// Distance between the first steps' front-edge centres.
    pub start_error_m: f64,
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
    let map_from_input: DAffine3 = map.input_from_map().inverse();
    let to_map = |x: f64, y: f64, z: f64| map_from_input.transform_point3(DVec3::new(x, y, z));
    let geometry = BuildingGeometry::new(building);
    let id_of: HashMap<&str, u32> = geometry
        .entities()
        .iter()
        .map(|e| (e.name.as_str(), e.id))
        .collect();
    // Observed points per true entity, in the map frame.
    let mut seen: HashMap<u32, Vec<DVec3>> = HashMap::new();
    if let Some(cloud) = observed {
        if let Some(labels) = &cloud.labels {
            for (p, l) in cloud.points.iter().zip(labels) {
                if p.is_finite() && l.entity != 0 {
                    seen.entry(l.entity)
                        .or_default()
                        .push(to_map(p.x as f64, p.y as f64, p.z as f64));
                }
            }
        }
    }
    let count = |name: &str| -> usize {
        id_of
            .get(name)
            .and_then(|id| seen.get(id))
            .map_or(0, |v| v.len())
    };
    let mut ev = Evaluation::default();

    // Walls.
    struct Piece {
        name: String,
        line: Line2,
        range: (f64, f64),
        full: (f64, f64),
        thickness: f64,
    }
    let mut pieces = Vec::new();
    for (i, w) in building.walls.iter().enumerate() {
        let a = to_map(w.start_m[0], w.start_m[1], 0.0).truncate();
        let b = to_map(w.end_m[0], w.end_m[1], 0.0).truncate();
        let line = Line2::through(a, b);
        let name = format!("walls[{i}]");
        let ranges: Vec<(f64, f64)> = if observed.is_none() {
            vec![(0.0, a.distance(b))]
        } else {
            let mut s: Vec<f64> = id_of
                .get(name.as_str())
                .and_then(|id| seen.get(id))
                .map(|v| v.iter().map(|p| line.coords(p.truncate()).0).collect())
                .unwrap_or_default();
            s.sort_by(f64::total_cmp);
            // 10 cm bins seen by fewer than `min_bin_points` points (a glimpse) are not observed.
            let mut bins: std::collections::BTreeMap<i64, (f64, f64, usize)> = Default::default();
            for v in s {
                let b = bins.entry((v / 0.1).floor() as i64).or_insert((v, v, 0));
                b.0 = b.0.min(v);
                b.1 = b.1.max(v);
                b.2 += 1;
            }
            let mut runs: Vec<(f64, f64, usize)> = Vec::new();
            for (lo, hi, n) in bins.into_values().filter(|b| b.2 >= c.min_bin_points) {
                match runs.last_mut() {
                    Some(r) if lo - r.1 <= c.piece_gap_m => {
                        r.1 = hi;
                        r.2 += n;
                    }
                    _ => runs.push((lo, hi, n)),
                }
            }
            runs.into_iter()
                .filter(|r| r.2 >= c.min_points && r.1 - r.0 >= c.min_length_m)
                .map(|r| (r.0, r.1))
                .collect()
        };
        for range in ranges {
            pieces.push(Piece {
                name: name.clone(),
                line,
                range,
                full: (0.0, a.distance(b)),
                thickness: w.thickness_m,
            });
        }
    }
    let walls: Vec<_> = map
        .of_class(EntityClass::Wall)
        .filter_map(|e| e.wall.as_ref().map(|w| (e.id, w)))
        .collect();
    let mut cands = Vec::new();
    for (pi, p) in pieces.iter().enumerate() {
        for (wi, (_, w)) in walls.iter().enumerate() {
            let (a, b) = (
                DVec2::from_array(w.segment_m[0]),
                DVec2::from_array(w.segment_m[1]),
            );
            let angle = undirected_angle_deg(b - a, p.line.dir);
            let offset = p.line.coords((a + b) / 2.0).1.abs();
            if angle > c.wall_max_angle_deg || offset > p.thickness / 2.0 + c.wall_max_offset_m {
                continue;
            }
            let (sa, sb) = (p.line.coords(a).0, p.line.coords(b).0);
            let (d0, d1) = (sa.min(sb), sa.max(sb));
            let inter = d1.min(p.range.1) - d0.max(p.range.0);
            let union = d1.max(p.range.1) - d0.min(p.range.0);
            let iou = inter / union.max(1e-9);
            if iou >= c.wall_min_iou {
                cands.push((iou, pi, wi, angle, offset));
            }
        }
    }
    cands.sort_by(|x, y| y.0.total_cmp(&x.0));
    let (mut used_p, mut used_w) = (vec![false; pieces.len()], vec![false; walls.len()]);
    let mut errors = Vec::new();
    for (_, pi, wi, angle, offset) in cands {
        if used_p[pi] || used_w[wi] {
            continue;
        }
        used_p[pi] = true;
        used_w[wi] = true;
        let (p, (id, w)) = (&pieces[pi], &walls[wi]);
        // An end is right anywhere from the observed end out to the wall's true end (the map
        // may carry a wall on behind what hid it): its error is its distance from that stretch.
        let near_end = |q: DVec2, from: f64, to: f64| {
            let (s, d) = p.line.coords(q);
            let (lo, hi) = (from.min(to), from.max(to));
            (s - s.clamp(lo, hi)).hypot(d)
        };
        let (a, b) = (
            DVec2::from_array(w.segment_m[0]),
            DVec2::from_array(w.segment_m[1]),
        );
        let start_end = |q: DVec2| near_end(q, p.range.0, p.full.0.min(p.range.0));
        let end_end = |q: DVec2| near_end(q, p.range.1, p.full.1.max(p.range.1));
        let errs = if start_end(a) + end_end(b) <= start_end(b) + end_end(a) {
            [start_end(a), end_end(b)]
        } else {
            [start_end(b), end_end(a)]
        };
        errors.extend(errs);
        ev.wall_matches.push(WallMatch {
            truth: p.name.clone(),
            piece_m: [p.range.0, p.range.1],
            entity: *id,
            endpoint_errors_m: errs,
            offset_m: offset,
            thickness_error_m: w.thickness_m - p.thickness,
            angle_deg: angle,
        });
    }
    for (pi, p) in pieces.iter().enumerate() {
        if !used_p[pi] {
            ev.missed
                .push(format!("{} [{:.2}, {:.2}] m", p.name, p.range.0, p.range.1));
        }
    }
    for (wi, (id, _)) in walls.iter().enumerate() {
        if !used_w[wi] {
            ev.spurious.push(*id);
        }
    }
    ev.walls = ClassScore::new(pieces.len(), walls.len(), ev.wall_matches.len());
    if !errors.is_empty() {
        ev.wall_endpoint_error_mean_m = errors.iter().sum::<f64>() / errors.len() as f64;
        ev.wall_endpoint_error_max_m = errors.iter().copied().fold(0.0, f64::max);
    }

    // Door openings and leaves.
    struct TrueDoor {
        name: String,
        center: DVec2,
        width: f64,
        height: f64,
        leaf: Option<(DVec2, DVec2, f64)>, // hinge point, swing side normal, open angle
    }
    let mut doors = Vec::new();
    for (i, w) in building.walls.iter().enumerate() {
        let a = to_map(w.start_m[0], w.start_m[1], 0.0).truncate();
        let b = to_map(w.end_m[0], w.end_m[1], 0.0).truncate();
        let line = Line2::through(a, b);
        for (j, d) in w.doors.iter().enumerate() {
            let name = format!("walls[{i}].doors[{j}]");
            let points = count(&format!("{name}.lintel")) + count(&format!("{name}.leaf"));
            if observed.is_some() && points < c.min_door_points {
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

    // Stairs.
    let stairs: Vec<_> = map
        .of_class(EntityClass::Stairs)
        .filter_map(|e| e.stairs.as_ref().map(|s| (e, s)))
        .collect();
    let mut expected = 0;
    let mut used_s = vec![false; stairs.len()];
    for (k, s) in building.stairs.iter().enumerate() {
        let name = format!("stairs[{k}]");
        if observed.is_some() && count(&name) < c.min_points {
            continue;
        }
        expected += 1;
        let dir = DVec2::from_angle(s.direction_deg.to_radians());
        let start = to_map(s.start_m[0], s.start_m[1], 0.0).truncate();
        let dir_map = (to_map(s.start_m[0] + dir.x, s.start_m[1] + dir.y, 0.0).truncate() - start)
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
        });
    }
    for (i, (e, _)) in stairs.iter().enumerate() {
        if !used_s[i] {
            ev.spurious.push(e.id);
        }
    }
    ev.stairs = ClassScore::new(expected, stairs.len(), ev.stairs_matches.len());

    // Floor and ceiling.
    let f = &building.floor;
    let (cx, cy) = (
        (f.min_m[0] + f.max_m[0]) / 2.0,
        (f.min_m[1] + f.max_m[1]) / 2.0,
    );
    for (class, name, z) in [
        (EntityClass::Floor, "floor", 0.0),
        (EntityClass::Ceiling, "ceiling", building.ceiling.height_m),
    ] {
        let want = usize::from(observed.is_none() || count(name) >= c.min_points);
        let found: Vec<_> = map.of_class(class).collect();
        let truth_z = to_map(cx, cy, z).z;
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
