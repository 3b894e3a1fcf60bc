//! An upper flight parted from the flight below it (see the `stairs` module and `flights`).
//!
//! A laser standing on the floor below a staircase with a mid landing sees the upper flight's
//! risers from below and none of its treads, nor the landing when that stands above the laser.
//! Each riser is then a line in the height map a run away from the next one, farther than the
//! blobs reach, and the landing leaves a gap between the flights: the lower flight is a part
//! of its own, found as a staircase ending on its landing, and the upper flight's risers are
//! parts of one or two risers each, too few levels to be a flight on their own (bench
//! office-66: a 4-step flight on a landing 0.54 m up, seen as parts of three risers and of
//! one).
//!
//! So for each lone flight found, the parts beyond its top, in line with it and standing
//! above its top level, that show no staircase of their own, are read together (with the lone
//! flight's part's own returns beyond its top step: its landing, and the upper flight's first
//! riser where that joined it) as the flight on its landing (see `flights::flight_above`):
//! heights from the landing, the lone flight's rise as the hint, and the same checks as any
//! flight's.

use super::extend::COVER_BIN_M;
use super::flights::flight_above;
use super::parts::Part;
use super::{across, part_points, DetectedStairs, StairsConfig};
use crate::points::median;
use crate::scene::Scene;
use glam::DVec2;

/// How far beyond a flight's top step an upper flight's returns may lie (m): a landing as deep
/// as the widest stair, and a long flight beyond it.
const REACH_M: f64 = 8.0;

/// How far beside a flight's width an upper flight's returns may lie (m): a side face's returns
/// spread by the range noise, a width measured from 1-99 % of the points.
const BESIDE_M: f64 = 0.15;

/// The share of a part's returns that must lie beyond the flight and in line with it for the
/// part to be taken as part of an upper flight.
const MIN_SHARE: f64 = 0.9;

/// The share of a part's returns that must stand above the flight's top level.
const MIN_ABOVE: f64 = 0.5;

/// The share of a flight's width an upper flight's risers cover (see [`spans_width`]).
const MIN_SPAN: f64 = 0.8;

/// Reads the returns of the parts beyond each lone flight of `found` (by part, as `parts`),
/// in line with it and above its top level, as the flight on its landing, where they show one
/// (see the module docs).
pub(super) fn join_upper_flights(
    parts: &[Part],
    found: &mut [Option<Vec<DetectedStairs>>],
    sc: &Scene,
    c: &StairsConfig,
) {
    for i in 0..parts.len() {
        let Some([lone]) = found[i].as_deref() else {
            continue;
        };
        let lone = lone.clone();
        // (seen from its side only, the flight shows its upper flight's side face instead, in
        // the plane of its own and standing from the floor)
        let face = side_face(&part_points(sc, &parts[i].members), &lone, c);
        let min_above = if face.is_some() { 0.0 } else { MIN_ABOVE };
        // 1. The parts beyond the lone flight's top, in line with it and above its top level,
        //    that show no staircase of their own.
        let beyond: Vec<usize> = (0..parts.len())
            .filter(|&j| {
                j != i
                    && found[j].is_none()
                    && lies_beyond(&parts[j], &lone, sc, min_above)
                    && face.is_none_or(|f| {
                        in_face_plane(&part_points(sc, &parts[j].members), &lone, f)
                    })
            })
            .collect();
        if beyond.is_empty() {
            continue;
        }
        // 2. The flight on the lone flight's landing, where those parts' returns span its
        //    width as risers do: from their returns and the lone flight's part's own beyond
        //    its top step (its landing, and the upper flight's first riser where that joined
        //    its part; office-126 of seeds 126-130: a 5-step upper flight whose first step,
        //    all in the lower flight's part, was left with no support).
        let joined = |of: fn(&Part) -> &Vec<usize>, own: bool| -> Vec<usize> {
            beyond
                .iter()
                .chain(own.then_some(&i))
                .flat_map(|&j| of(&parts[j]).iter().copied())
                .collect()
        };
        if face.is_none() && !spans_width(&part_points(sc, &joined(|p| &p.members, false)), &lone) {
            continue;
        }
        let pts = part_points(sc, &joined(|p| &p.surface, true));
        let all = part_points(sc, &joined(|p| &p.members, true));
        if let Some(mut second) = flight_above(&lone, &pts, &all, sc, c) {
            if face.is_some() {
                second.rules.push(
                    "seen from its side only, its side face in the plane of the lower flight's"
                        .to_string(),
                );
            }
            found[i] = Some(vec![lone, second]);
        }
    }
}

