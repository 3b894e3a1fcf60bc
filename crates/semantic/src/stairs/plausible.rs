//! A staircase from its best profile (see the `stairs` module): its width, landing and start
//! from the blob's points, and the checks that make it one people could climb (rise, run and
//! steps in the building codes' ranges, every step supported, no floor seen under it).

use super::climbs_on::{face_climbs_on, surface_climbs_on, PastTop};
use super::floor::{floor_density, floor_in_strip};
use super::oblique_face::one_face_off_deg;
use super::profile::Profile;
use super::taller_face::face_goes_on_above;
use super::top_end::top_end;
use super::{DetectedStairs, StairsConfig};
use crate::points::quantile;
use crate::scene::Scene;
use glam::DVec2;

/// Points on the steps that give a staircase its width: fewer and it is taken from all of its
/// blob's points.
const MIN_WIDTH_POINTS: usize = 20;

/// A gap across the flight wider than this between points on its steps separates it from
/// clutter beside it (a flight's treads and risers span its width; a laser's sampling of them
/// leaves gaps of a few centimetres, a side face seen alone is one line).
const WIDTH_GAP_M: f64 = 0.3;
/// A side face's returns are binned this finely across it to find where they pile up (the
/// range noise spreads a plane's returns over a few centimetres).
const FACE_BIN_M: f64 = 0.02;

/// A side face's returns on each step lie this near one line in plan (the laser's range noise
/// at grazing angles and the registration's error, a few centimetres).
const SIDE_FACE_STRAIGHT_M: f64 = 0.05;

/// The flight's length along its direction: its steps' runs.
fn length_m(p: &Profile) -> f64 {
    p.run * p.steps as f64
}

/// The step (0 the lowest) a point `s` along the flight's direction at height `z` (above its
/// foot) lies on: within the step's run, above the step below (by 2 cm) and at most 3 cm over
/// its tread; `None` if it lies on none.
pub(super) fn step_holding(p: &Profile, s: f64, z: f64) -> Option<usize> {
    p.step_of(s).filter(|&k| {
        let top = (k + 1) as f64 * p.rise;
        z > top - p.rise + 0.02 && z <= top + 0.03
    })
}

