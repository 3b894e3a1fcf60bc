//! A part's staircase search (see the `stairs` module): the best staircase (or the two flights
//! of one with a mid landing) along the part's candidate directions; where it shows none, the
//! best along each of its straight faces in plan, each on its own (see `side_faces`).

use super::levels::ON_A_LEVEL;
use super::plausible::finish;
use super::profile::{profile, profile_other_count, profile_up_to_plateau, Profile};
use super::top_end::level_runs_on;
use super::{flights, side_faces, DetectedStairs, StairsConfig};
use crate::scene::Scene;
use glam::DVec2;
use rayon::prelude::*;

/// A part's points and where to look for a staircase in them.
#[derive(Clone, Copy)]
pub(super) struct Search<'a> {
    /// The part's returns on surfaces `(xy, height above the floor)`: its levels and support.
    pub pts: &'a [(DVec2, f64)],
    /// All of its returns (the fits' edges).
    pub all: &'a [(DVec2, f64)],
    /// The candidate directions of ascent.
    pub cands: &'a [DVec2],
    /// How many of the first `cands` are the walls' directions (or square to them).
    pub walls_cands: usize,
    /// The whole scene (the floor beside a flight, seen or hidden).
    pub sc: &'a Scene<'a>,
    /// The stage's parameters.
    pub c: &'a StairsConfig,
}

