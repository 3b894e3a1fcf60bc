//! Staircases with a landing half-way: two straight flights in line, the second starting on
//! the first's landing. Along the direction of ascent the profile climbs, stays level for
//! longer than any tread (building codes cap a tread at 0.45 m or so, `run_m`; a landing is at
//! least as deep as the stair is wide) and climbs again. Each flight is found on its own: the
//! lower one on the points before the landing's far edge (the landing is its top level), the
//! upper one on the points from just before that edge on and across the lower one's width (the
//! two are in line), with heights measured from the landing (its foot stands there). A
//! staircase is thus reported as its flights, each with its own step count, as a building file
//! describes it (`[[stairs]]` with `base_m`).
//!
//! Either flight may be hidden or only glimpsed (a survey that saw the staircase from above,
//! or its side face past a wall). A lower flight whose own profile shows no steps is read with
//! the upper one's rise (a staircase's risers are uniform) before it counts as hidden: mixed
//! pixels level with the landing can hide a level of its running maximum. Where the lower one
//! is still no plausible staircase, the upper one is a flight on the landing if the landing
//! stands a whole number of its risers up (at least `min_steps`) and the floor before the
//! landing, where the hidden flight would stand, is not seen; where the upper one is none, the
//! lower one is a flight ending on its landing. The upper flight ends at the far edge of its
//! own top landing where something stands beyond it.
//!
//! A level stretch can also be treads above the laser that the scans missed, part way up one
//! straight flight: then the two flights fitted meet, the upper one's first riser within a
//! tread's depth of the lower one's top front edge, and their points are one flight.
use super::extend::parted_risers;
use super::floor::{floor_density, floor_in_strip};
use super::landing::{mid_landing, Landing};
use super::plausible::finish;
use super::profile::{profile, profile_near};
use super::{DetectedStairs, StairsConfig};
use crate::scene::Scene;
use glam::DVec2;

/// How far beside the lower flight's width the upper flight's points may lie (m): a side
/// face's returns spread by the range noise, and a width measured from 1-99 % of the points.
const IN_LINE_MARGIN_M: f64 = 0.15;

/// How far under the lower flight's top level a landing may be read, in its rises. The
/// landing's height is the profile's running maximum over a level stretch, where a rise that
/// the profile falls back from within a landing's depth counts as something standing on it
/// (see `landing`); a side face whose top edge over the landing is hidden (office-74, seeds 71-75: a
/// desk's top in front of it, above the laser, hid it over half the landing) falls back under
/// the flight's top step too, and the landing reads low (office-74: at 0.48 m, the top step
/// read at 0.58 m, two thirds of a rise higher). Its flight, fitted on the points before the
/// landing's far edge, still climbs to the top step: that is the landing. (More than a level
/// and a half over it is no flight climbing to it.)
const LANDING_UNDER_TOP: f64 = 1.5;

/// How far over the landing's height the lower flight's top may stand before it is fitted again
/// on the points up to that height (m): the measurement's few centimetres. Mixed pixels over a
/// landing's near edge (hall-93 of seeds 91-95: 6-8 cm over it along 0.17 m) lift the top
/// height a flight's count is fitted to, and with it its rise (4 steps of 0.205 m for 0.184 m),
/// and the upper flight, heights from that top, lost a step. Where the points up to the
/// landing show as many steps, those are the flight; where they show fewer (the landing read
/// low, see [`LANDING_UNDER_TOP`]), the first fit stands.
const OVER_LANDING_M: f64 = 0.03;