/// The staircase of the best profile: its width, landing and start from the blob's points;
/// `None` if it is no staircase people could climb (see the module docs).
pub(crate) fn finish(
    pts: &[(DVec2, f64)],
    p: Profile,
    sc: &Scene,
    c: &StairsConfig,
) -> Option<DetectedStairs> {
    let dir = p.dir;
    // Rise and run must make a stair together: its pace (2 x rise + run) within the codes'.
    if 2.0 * p.rise + p.run > c.max_pace_m {
        return None;
    }
    // The width from the points on the flight's steps (a tread, a riser or a side face between
    // a step's height and the one below: as `step_holding` places them), not from all of the
    // blob's (a desk or chairs beside the flight join its blob at other heights), and of those
    // the run across the direction holding most of them (clutter beside the flight whose parts
    // happen to stand at step heights is apart from it); from all of the blob's points where
    // too few are on the steps.
    let steps_xy: Vec<DVec2> = pts
        .iter()
        .filter(|(q, z)| step_holding(&p, q.dot(dir), *z).is_some())
        .map(|(q, _)| *q)
        .collect();
    // A side face climbs along its own line; one read obliquely is no staircase (see
    // `oblique_face`).
    if steps_xy.len() >= MIN_WIDTH_POINTS
        && one_face_off_deg(&steps_xy, dir).is_some_and(|deg| deg > c.snap_direction_deg)
    {
        return None;
    }
    let on_steps = densest_run(steps_xy.iter().map(|q| dir.perp_dot(*q)).collect());
    let mut ts: Vec<f64> = if on_steps.len() >= MIN_WIDTH_POINTS {
        on_steps
    } else {
        pts.iter().map(|(q, _)| dir.perp_dot(*q)).collect()
    };
    let mut t0 = quantile(&mut ts, 0.01).unwrap_or(0.0);
    let mut t1 = quantile(&mut ts, 0.99).unwrap_or(0.0);
    let mut width_rule = format!("{:.2} m wide across its points", t1 - t0);
    let side_only = t1 - t0 < c.min_width_m;
    if side_only {
        // Only a side face was seen (the treads above the laser are hidden): the staircase
        // extends `default_width_m` away from the side with floor in front of the face.
        let length = length_m(&p);
        let line = crate::points::Line2 {
            origin: dir * (p.front1 + length / 2.0) + dir.perp() * ((t0 + t1) / 2.0),
            dir,
        };
        let (mut left, mut right) = (0usize, 0usize);
        sc.index
            .for_each_near_line(&line, -length / 2.0, length / 2.0, 0.4, |_, _, d, z| {
                if (z - sc.floor).abs() <= 0.03 && d.abs() >= 0.05 {
                    if d > 0.0 {
                        left += 1;
                    } else {
                        right += 1;
                    }
                }
            });
        // The face stands where its returns pile up: stray returns beyond it (mixed pixels at
        // its edges, a registration's smear, 5 % of an upper flight's seen from the floor
        // below) set the 1-99 % span a few centimetres to over 0.1 m wide of it, and the
        // width assumed from there would reach over the floor in front of the face.
        let face = densest(&ts, FACE_BIN_M).unwrap_or((t0 + t1) / 2.0);
        if left > right {
            t1 = t1.min(face + FACE_BIN_M);
            t0 = t1 - c.default_width_m;
        } else {
            t0 = t0.max(face - FACE_BIN_M);
            t1 = t0 + c.default_width_m;
        }
        // A staircase hides the floor under it: floor seen where its assumed width would be
        // (past the side face) means there is none.
        let hidden_side = (t0 + t1) / 2.0;
        let line = crate::points::Line2 {
            origin: dir * (p.front1 + length / 2.0) + dir.perp() * hidden_side,
            dir,
        };
        let mut floor_seen = 0usize;
        let inner = c.default_width_m / 2.0 - 0.1;
        sc.index.for_each_near_line(
            &line,
            -length / 2.0 + 0.05,
            length / 2.0 - 0.05,
            inner.max(0.0),
            |_, _, _, z| {
                floor_seen += usize::from((z - sc.floor).abs() <= 0.03);
            },
        );
        if floor_seen > c.min_step_points {
            return None;
        }
        if !side_face_is_one_plane(pts, &p, c.min_step_points) {
            return None;
        }
        // Over its steps is open air; a face going on up is something taller's (see
        // `taller_face`).
        if face_goes_on_above(pts, &p, face, c.min_step_points) {
            return None;
        }
        // Its face ends level past its top step; a ramp's climbs on (see `climbs_on`).
        let past = PastTop {
            dir,
            across_m: face,
            end_m: p.front1 + length,
            rise_m: p.rise,
        };
        if face_climbs_on(sc, past) {
            return None;
        }
        width_rule = format!(
            "only a side face seen: width assumed {:.2} m, away from the floor seen in front of it",
            c.default_width_m
        );
    }
    let width = t1 - t0;
    // Past its top step a flight's treads end level (a landing, the floor above) or at what
    // rises beyond it; a ramp's surface, read in bands where the laser's lines cross it, climbs
    // on (see `climbs_on`).
    let middle = PastTop {
        dir,
        across_m: (t0 + t1) / 2.0,
        end_m: p.front1 + length_m(&p),
        rise_m: p.rise,
    };
    if !side_only && surface_climbs_on(sc, middle) {
        return None;
    }
    // The local point density: the floor's around the staircase (points per m² of the 10 cm
    // cells where it was seen).
    let density = floor_density(sc, dir, (p.front1, p.front1 + length_m(&p)), (t0, t1));
    // A staircase hides the floor under it (the risers close it, or the flight stands on a
    // solid base), and a laser on the floor sees none from the second step on (the first
    // one's front is fuzzed by its riser's foot); furniture whose parts happen to stand at
    // step heights (a chair's seat, a desk's top) stands on legs, and the floor between them
    // is seen. The middle half of the width is counted: the width spans 1-99 % of the points,
    // and a few stray returns beside the staircase (mixed pixels towards a wall behind it)
    // widen it over floor that is seen.
    if !side_only {
        let length = p.run * (p.steps as f64 - 1.0) - 0.05;
        let floor_seen = floor_in_strip(
            sc,
            dir,
            (p.front1 + p.run + length / 2.0, (t0 + t1) / 2.0),
            (length / 2.0, (t1 - t0) / 4.0),
        );
        // Seen at the density of the floor around it (less what its top shadows from far
        // scanners), the floor is under legs; the footprint's strip may still overlap floor
        // beside a staircase where its direction or start is off by a little, or its width
        // spans clutter beside it, but not half of it.
        let open = 0.5 * density * length * (t1 - t0) / 2.0;
        if floor_seen > c.min_step_points && floor_seen as f64 > open {
            return None;
        }
    }
    // Every step rests on points of its own: on its tread, its riser, or the side face between
    // its height and the one below (a staircase seen from its side shows its steps so).
    let mut per_step = vec![0usize; p.steps as usize];
    for (q, z) in pts {
        let (s, t) = (q.dot(dir), dir.perp_dot(*q));
        if t < t0 - 0.05 || t > t1 + 0.05 {
            continue;
        }
        if let Some(k) = step_holding(&p, s, *z) {
            per_step[k] += 1;
        }
    }
    // Seen from its side only, the lowest step's side face is a low strip at grazing angles
    // that clutter in the room hides first; the floor hidden under the whole footprint (checked
    // above) stands in for it, and its count still follows from the levels above it.
    let first_checked = usize::from(side_only && per_step.len() > c.min_steps as usize);
    // ... as many as the local point density promises on that much surface; one step may
    // fall short (see `supported`).
    let promised = c.min_step_fill * density * p.rise * p.run;
    let passes = |n: usize| n >= c.min_step_points && n as f64 >= promised;
    let checked = &per_step[first_checked..];
    let (weakest, short) = supported(checked, p.found + 1 >= p.steps, side_only, c, passes)?;
    let top_short = short == Some(checked.len() - 1);
    let short = short.map_or(String::new(), |k| {
        format!(
            "; step {} short of that ({} points)",
            k + first_checked + 1,
            checked[k]
        )
    });
    let top_depth = top_end(pts, &p, (t0, t1), sc, c) - (p.front1 + p.run * (p.steps as f64 - 1.0));
    let landing = if top_depth - p.run > 0.1 {
        top_depth - p.run
    } else {
        0.0
    };
    let start = dir * p.front1 + dir.perp() * ((t0 + t1) / 2.0);
    let rules = vec![
        format!(
            "{} of {} levels at multiples of a {:.3} m rise, climbing along {:.1} deg, their edges {:.3} m apart (the paper's parallel lines at equal spacing, each step above the previous)",
            p.found,
            p.steps,
            p.rise,
            dir.y.atan2(dir.x).to_degrees(),
            p.run
        ),
        format!("step count {} from the top level; {width_rule}", p.steps),
        format!(
            "every step supported: at least {weakest} points on its tread, riser or side{short} (rise {:.3} m within {:.2}-{:.2}, run {:.3} m within {:.2}-{:.2}, pace 2 x rise + run {:.3} m at most {:.2}: building codes' ranges)",
            p.rise, c.rise_m[0], c.rise_m[1], p.run, c.run_m[0], c.run_m[1], 2.0 * p.rise + p.run, c.max_pace_m
        ),
    ];
    Some(DetectedStairs {
        steps: p.steps,
        rise: p.rise,
        run: p.run,
        width,
        dir,
        start,
        landing,
        base: 0.0,
        support: pts.len() as u64,
        confidence: (p.found as f64 / p.steps as f64).min(1.0),
        top_short,
        rules,
    })
}