impl Search<'_> {
    /// The part's staircase; where it shows none, the best of its straight faces' (in
    /// parallel: a large part, a garage's row of cars, has dozens of faces). Where the part's
    /// staircase climbs along a direction of its own (no wall's), a face's staircase along a
    /// wall's direction wins if it has as many flights and steps at least (see
    /// [`square_to_the_walls`]).
    pub(super) fn stairs(&self) -> Option<Vec<DetectedStairs>> {
        let Some(part) = self.best() else {
            return self.faces();
        };
        if self.along_a_wall(&part) {
            return Some(part);
        }
        match self.faces() {
            Some(face) if self.along_a_wall(&face) && square_to_the_walls(&face, &part) => {
                Some(face)
            }
            _ => Some(part),
        }
    }

    /// True if `flights` climb along one of the walls' candidate directions.
    fn along_a_wall(&self, flights: &[DetectedStairs]) -> bool {
        let cos = self.c.snap_direction_deg.to_radians().cos();
        flights.first().is_some_and(|f| {
            self.cands[..self.walls_cands]
                .iter()
                .any(|d| d.dot(f.dir) >= cos)
        })
    }

    /// The best staircase of the part's straight faces, each on its own (see `side_faces`).
    fn faces(&self) -> Option<Vec<DetectedStairs>> {
        side_faces::side_faces(self.pts, self.cands, self.walls_cands, self.c)
            .into_par_iter()
            .filter_map(|face| {
                let (pts, all) = (face.select(self.pts), face.select(self.all));
                let cands = [face.dir, -face.dir];
                Search {
                    pts: &pts,
                    all: &all,
                    cands: &cands,
                    walls_cands: face.walls_cands(),
                    ..*self
                }
                .best()
            })
            .max_by(|a, b| confidence(a).total_cmp(&confidence(b)))
    }

    /// The best staircase along one of the candidate directions.
    fn best(&self) -> Option<Vec<DetectedStairs>> {
        // A staircase with a landing half-way is its two flights (see `flights`): the
        // direction that shows both, else one flight (see below). (The directions in
        // parallel too: one large blob, a row of parked cars, would otherwise keep one
        // thread busy while the others wait.)
        let flights: Vec<(bool, Vec<DetectedStairs>)> = self
            .cands
            .par_iter()
            .enumerate()
            .filter_map(|(k, &dir)| {
                flights::two_flights(self.pts, self.all, dir, self.sc, self.c)
                    .map(|f| (k < self.walls_cands, f))
            })
            .collect();
        // Of as many flights, a wall's direction first (as for one flight, below). A lone
        // flight (the other one not found) competes with the search for one flight below,
        // which compares every direction's fit: the first direction that shows something
        // beyond a flight's top landing as a second flight's start, or a level stretch
        // part way up a flight seen obliquely as a landing, need not be the flight's.
        let most = flights.iter().map(|f| f.1.len()).max().unwrap_or(0);
        // (the first along a wall's direction, else the first)
        let chosen = flights
            .into_iter()
            .filter(|f| f.1.len() == most)
            .min_by_key(|f| !f.0);
        let mut lone = None;
        if let Some(f) = chosen {
            if most >= 2 {
                return Some(f.1);
            }
            lone = Some(f);
        }
        let mut profs: Vec<_> = self
            .cands
            .par_iter()
            .enumerate()
            .filter_map(|(k, &dir)| {
                profile(self.pts, self.all, dir, self.c).map(|r| (k < self.walls_cands, r))
            })
            .collect();
        // The most levels that make a plausible staircase (a direction oblique to a face
        // seen from its side reads as steps too, but not as a staircase people climb); of
        // as many, a wall's direction (a staircase is built square to the walls around it:
        // the blob's own axes lean towards whatever stands beside it, and the edges of a
        // staircase seen obliquely, smeared over a few bins, can still fit as well), then
        // the best fit, then the first direction.
        profs.sort_by(|(wa, a), (wb, b)| {
            b.found
                .cmp(&a.found)
                .then(wb.cmp(wa))
                .then(b.score.total_cmp(&a.score))
        });
        let one = profs.into_iter().find_map(|(on_wall, p)| {
            // A staircase is built square to the walls around it. Along a direction of the
            // part's own, every level must be seen: furniture of assorted heights (a desk, a
            // chair's seat and back, a box beside them: fresh office-44) shows levels at
            // multiples of some rise along some direction, with one or more missing.
            if !on_wall && p.found < p.steps {
                return None;
            }
            // (another step count, fitted along the chosen direction only, wins where it fits
            // better, finds as large a share of its levels and still makes a staircase: see
            // `profile_other_count`)
            let (dir, fit_score) = (p.dir, p.fit_score);
            let share = levels_share(&p);
            // (where it makes no staircase along a wall's direction, the count up to its top
            // level's plateau may: see `profile_up_to_plateau`)
            let one = finish(self.pts, p, self.sc, self.c).or_else(|| {
                on_wall
                    .then(|| profile_up_to_plateau(self.pts, self.all, dir, self.c))
                    .flatten()
                    .and_then(|q| finish(self.pts, q, self.sc, self.c))
            })?;
            let other = profile_other_count(self.pts, self.all, dir, fit_score, self.c)
                .filter(|o| levels_share(o) >= share)
                .and_then(|o| finish(self.pts, o, self.sc, self.c));
            Some((on_wall, self.ending_on_a_level(other.unwrap_or(one))))
        });
        // The lone flight wins if it is along a wall's direction or the one flight is not,
        // and it found as large a share of its levels (on a tie: a staircase with a mid
        // landing read as one flight misses a level), unless the one flight climbs on through
        // its landing (see `climbs_through`) or up to it (see `climbs_up_to`).
        match (one, lone) {
            (Some((one_on_wall, one)), Some((lone_on_wall, lone)))
                if (lone_on_wall || !one_on_wall)
                    && lone.iter().all(|l| l.confidence >= one.confidence)
                    && !climbs_through(&one, &lone, self.c)
                    && !climbs_up_to(&one, &lone, self.c) =>
            {
                Some(lone)
            }
            (Some((_, one)), _) => Some(vec![one]),
            (None, lone) => lone.map(|l| l.1),
        }
    }

    /// The flight `f`, or, where its top step may be something standing at its top, the
    /// flight read again without it, if that shows fewer steps ending on a level with every
    /// step supported. A flight ends on a level (its landing, or the floor above) at least as
    /// deep as it is wide, and its top step's face, the landing's, is seen as well as the
    /// others'. A top step with no level beyond it (its top level ending within a run past its
    /// front), or the one step short of support, may be what stands there: office-353 of
    /// seeds 351-355, a person beside a 4-step flight's landing in one scan, 0.3 m over it, read
    /// as 6 steps of 0.167 m for 4 of 0.181 m, the top one with no landing; garage-341 of seeds
    /// 341-345, what a person left over a 4-step flight's landing read as a fifth step of the
    /// same rise, 4 points on it. Read again on the points before that step, then on those
    /// under its level (over the landing, a quarter of a rise up); where neither reading ends
    /// on a level (a flight whose top the laser did not see), the first stands.
    fn ending_on_a_level(&self, f: DetectedStairs) -> DetectedStairs {
        if (f.landing > 0.0 && !f.top_short) || f.steps <= self.c.min_steps {
            return f;
        }
        let top_front = f.start.dot(f.dir) + f.run * f64::from(f.steps - 1);
        let under = (f64::from(f.steps - 1) + ON_A_LEVEL) * f.rise;
        let before = |p: &[(DVec2, f64)]| flights::before(p, f.dir, top_front);
        let below = |p: &[(DVec2, f64)]| -> Vec<(DVec2, f64)> {
            p.iter().filter(|(_, z)| *z <= under).copied().collect()
        };
        let read = |pts: Vec<(DVec2, f64)>, all: Vec<(DVec2, f64)>| {
            profile(&pts, &all, f.dir, self.c)
                .and_then(|p| finish(&pts, p, self.sc, self.c))
                .filter(|g| g.landing > 0.0 && !g.top_short && g.steps < f.steps)
                .filter(|g| f.top_short || !dropped_step_runs_on(&f, g, self.all))
        };
        read(before(self.pts), before(self.all))
            .or_else(|| read(below(self.pts), below(self.all)))
            .map(|mut g| {
                g.rules.push(format!(
                    "read again without the top step of {} found first, {} (something standing at the top)",
                    f.steps,
                    if f.top_short { "short of support" } else { "with no level beyond it" }
                ));
                g
            })
            .unwrap_or(f)
    }
}