/// The flights of a staircase with a mid landing climbing along `dir`, if the points show one
/// (see the module docs): both, or the one of them that is plausible; `None` if they show no
/// mid landing or neither flight is.
pub(super) fn two_flights(
    pts: &[(DVec2, f64)],
    all: &[(DVec2, f64)],
    dir: DVec2,
    sc: &Scene,
    c: &StairsConfig,
) -> Option<Vec<DetectedStairs>> {
    // 1. The landing: the running maximum of the profile level for more than a tread, with
    //    at least `min_steps` of the lowest rise below it and a climb beyond it.
    let landing = mid_landing(pts, dir, c)?;
    let (landing_start, landing_end, landing_height) = (landing.near, landing.far, landing.height);
    // 2. The lower flight: the points before the landing's far edge.
    let (lower, lower_all) = (before(pts, dir, landing_end), before(all, dir, landing_end));
    let fit_lower = |lower: &[(DVec2, f64)], lower_all: &[(DVec2, f64)]| {
        profile(lower, lower_all, dir, c)
            .and_then(|p| finish(lower, p, sc, c))
            .filter(|f| climbs_to(f, &landing, dir, c))
    };
    let first = fit_lower(&lower, &lower_all);
    //    Where its top stands over the landing, fitted again on the points up to the landing's
    //    height (see `OVER_LANDING_M`), kept if that finds as many steps.
    let first = first.map(|f| {
        if f.rise * f64::from(f.steps) - landing_height <= OVER_LANDING_M {
            return f;
        }
        let up_to = |p: &[(DVec2, f64)]| -> Vec<(DVec2, f64)> {
            p.iter()
                .filter(|(_, z)| *z <= landing_height + OVER_LANDING_M)
                .copied()
                .collect()
        };
        let (capped, capped_all) = (up_to(&lower), up_to(&lower_all));
        match fit_lower(&capped, &capped_all) {
            Some(g) if g.steps == f.steps => g,
            _ => f,
        }
    });
    let base = match &first {
        Some(first) => first.rise * first.steps as f64,
        None => landing_height,
    };
    // The lower flight climbs to the landing: its top level is the landing's height, or stands
    // a level over the landing read where the profile fell back under its top step past the
    // edge of what hid the landing's side face (see `LANDING_UNDER_TOP`).
    if let Some(first) = &first {
        let over = base - landing_height;
        if over < -0.5 * first.rise || over > LANDING_UNDER_TOP * first.rise {
            return None;
        }
    }
    // 3. The upper flight: from a tread's depth before that edge on, heights from the landing,
    //    up to the far edge of its own top landing if something stands beyond that (a
    //    cupboard, a wall the map did not find: no part of this flight).
    //    Where the lower flight was found, the upper one climbs in line with it: its points
    //    are those across the lower one's width (and the measurement's spread); a person
    //    walking past in front of its side face, smeared into a wall of returns a landing's
    //    height up, is beside it.
    let (second, upper_end) = upper_flight(
        (pts, all),
        dir,
        landing_end - c.run_m[1],
        base,
        first.as_ref(),
        sc,
        c,
    );
    // 4. A lower flight its own profile did not show, read with the upper one's rise (a
    //    staircase's risers are uniform), where its steps climb to the landing: mixed pixels
    //    level with the landing, along rays grazing its edge, can lie over the lower flight's
    //    top treads and hide a level of the running maximum.
    let first = first.or_else(|| {
        let rise = second.as_ref()?.rise;
        profile_near(&lower, &lower_all, dir, c, Some(rise))
            .and_then(|p| finish(&lower, p, sc, c))
            .filter(|f| (f.rise * f64::from(f.steps) - landing_height).abs() <= 0.5 * f.rise)
            .filter(|f| climbs_to(f, &landing, dir, c))
    });
    match (first, second) {
        // (the level stretch was no landing: a straight flight whose middle treads the laser
        // missed, both flights one)
        (Some(first), Some(second)) if !on_its_landing(&first, &second, c) => {
            one_flight(pts, all, dir, upper_end, sc, c).map(|one| vec![one])
        }
        (Some(first), Some(mut second)) => {
            second.base = base;
            second.rules.push(format!(
                "starts on the landing of the flight below, {base:.2} m above the floor"
            ));
            Some(vec![first, second])
        }
        (Some(mut first), None) => {
            first.rules.push(
                "ends on a landing; nothing beyond it climbs as a flight of stairs".to_string(),
            );
            Some(vec![first])
        }
        (None, Some(mut second)) => {
            // The hidden flight climbed to the landing in risers like the upper one's (a
            // staircase's risers are uniform): the landing stands a whole number of them up,
            // at least a flight's worth.
            let risers = base / second.rise;
            if risers.round() < f64::from(c.min_steps) || (risers - risers.round()).abs() > 0.25 {
                return None;
            }
            // And it hid the floor it stands on, before the landing: a parked car's body top
            // read as a landing, with its cabin's front as a flight on it (fresh garage-43),
            // has open floor before it.
            let hidden_length = (risers.round() - 1.0) * c.run_m[0];
            if floor_seen_before(&second, landing_start, hidden_length, sc, c) {
                return None;
            }
            second.base = base;
            second.rules.push(format!(
                "starts on a landing {base:.2} m above the floor ({:.0} of its risers up); the flight below it is hidden or only glimpsed",
                risers.round()
            ));
            Some(vec![second])
        }
        (None, None) => None,
    }
}

