//! Where a flight's top level (its landing) ends along its direction (see the `stairs`
//! module).

use super::floor::floor_in_strip;
use super::profile::Profile;
use super::StairsConfig;
use crate::points::quantile;
use crate::scene::Scene;
use glam::DVec2;

/// A stretch along a flight's top level this long without returns on it is looked under: a
/// landing hides the floor under it, so floor seen there is past the landing's end (a laser
/// samples a landing's top, or its side face's top edge, a few centimetres apart, but at
/// grazing angles or past an occluder the gaps reach 0.3 m: bench hall-7).
pub(super) const LANDING_GAP_M: f64 = 0.1;

/// Where a flight's top level ends along its direction: the returns at the top level (within
/// half a rise of it) across the flight's width `t`, from the top step's front on until a gap
/// between them (over [`LANDING_GAP_M`]) shows the floor in the middle half of the width (more
/// than `min_step_points` returns), their 99th percentile (a stray or two over the far edge).
/// Returns higher than that over the landing (a handrail, a person, a chair's backrest) and
/// things past the floor beyond it (office-244 of seeds 241-245: a chair 0.3 m past a landing's
/// end, its seat and legs at the landing's height, its backrest two rises over it, read as
/// 0.4 m more landing) are not the landing.
pub(super) fn top_end(
    pts: &[(DVec2, f64)],
    p: &Profile,
    t: (f64, f64),
    sc: &Scene,
    c: &StairsConfig,
) -> f64 {
    let top = f64::from(p.steps) * p.rise;
    let top_front = p.front1 + p.run * (f64::from(p.steps) - 1.0);
    let mut along: Vec<f64> = pts
        .iter()
        .filter(|(q, z)| {
            let across = p.dir.perp_dot(*q);
            (z - top).abs() <= p.rise / 2.0 && across >= t.0 - 0.05 && across <= t.1 + 0.05
        })
        .map(|(q, _)| q.dot(p.dir))
        .filter(|&s| s >= top_front)
        .collect();
    along.sort_by(f64::total_cmp);
    let floor_between = |a: f64, b: f64| {
        let centre = ((a + b) / 2.0, (t.0 + t.1) / 2.0);
        floor_in_strip(sc, p.dir, centre, ((b - a) / 2.0, (t.1 - t.0) / 4.0))
    };
    let mut end = top_front;
    let mut run: Vec<f64> = along
        .into_iter()
        .take_while(|&s| {
            let on = s - end <= LANDING_GAP_M || floor_between(end, s) <= c.min_step_points;
            end = end.max(s);
            on
        })
        .collect();
    quantile(&mut run, 0.99).unwrap_or(top_front)
}

/// Bins along a flight (m) in which [`level_runs_on`] reads the highest return.
const LEVEL_BIN_M: f64 = 0.05;