/// True if `f`'s top level runs flat over all of the landing `g` (`f` read again without its
/// top step) claims (see `top_end::level_runs_on`): that step is a tread, no thing standing.
fn dropped_step_runs_on(f: &DetectedStairs, g: &DetectedStairs, pts: &[(DVec2, f64)]) -> bool {
    let from = g.start.dot(g.dir) + g.run * f64::from(g.steps);
    let across = (g.dir.perp_dot(g.start), g.width / 2.0 + 0.05);
    let level = f.base + f.rise * f64::from(f.steps);
    level_runs_on(pts, g.dir, across, (from, from + g.landing), level, f.rise)
}

/// True if `one` (a flight read along all of a part) is the lone flight `lone` (a flight
/// found ending on a landing, nothing beyond it climbing as a flight) continued, in the same
/// steps, through what was read as its landing: `lone` is one flight from the floor, and `one`
/// starts where it starts, climbs the same way in the same steps (the lone flight's landing is
/// one of its levels, within [`ON_A_LEVEL`] of a rise), has more steps, a bin on every one of
/// its levels, and steps past the lone flight's top step (over what was read as its landing).
/// A mid landing read as steps would leave the levels on it empty (a landing is deeper than a
/// tread, and level); here the "landing" was a tread with something beside the flight standing
/// a rise over it (office-101 of seeds 101-105: a 1 m box beside the side face of a 7-step
/// flight, over its third and fourth steps, held the running maximum level for 0.8 m, and the
/// flight read as 6 steps). A flight read along all of a part in other steps climbs through
/// nothing: returns over the far edge of the lone flight's top landing (mixed pixels where rays
/// rising past it met the wall behind) set its top high, and the count climbing to them cut
/// the flight into more, lower steps (office-117 of seeds 116-120: 5 steps of 0.172 m x
/// 0.255 m, every level seen, lost to 6 of 0.160 m x 0.200 m whose top riser stood where the 5
/// steps' did; office-43 scanned again on 2026-12-04: 4 steps of 0.185 m lost to 5 of 0.172
/// m, whose fourth level lay 5 cm under the landing).
fn climbs_through(one: &DetectedStairs, lone: &[DetectedStairs], c: &StairsConfig) -> bool {
    let [lone] = lone else {
        return false;
    };
    let same_start = (one.start - lone.start).dot(one.dir).abs() <= one.run.min(lone.run) / 2.0;
    // (its steps go on past the lone flight's top step, over what was read as its landing)
    let top_front =
        |f: &DetectedStairs| f.start.dot(one.dir) + f64::from(f.steps.saturating_sub(1)) * f.run;
    let past_its_top = top_front(one) - top_front(lone) >= lone.run / 2.0;
    lone.base == 0.0
        && one.base == 0.0
        && same_way_and_steps(one, lone, c)
        && same_start
        && one.steps > lone.steps
        && past_its_top
        && one.confidence >= 1.0
}

