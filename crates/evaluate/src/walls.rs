//! Evaluation of walls: the expected wall pieces (see the crate docs) matched with the
//! map's walls, and the end errors.

use crate::config::EvalConfig;
use crate::score::ClassScore;
use crate::truth::Truth;
use crate::Evaluation;
use cloud::EntityClass;
use glam::{DVec2, DVec3};
use scanner::Building;
use semantic::undirected_angle_deg;
use semantic::Line2;
use semantic::SemanticMap;
use serde::{Deserialize, Serialize};

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
    /// The scans saw one face of the true wall only: `offset_m` and `endpoint_errors_m`
    /// compare that face with the map wall's face on the same side, not the centre lines (a
    /// wall seen from one side cannot show its thickness; its seen face is what a robot meets).
    #[serde(default)]
    pub one_face: bool,
}

/// The expected walls' observed length and how much of it map walls cover: where the matching
/// of pieces counts a wall found by one map wall over half of it, this counts the stretches no
/// map wall runs along (several map walls along one piece count once).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct WallLength {
    /// The expected pieces' total length (metres).
    pub expected_m: f64,
    /// Their length along which a map wall runs (within the direction and offset gates).
    pub covered_m: f64,
    /// `covered_m / expected_m` (1 when nothing was expected).
    pub recall: f64,
}

/// An expected wall: the observed piece of a true wall (the whole wall where nothing was
/// observed), in the map frame.
struct Piece {
    /// The true wall, e.g. `walls[3]`.
    name: String,
    /// Its centre line (from its start).
    line: Line2,
    /// The observed piece along `line`.
    range: (f64, f64),
    /// The whole wall along `line`.
    full: (f64, f64),
    thickness: f64,
    /// The side (+1 left of `line`, -1 right) of the one face the scans saw, or `None` if they
    /// saw both (or no observed cloud was given).
    seen_side: Option<f64>,
}

impl Piece {
    /// Signed distance of a map wall's centre-line point `q` (the map wall `thickness_m`
    /// thick) from the compared line: the true centre line, or for a wall seen from one side
    /// the true seen face, `q` then moved to the map wall's face on that side.
    fn offset(&self, q: DVec2, thickness_m: f64) -> (f64, f64) {
        let (s, d) = self.line.coords(q);
        match self.seen_side {
            Some(side) => (s, d + side * (thickness_m - self.thickness) / 2.0),
            None => (s, d),
        }
    }
}

/// The face of a true wall the scans saw over the piece `range`: `None` if they saw both faces
/// along at least half of the piece's observed 10 cm stretches (each face with `min_bin_points`
/// there), else the side (+1 left of `line`, -1 right) of the face with more points. Points
/// within a quarter thickness of the centre line (on the wall's ends) count for neither face.
fn seen_side(
    points: &[DVec3],
    line: &Line2,
    range: (f64, f64),
    t: f64,
    min_bin_points: usize,
) -> Option<f64> {
    let mut bins: std::collections::BTreeMap<i64, [usize; 2]> = Default::default();
    for p in points {
        let (s, d) = line.coords(p.truncate());
        if s < range.0 || s > range.1 || d.abs() < t / 4.0 {
            continue;
        }
        bins.entry((s / 0.1).floor() as i64).or_default()[usize::from(d > 0.0)] += 1;
    }
    let both = bins
        .values()
        .filter(|[r, l]| *r >= min_bin_points && *l >= min_bin_points)
        .count();
    if 2 * both >= bins.len() {
        return None;
    }
    let (right, left) = bins
        .values()
        .fold((0, 0), |(r, l), [br, bl]| (r + br, l + bl));
    Some(if left >= right { 1.0 } else { -1.0 })
}