/// True if the highest returns across a flight's width (`across`, centre and half-width)
/// stand at `level_m` (within a quarter `rise_m`) all along `from..to` along `dir`: in four
/// fifths of the [`LEVEL_BIN_M`] bins holding returns, and at least half the bins hold some.
/// A flight read again without its top step (see `Search`) claims a landing there one rise
/// under that level; a level running flat one rise over it all the way is the dropped step's
/// tread and what can be seen of the landing beyond it (office-441 of seeds 441-445: a 4-step
/// flight seen from its side only through a doorway, its side face's top edge seen 9 cm past
/// its top step, read as 3 steps whose "landing" was the fourth step's side face under its
/// top edge). Something standing at a flight's top (a person) stands higher than one rise,
/// or over part of it only.
pub(super) fn level_runs_on(
    pts: &[(DVec2, f64)],
    dir: DVec2,
    across: (f64, f64),
    (from, to): (f64, f64),
    level_m: f64,
    rise_m: f64,
) -> bool {
    let bins = ((to - from) / LEVEL_BIN_M).floor();
    if !(1.0..=1000.0).contains(&bins) {
        return false;
    }
    let mut highest = vec![f64::NEG_INFINITY; bins as usize];
    for (q, z) in pts {
        let (s, t) = (q.dot(dir), dir.perp_dot(*q));
        if (t - across.0).abs() > across.1 || s < from || s >= to {
            continue;
        }
        let k = (((s - from) / LEVEL_BIN_M) as usize).min(highest.len() - 1);
        highest[k] = highest[k].max(*z);
    }
    let read: Vec<f64> = highest.into_iter().filter(|z| z.is_finite()).collect();
    let at = read
        .iter()
        .filter(|&&z| (z - level_m).abs() <= rise_m / 4.0)
        .count();
    2 * read.len() >= bins as usize && 5 * at >= 4 * read.len()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::points::XyIndex;
    use crate::stairs::tests::over_floor;

    /// 3 steps of 0.15 m x 0.3 m climbing +X from x = 0, 1 m wide (y 0..1), their top level
    /// running on to x = 1.9 (a 1 m landing), sampled every 2 cm but for `unsampled` (along),
    /// with `beyond` added; the floor seen everywhere but under the flight and its landing.
    /// Where `top_end` puts the top level's end.
    fn end_of(unsampled: (f64, f64), beyond: &[(DVec2, f64)]) -> f64 {
        let (rise, run) = (0.15, 0.3);
        let mut pts: Vec<(DVec2, f64)> = Vec::new();
        for i in 0..95 {
            let x = 0.01 + 0.02 * f64::from(i);
            let top = rise * ((x / run).floor() + 1.0).min(3.0);
            if x > unsampled.0 && x < unsampled.1 {
                continue;
            }
            for j in 0..50 {
                pts.push((DVec2::new(x, 0.01 + 0.02 * f64::from(j)), top));
            }
        }
        pts.extend_from_slice(beyond);
        let hidden = DVec2::new(1.9, 1.0);
        let points = over_floor(&pts, DVec2::new(-1.0, -2.0), (125, 100), hidden);
        let index = XyIndex::new(&points, DVec2::splat(-3.0), DVec2::splat(5.0), 0.25);
        let sc = Scene::with_one_index(&points, &index, 0.0, 2.5);
        let p = Profile {
            dir: DVec2::X,
            rise,
            run,
            front1: 0.0,
            steps: 3,
            found: 3,
            score: 3.0,
            fit_score: 0.0,
        };
        top_end(&pts, &p, (0.0, 1.0), &sc, &StairsConfig::default())
    }

    /// Regression (office-244 of seeds 241-245): a chair 0.3 m past a 3-step flight's landing,
    /// its seat at the landing's height and its backrest two rises over it, was read as more
    /// landing, and the staircase's box took the chair in. The floor seen between them ends
    /// the landing.
    #[test]
    fn a_chair_past_a_landing_with_floor_between_is_no_landing() {
        let mut chair: Vec<(DVec2, f64)> = Vec::new();
        for i in 0..23 {
            let x = 2.2 + 0.02 * f64::from(i);
            for j in 0..23 {
                chair.push((DVec2::new(x, 0.3 + 0.02 * f64::from(j)), 0.45));
            }
        }
        for j in 0..23 {
            for k in 0..20 {
                chair.push((
                    DVec2::new(2.65, 0.3 + 0.02 * f64::from(j)),
                    0.47 + 0.02 * f64::from(k),
                ));
            }
        }
        let end = end_of((0.0, 0.0), &chair);
        assert!((end - 1.9).abs() < 0.05, "end {end}");
    }

    /// A landing whose returns leave a gap (grazing angles, an occluder: bench hall-7's 0.3 m)
    /// over the floor it hides goes on past the gap.
    #[test]
    fn a_gap_in_a_landings_returns_over_no_floor_does_not_end_it() {
        let end = end_of((1.2, 1.5), &[]);
        assert!((end - 1.9).abs() < 0.05, "end {end}");
    }

    /// A level one rise over a stretch, read in every bin, runs on; one with a person on part
    /// of it (standing higher), one seen over under half of the stretch, or one a rise lower,
    /// does not.
    #[test]
    fn a_level_runs_on_where_its_highest_returns_stand_all_along() {
        let (rise, level) = (0.17, 0.68);
        let face = |from: f64, to: f64, top: f64| -> Vec<(DVec2, f64)> {
            let n = ((to - from) / 0.01).round() as usize;
            (0..n)
                .flat_map(|i| {
                    let x = from + 0.01 * i as f64;
                    // (a side face: returns from the floor up to its top edge)
                    (0..=10).map(move |k| (DVec2::new(x, 0.03), top * f64::from(k) / 10.0))
                })
                .collect()
        };
        let runs_on = |pts: &[(DVec2, f64)]| {
            level_runs_on(pts, DVec2::X, (0.5, 0.55), (1.0, 1.35), level, rise)
        };
        assert!(runs_on(&face(1.0, 1.35, level)));
        let mut person = face(1.0, 1.35, level);
        person.extend(face(1.15, 1.3, 1.2));
        assert!(!runs_on(&person));
        assert!(!runs_on(&face(1.0, 1.15, level)));
        assert!(!runs_on(&face(1.0, 1.35, level - rise)));
    }
}