/// True if `one` (a flight read along all of a part, from the floor) is the lone flight `lone`
/// (a flight found on a landing, the flight below it hidden or only glimpsed) with the steps
/// below it seen after all: `one` climbs the same way in the same steps, the landing is one of
/// its levels (within [`ON_A_LEVEL`] of a rise), it ends at the lone flight's top level, starts
/// before it, and has a bin on every one of its levels, those under the landing too. A mid
/// landing read as steps would leave the levels on it empty, and a hidden flight's levels have
/// none; here the "landing" was a tread with something over it (hall-125 of seeds 121-125: a
/// 0.2 m stretch of mixed pixels 0.22 m over the fourth tread of an 11-step flight, seen from
/// its side, and the sixth tread beyond it, 6 cm higher, read as a landing in two voxel layers;
/// the flight read as its upper 5 steps on a landing with the flight below it hidden, though the
/// profile along all of it found all 11 levels).
fn climbs_up_to(one: &DetectedStairs, lone: &[DetectedStairs], c: &StairsConfig) -> bool {
    let [lone] = lone else {
        return false;
    };
    // (the landing on one of its levels, and the two tops one level)
    let on_a_level = |h: f64| (h / one.rise - (h / one.rise).round()).abs() <= ON_A_LEVEL;
    let one_top = one.rise * f64::from(one.steps);
    let lone_top = lone.base + lone.rise * f64::from(lone.steps);
    let same_top = (one_top - lone_top).abs() <= ON_A_LEVEL * one.rise;
    let starts_before = (lone.start - one.start).dot(one.dir) >= one.run;
    lone.base > 0.0
        && one.base == 0.0
        && same_way_and_steps(one, lone, c)
        && on_a_level(lone.base)
        && same_top
        && starts_before
        && one.steps > lone.steps
        && one.confidence >= 1.0
}

/// True if `one` climbs the way `lone` does in its steps: their directions within the
/// snapping angle, and their rises so near that `one`'s level at the lone flight's top (its
/// landing, or its top level) lies within [`ON_A_LEVEL`] of a rise of it.
fn same_way_and_steps(one: &DetectedStairs, lone: &DetectedStairs, c: &StairsConfig) -> bool {
    let same_way = one.dir.dot(lone.dir) >= c.snap_direction_deg.to_radians().cos();
    let same_steps = (one.rise - lone.rise).abs() * f64::from(lone.steps) <= ON_A_LEVEL * lone.rise;
    same_way && same_steps
}

/// The share of a profile's levels with a bin on them. Another step count must find as large a
/// share as the count it would replace: a flight seen from below, its upper treads hidden
/// above the laser, shows mixed pixels over each tread (rays grazing a nosing, on to the next
/// riser), and a count of fewer, higher steps lets them all lie under its levels, fitting the
/// envelope better while missing levels of its own (hall-72 of the blind seeds: 12 steps of
/// 0.188 m, every level seen, read as 11 of 0.203 m with one level missing).
fn levels_share(p: &Profile) -> f64 {
    f64::from(p.found) / f64::from(p.steps.max(1))
}