/// The expected wall pieces (see the crate docs).
fn expected_pieces(building: &Building, t: &Truth, c: &EvalConfig) -> Vec<Piece> {
    let mut pieces = Vec::new();
    for (i, w) in building.walls.iter().enumerate() {
        let a = t.to_map(w.start_m[0], w.start_m[1], 0.0).truncate();
        let b = t.to_map(w.end_m[0], w.end_m[1], 0.0).truncate();
        let line = Line2::through(a, b);
        let name = format!("walls[{i}]");
        let ranges: Vec<(f64, f64)> = if !t.observed {
            vec![(0.0, a.distance(b))]
        } else {
            let mut s: Vec<f64> = t
                .points(&name)
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
        let points = t.points(&name).map(Vec::as_slice).unwrap_or_default();
        for range in ranges {
            let seen_side = if t.observed {
                seen_side(points, &line, range, w.thickness_m, c.min_bin_points)
            } else {
                None
            };
            pieces.push(Piece {
                name: name.clone(),
                line,
                range,
                full: (0.0, a.distance(b)),
                thickness: w.thickness_m,
                seen_side,
            });
        }
    }
    pieces
}

/// A map wall's extent `[from, to]` along `p`'s line if it passes the direction and offset
/// gates for `p`.
fn extent_along(p: &Piece, w: &semantic::WallInfo, c: &EvalConfig) -> Option<(f64, f64, f64, f64)> {
    let (a, b) = (
        DVec2::from_array(w.segment_m[0]),
        DVec2::from_array(w.segment_m[1]),
    );
    let angle = undirected_angle_deg(b - a, p.line.dir);
    let offset = p.offset((a + b) / 2.0, w.thickness_m).1.abs();
    if angle > c.wall_max_angle_deg || offset > p.thickness / 2.0 + c.wall_max_offset_m {
        return None;
    }
    let (sa, sb) = (p.line.coords(a).0, p.line.coords(b).0);
    Some((sa.min(sb), sa.max(sb), angle, offset))
}

/// Two consecutive pieces of one true wall are one expected piece where a map wall runs from
/// one through the gap between them into the other: the map carried the wall on behind what
/// hid it from the scans, which is right (as for the ends, see the crate docs); counted as two
/// pieces, one of them would read as missed.
fn join_spanned_pieces(
    pieces: Vec<Piece>,
    walls: &[&semantic::WallInfo],
    t: &Truth,
    c: &EvalConfig,
) -> Vec<Piece> {
    let mut out: Vec<Piece> = Vec::with_capacity(pieces.len());
    for p in pieces {
        if let Some(prev) = out.last_mut() {
            let spans = prev.name == p.name
                && walls.iter().any(|w| {
                    extent_along(prev, w, c)
                        .is_some_and(|(d0, d1, ..)| d0 < prev.range.1 && d1 > p.range.0)
                });
            if spans {
                prev.range.1 = p.range.1;
                let points = t.points(&prev.name).map(Vec::as_slice).unwrap_or_default();
                prev.seen_side = seen_side(
                    points,
                    &prev.line,
                    prev.range,
                    prev.thickness,
                    c.min_bin_points,
                );
                continue;
            }
        }
        out.push(p);
    }
    out
}

/// Matches the expected wall pieces with the map's walls (greedy, best intersection over union
/// first), and records the matches, the misses, the spurious walls and the end errors.
pub(crate) fn evaluate_walls(
    ev: &mut Evaluation,
    map: &SemanticMap,
    building: &Building,
    t: &Truth,
    c: &EvalConfig,
) {
    let walls: Vec<_> = map
        .of_class(EntityClass::Wall)
        .filter_map(|e| e.wall.as_ref().map(|w| (e.id, w)))
        .collect();
    let geometries: Vec<_> = walls.iter().map(|(_, w)| *w).collect();
    let pieces = join_spanned_pieces(expected_pieces(building, t, c), &geometries, t, c);
    let mut cands = Vec::new();
    for (pi, p) in pieces.iter().enumerate() {
        for (wi, (_, w)) in walls.iter().enumerate() {
            let Some((d0, d1, angle, offset)) = extent_along(p, w, c) else {
                continue;
            };
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
            let (s, d) = p.offset(q, w.thickness_m);
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
            one_face: p.seen_side.is_some(),
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
    ev.wall_length = covered_length(&pieces, &geometries, c);
    if !errors.is_empty() {
        ev.wall_endpoint_error_mean_m = errors.iter().sum::<f64>() / errors.len() as f64;
        ev.wall_endpoint_error_max_m = errors.iter().copied().fold(0.0, f64::max);
    }
}

/// The expected pieces' length along which some map wall runs: per piece, the union of the
/// extents of every map wall that passes its direction and offset gates, clipped to the piece
/// (two map walls along one piece both count; a stretch none runs along is missed, however the
/// pieces were matched).
fn covered_length(pieces: &[Piece], walls: &[&semantic::WallInfo], c: &EvalConfig) -> WallLength {
    let (mut expected_m, mut covered_m) = (0.0, 0.0);
    for p in pieces {
        expected_m += p.range.1 - p.range.0;
        let mut spans: Vec<(f64, f64)> = walls
            .iter()
            .filter_map(|w| extent_along(p, w, c))
            .map(|(d0, d1, ..)| (d0.max(p.range.0), d1.min(p.range.1)))
            .filter(|(a, b)| b > a)
            .collect();
        spans.sort_by(|x, y| x.0.total_cmp(&y.0));
        let mut reach = f64::NEG_INFINITY;
        for (a, b) in spans {
            covered_m += (b - a.max(reach)).max(0.0);
            reach = reach.max(b);
        }
    }
    let recall = if expected_m > 0.0 {
        covered_m / expected_m
    } else {
        1.0
    };
    WallLength {
        expected_m,
        covered_m,
        recall,
    }
}
