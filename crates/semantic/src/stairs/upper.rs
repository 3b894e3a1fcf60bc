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
use super::{part_points, DetectedStairs, StairsConfig};
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
        // 1. The parts beyond the lone flight's top, in line with it and above its top level,
        //    that show no staircase of their own.
        let beyond: Vec<usize> = (0..parts.len())
            .filter(|&j| j != i && found[j].is_none() && lies_beyond(&parts[j], &lone, sc))
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
        if !spans_width(&part_points(sc, &joined(|p| &p.members, false)), &lone) {
            continue;
        }
        let pts = part_points(sc, &joined(|p| &p.surface, true));
        let all = part_points(sc, &joined(|p| &p.members, true));
        if let Some(second) = flight_above(&lone, &pts, &all, sc, c) {
            found[i] = Some(vec![lone, second]);
        }
    }
}

/// True if nearly all of a part's returns lie beyond the flight's top step (up to [`REACH_M`]
/// on) and across its width, and most of them above its top level (the side face of the
/// landing below the upper flight may join its first riser's part).
fn lies_beyond(part: &Part, flight: &DetectedStairs, sc: &Scene) -> bool {
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
    in_line as f64 >= MIN_SHARE * n && above as f64 >= MIN_ABOVE * n
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