/// True if `face`, a staircase read on one straight face of a part along a wall's direction,
/// replaces `part`, the part's own reading along a direction of its own: it has as many
/// flights at least, and as many steps in all. A staircase is built square to the walls
/// around it, and a reading along a direction of the part's own explains no more of it:
/// office-462 of seeds 461-465, a staircase with a mid landing (two flights of 4 steps) seen
/// from its side only, joined by a desk and a chair into one part, read as its upper flight
/// alone, 16 degrees off (the clutter's axis), where its side face alone shows both flights
/// climbing square to the walls.
fn square_to_the_walls(face: &[DetectedStairs], part: &[DetectedStairs]) -> bool {
    let steps = |f: &[DetectedStairs]| f.iter().map(|s| s.steps).sum::<u32>();
    face.len() >= part.len() && steps(face) >= steps(part)
}

/// The least confidence of a staircase's flights.
fn confidence(flights: &[DetectedStairs]) -> f64 {
    flights.iter().map(|f| f.confidence).fold(1.0, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flight climbing +X from x = 0 on the floor, every level seen.
    fn flight(steps: u32, rise: f64, run: f64) -> DetectedStairs {
        DetectedStairs::straight(0.0, steps, rise, run)
    }

    #[test]
    fn a_flight_climbs_through_a_landing_only_in_the_same_steps_and_past_its_top() {
        let c = StairsConfig::default();
        let lone = [flight(6, 0.156, 0.31)];
        // office-101: the same steps, one more, its top riser a run past the lone flight's.
        assert!(climbs_through(&flight(7, 0.156, 0.31), &lone, &c));
        // office-43: one more step of a rise 7 % lower, its sixth level 6 cm under the landing.
        assert!(!climbs_through(&flight(7, 0.146, 0.31), &lone, &c));
        // Levels on the lone flight's, but the same length cut into more, shorter treads: its
        // top riser stands where the lone flight's does (office-117's shape).
        assert!(!climbs_through(&flight(7, 0.156, 0.258), &lone, &c));
        // A level missed, or no more steps: no continuation either.
        let mut missed = flight(7, 0.156, 0.31);
        missed.confidence = 6.0 / 7.0;
        assert!(!climbs_through(&missed, &lone, &c));
        assert!(!climbs_through(&flight(6, 0.156, 0.31), &lone, &c));
    }

    #[test]
    fn a_flight_climbs_up_to_a_landing_only_in_the_same_steps_to_the_same_top() {
        let c = StairsConfig::default();
        // hall-125: the upper 5 of 11 steps read on a "landing" 6 rises up.
        let mut upper = flight(5, 0.158, 0.22);
        (upper.base, upper.start) = (0.932, DVec2::new(1.59, 0.0));
        let lone = [upper.clone()];
        assert!(climbs_up_to(&flight(11, 0.157, 0.266), &lone, &c));
        // A real mid landing: the flight from the floor misses the levels on it.
        let mut missed = flight(11, 0.157, 0.266);
        missed.confidence = 9.0 / 11.0;
        assert!(!climbs_up_to(&missed, &lone, &c));
        // Other steps, or a top a rise away, are no such flight.
        assert!(!climbs_up_to(&flight(13, 0.133, 0.22), &lone, &c));
        assert!(!climbs_up_to(&flight(10, 0.157, 0.266), &lone, &c));
        // A landing between two of its levels, the steps on it of another rise.
        let mut between = upper;
        between.base = 0.85;
        between.rise = 0.1745;
        assert!(!climbs_up_to(&flight(11, 0.157, 0.266), &[between], &c));
        // A flight on the floor is no lone flight on a landing.
        assert!(!climbs_up_to(
            &flight(11, 0.157, 0.266),
            &[flight(5, 0.157, 0.266)],
            &c
        ));
    }
}