/// Returns `(xy, height)`.
type Returns<'a> = &'a [(DVec2, f64)];

/// The upper flight of a staircase along `dir`: from `from` on (along `dir`), heights from
/// the landing at `base`, in line with the lower flight where that was found (`first`), up to
/// the far edge of its own top landing if something stands beyond that (see `two_flights`).
/// Also where that edge is (infinity if nothing stands beyond).
fn upper_flight(
    (pts, all): (Returns, Returns),
    dir: DVec2,
    from: f64,
    base: f64,
    first: Option<&DetectedStairs>,
    sc: &Scene,
    c: &StairsConfig,
) -> (Option<DetectedStairs>, f64) {
    let in_line = |q: DVec2| {
        first.is_none_or(|f| dir.perp_dot(q - f.start).abs() <= f.width / 2.0 + IN_LINE_MARGIN_M)
    };
    let above = |p: &[(DVec2, f64)]| -> Vec<(DVec2, f64)> {
        p.iter()
            .filter(|(q, z)| q.dot(dir) >= from && *z >= base - 0.05 && in_line(*q))
            .map(|(q, z)| (*q, z - base))
            .collect()
    };
    let (mut upper, mut upper_all) = (above(pts), above(all));
    let upper_end = mid_landing(&upper, dir, c).map_or(f64::INFINITY, |l| l.far);
    upper.retain(|(q, _)| q.dot(dir) < upper_end);
    upper_all.retain(|(q, _)| q.dot(dir) < upper_end);
    let rise = first.map(|f| f.rise);
    let second = profile_near(&upper, &upper_all, dir, c, rise).and_then(|p| {
        // (with the returns of its risers the blobs parted from it, see `parted_risers`)
        if let Some(f) = first {
            upper.extend(parted_risers(&p, &upper, f, base, sc, c));
        }
        finish(&upper, p, sc, c)
    });
    (second, upper_end)
}

/// The flight on the landing of a flight found on its own (`first`: its top level is the
/// landing), from the points `pts` and `all` beyond its top step (see `upper`): `None` where
/// they show none, or one starting within a tread's depth of its top front edge (the two
/// would be one straight flight whose middle treads the laser missed).
pub(super) fn flight_above(
    first: &DetectedStairs,
    pts: &[(DVec2, f64)],
    all: &[(DVec2, f64)],
    sc: &Scene,
    c: &StairsConfig,
) -> Option<DetectedStairs> {
    let base = first.rise * f64::from(first.steps);
    let from = first.start.dot(first.dir) + first.run * f64::from(first.steps);
    let (second, _) = upper_flight((pts, all), first.dir, from, base, Some(first), sc, c);
    let mut second = second.filter(|s| on_its_landing(first, s, c))?;
    second.base = base;
    second.rules.push(format!(
        "starts on the landing of the flight below, {base:.2} m above the floor (its risers seen from below, apart from that flight's)"
    ));
    Some(second)
}

/// True if `flight` may be the one climbing to `landing` along `dir`: where the landing was
/// read in two layers (see `landing`), its near edge is where its lower layer starts, and the
/// flight's top riser stands there, no more than the shortest tread (`run_m`) past it. A
/// landing's side face, a solid block's, holds points at every height up to its top edge, and
/// the grid search of the steps can lay a flight's treads on it: office-82 of seeds 81-85 (the
/// lower flight seen by no scan) read the landing's lower layer as a flight of 3 steps, its
/// top riser 0.47 m in from the landing's near edge.
fn climbs_to(flight: &DetectedStairs, landing: &Landing, dir: DVec2, c: &StairsConfig) -> bool {
    let top_riser = flight.start.dot(dir) + f64::from(flight.steps.saturating_sub(1)) * flight.run;
    !landing.layered || top_riser - landing.near <= c.run_m[0]
}