/// True if nearly all of a part's returns lie beyond the flight's top step (up to [`REACH_M`]
/// on) and across its width, and a `min_above` share of them above its top level (most: the
/// side face of the landing below the upper flight may join its first riser's part; any,
/// for an upper flight's side face standing from the floor).
fn lies_beyond(part: &Part, flight: &DetectedStairs, sc: &Scene, min_above: f64) -> bool {
    let top_level = flight.rise * f64::from(flight.steps) - 0.05;
    let first_beyond = flight.run * f64::from(flight.steps);
    let (mut in_line, mut above) = (0usize, 0usize);
    for &k in &part.members {
        let p = sc.points[k];
        let q = DVec2::new(p.x as f64, p.y as f64) - flight.start;
        let (along, across) = (q.dot(flight.dir), flight.dir.perp_dot(q));
        if along >= first_beyond
            && along <= first_beyond + REACH_M
            && across.abs() <= flight.width / 2.0 + BESIDE_M
        {
            in_line += 1;
            above += usize::from(p.z as f64 - sc.floor >= top_level);
        }
    }
    let n = part.members.len() as f64;
    in_line as f64 >= MIN_SHARE * n && above as f64 >= min_above * n
}

/// How far from a side face's plane the returns of an upper flight's side face may lie (m):
/// the range noise and a registration's smear.
const FACE_M: f64 = 0.1;

/// Where a flight's side face stands across it (from its start, along its direction's
/// normal), where the flight was seen from its side only: its part's returns `own` (1 % to
/// 99 %) span less than `min_width_m` across it. `None` where more was seen.
fn side_face(own: &[(DVec2, f64)], flight: &DetectedStairs, c: &StairsConfig) -> Option<f64> {
    let xy: Vec<DVec2> = own.iter().map(|(q, _)| *q - flight.start).collect();
    if xy.is_empty() || across(&xy, flight.dir) >= c.min_width_m {
        return None;
    }
    let mut t: Vec<f64> = xy.iter().map(|q| flight.dir.perp_dot(*q)).collect();
    median(&mut t)
}

/// True if at least [`MIN_SHARE`] of the returns `pts` lie within [`FACE_M`] of the side face
/// `face` (across `flight`, see [`side_face`]): an upper flight seen from the side, as the
/// flight below it was (office-441 of seeds 441-445: a staircase with a mid landing seen
/// through a doorway from its side only, the landing's side face hidden by the door's frame;
/// the upper flight's side face, a part of its own, was left out of the map).
fn in_face_plane(pts: &[(DVec2, f64)], flight: &DetectedStairs, face: f64) -> bool {
    let on = pts
        .iter()
        .filter(|(q, _)| (flight.dir.perp_dot(*q - flight.start) - face).abs() <= FACE_M)
        .count();
    !pts.is_empty() && on as f64 >= MIN_SHARE * pts.len() as f64
}

/// True if the returns `pts` span the flight's width as an upper flight's risers do, each
/// across all of it: they cover at least [`MIN_SPAN`] of it in bins [`COVER_BIN_M`] wide. A
/// tall cabinet beyond a flight's landing, along its line, shows its shelves at heights a rise
/// apart too, but on a face along the flight (bench office-61: its face and what stood in
/// front of it covered half of the flight's width, and read as a 6-step flight on the
/// landing; office-66's upper flight covers all of it).
fn spans_width(pts: &[(DVec2, f64)], flight: &DetectedStairs) -> bool {
    let half = flight.width / 2.0;
    let bins = ((flight.width / COVER_BIN_M).ceil() as usize).clamp(1, 1000);
    let mut covered = vec![false; bins];
    for (q, _) in pts {
        let t = flight.dir.perp_dot(*q - flight.start) + half;
        if (0.0..flight.width).contains(&t) {
            covered[((t / COVER_BIN_M) as usize).min(bins - 1)] = true;
        }
    }
    covered.iter().filter(|&&b| b).count() as f64 >= MIN_SPAN * bins as f64
}