/// The fewest points on a step of those that pass, and the one step that falls short if any (its
/// index in `per_step`), where the steps' counts `per_step` (from the lowest checked) make a
/// staircase: every step passes, or all but one. Where the envelope shows every level of a flight
/// longer than the shortest, or all but one (`levels_seen`), the step that falls short may be any
/// that holds points: a side face sampled sparsely between two scans' views, or at grazing angles
/// far along a long flight seen from its top end (office-3's third step held 3 returns). On a
/// flight seen from its side only (`side_face`), a step between two that pass may fall short
/// however many levels were seen, and hold no point at all: a flight does not skip a step, and
/// clutter in front of a side face hides one (office-3 as surveyed clear of its doors' swings: 7 of
/// its 8 steps' faces seen, the third one not, and 5 of its 8 levels in the envelope). A side face
/// fills every step's band under the flight's line for a count near the true one, so an empty band
/// is a hidden step there; seen on treads and risers, an empty step is more often a count that is
/// off (office-74's upper flight read as 5 steps of 0.135 m over the true 4 of 0.158 m, its second
/// step empty).
fn supported(
    per_step: &[usize],
    levels_seen: bool,
    side_face: bool,
    c: &StairsConfig,
    passes: impl Fn(usize) -> bool,
) -> Option<(usize, Option<usize>)> {
    let short: Vec<usize> = (0..per_step.len())
        .filter(|&k| !passes(per_step[k]))
        .collect();
    let allowed = match short[..] {
        [] => true,
        [k] => {
            let between = side_face && k > 0 && k + 1 < per_step.len();
            per_step.len() > c.min_steps as usize && (between || (levels_seen && per_step[k] > 0))
        }
        _ => false,
    };
    let weakest = per_step.iter().copied().filter(|&n| passes(n)).min()?;
    allowed.then(|| (weakest, short.first().copied()))
}