/// True if the upper flight starts on the lower one's landing: its first riser stands beyond
/// the lower flight's top front edge (along their direction) by more than any tread is deep
/// (`run_m`). hall-14 of the held-out styles (seed 14) read its straight 10-step flight as two
/// flights of 5, the upper one's first riser 3 cm past the lower one's top front edge: the level
/// stretch part way up was treads the laser missed.
fn on_its_landing(first: &DetectedStairs, second: &DetectedStairs, c: &StairsConfig) -> bool {
    let top_front = f64::from(first.steps.saturating_sub(1)) * first.run;
    (second.start - first.start).dot(first.dir) - top_front > c.run_m[1]
}

/// The flights of a staircase read as two where its treads in the middle were missed, as one:
/// the points before `end` (where the upper flight's top landing ends and something stands
/// beyond it).
fn one_flight(
    pts: &[(DVec2, f64)],
    all: &[(DVec2, f64)],
    dir: DVec2,
    end: f64,
    sc: &Scene,
    c: &StairsConfig,
) -> Option<DetectedStairs> {
    let (pts, all) = (before(pts, dir, end), before(all, dir, end));
    let mut one = profile(&pts, &all, dir, c).and_then(|p| finish(&pts, p, sc, c))?;
    one.rules.push(
        "one flight: the level stretch part way up is shorter than a landing once both parts are fitted"
            .to_string(),
    );
    Some(one)
}

/// The points `(xy, height)` before `end` along `dir`.
pub(super) fn before(pts: &[(DVec2, f64)], dir: DVec2, end: f64) -> Vec<(DVec2, f64)> {
    pts.iter()
        .filter(|(q, _)| q.dot(dir) < end)
        .copied()
        .collect()
}

/// True if the floor is seen, at the density of the floor around, over the middle half of
/// `upper`'s width along the `length` before `landing_start` (along its direction): where a
/// flight hidden under a landing would stand.
fn floor_seen_before(
    upper: &DetectedStairs,
    landing_start: f64,
    length: f64,
    sc: &Scene,
    c: &StairsConfig,
) -> bool {
    let dir = upper.dir;
    let t = dir.perp_dot(upper.start);
    let (t0, t1) = (t - upper.width / 2.0, t + upper.width / 2.0);
    let s = (landing_start - length, landing_start);
    let density = floor_density(sc, dir, s, (t0, t1));
    let floor_seen = floor_in_strip(
        sc,
        dir,
        ((s.0 + s.1) / 2.0, t),
        (length / 2.0, upper.width / 4.0),
    );
    let open = 0.5 * density * length * upper.width / 2.0;
    floor_seen > c.min_step_points && floor_seen as f64 > open
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flight of `steps` climbing +X from `start_x` on a base `base` m up (rise 0.17 m,
    /// run 0.28 m).
    fn flight(start_x: f64, steps: u32, base: f64) -> DetectedStairs {
        DetectedStairs {
            width: 1.1,
            base,
            ..DetectedStairs::straight(start_x, steps, 0.17, 0.28)
        }
    }

    #[test]
    fn an_upper_flight_starts_on_a_landing_deeper_than_a_tread() {
        let c = StairsConfig::default();
        // Lower flight: 5 steps from x = 0, its top front edge at 4 runs (1.12 m).
        let lower = flight(0.0, 5, 0.0);
        // A 1 m landing, then the upper flight: one staircase with a mid landing.
        assert!(on_its_landing(&lower, &flight(2.12, 5, 0.85), &c));
        // The upper flight's first riser 3 cm past the lower one's top front edge (hall-14):
        // no landing between them.
        assert!(!on_its_landing(&lower, &flight(1.15, 5, 0.85), &c));
        // A tread's depth past it (the longest tread allowed) is still no landing.
        assert!(!on_its_landing(
            &lower,
            &flight(1.12 + c.run_m[1] - 0.01, 5, 0.85),
            &c
        ));
    }
}