/// True if the returns on the steps of a flight seen from its side only lie on one vertical
/// plane along it: each step's (the median across the flight of those on it) within
/// [`SIDE_FACE_STRAIGHT_M`] of one straight line through them all (a direction a little off
/// the face's tilts that line; a face does not bend). Steps with fewer than `min_points`
/// returns are not looked at, and fewer than three such steps show no bend. On mixed-26 a
/// crate's edge, a person's streak crossing over it diagonally and returns beside it read as
/// three levels along one direction, the steps' medians 0.17-0.18 m apart across it by
/// turns; the side faces of the bench's flights bend by 8 mm at most.
fn side_face_is_one_plane(pts: &[(DVec2, f64)], p: &Profile, min_points: usize) -> bool {
    let mut across: Vec<Vec<f64>> = vec![Vec::new(); p.steps as usize];
    for (q, z) in pts {
        let s = q.dot(p.dir);
        if let Some(k) = step_holding(p, s, *z) {
            across[k].push(p.dir.perp_dot(*q));
        }
    }
    let medians: Vec<(f64, f64)> = across
        .iter_mut()
        .enumerate()
        .filter(|(_, t)| t.len() >= min_points)
        .filter_map(|(k, t)| Some((k as f64, quantile(t, 0.5)?)))
        .collect();
    if medians.len() < 3 {
        return true;
    }
    // The least-squares line t = mean + slope (k - mean k) through the medians.
    let n = medians.len() as f64;
    let (mk, mt) = medians
        .iter()
        .fold((0.0, 0.0), |(a, b), (k, t)| (a + k / n, b + t / n));
    let sxx: f64 = medians.iter().map(|(k, _)| (k - mk).powi(2)).sum();
    let sxy: f64 = medians.iter().map(|(k, t)| (k - mk) * (t - mt)).sum();
    let slope = sxy / sxx;
    medians
        .iter()
        .all(|(k, t)| (t - mt - slope * (k - mk)).abs() <= SIDE_FACE_STRAIGHT_M)
}

/// The centre of the `bin_m` wide bin (from the smallest value) holding most of `values`,
/// the first of equals; `None` for none.
fn densest(values: &[f64], bin_m: f64) -> Option<f64> {
    let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if hi < lo {
        return None;
    }
    let n = (((hi - lo) / bin_m) as usize + 1).min(100_000);
    let mut counts = vec![0usize; n];
    for v in values {
        counts[(((v - lo) / bin_m) as usize).min(n - 1)] += 1;
    }
    let k = (0..n).max_by_key(|&k| (counts[k], std::cmp::Reverse(k)))?;
    Some(lo + (k as f64 + 0.5) * bin_m)
}

/// Of coordinates `t`, the run without a gap over [`WIDTH_GAP_M`] holding most of them.
fn densest_run(mut t: Vec<f64>) -> Vec<f64> {
    t.sort_unstable_by(f64::total_cmp);
    let mut best = 0..0;
    let mut start = 0;
    for i in 1..=t.len() {
        if i == t.len() || t[i] - t[i - 1] > WIDTH_GAP_M {
            if i - start > best.len() {
                best = start..i;
            }
            start = i;
        }
    }
    t[best].to_vec()
}

#[cfg(test)]
#[path = "plausible_tests.rs"]
mod tests;
