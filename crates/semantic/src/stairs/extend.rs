//! A flight's risers, seen alone: its top one, and one between its steps. From the floor below,
//! an upper flight shows its risers
//! (their faces turned to the laser) and, where the laser sees it, its side face; its treads
//! are above the laser. The risers stand a run apart in plan, and where the side face is
//! unseen near the top the height map's blobs (pixels within two of each other) part them: the
//! flight's blob ends a step short of its top, and the top riser is a blob of its own, too
//! small for a staircase. So each flight is looked at one run past its top step's front: a
//! riser standing there is one more step. A riser is points on a face across the flight
//! (covering at least half its width, in bins of 10 cm: a few mixed pixels strung along the
//! landing's front edge span the width but cover little of it), between its top tread's height
//! and one rise above it, its top edge at that rise, and nothing standing right above it (a
//! person on the landing, a cupboard, a wall beyond the flight stand higher). A riser between
//! two steps whose returns end short of the side face is parted from the flight's blob too,
//! and leaves its step with no support of the flight's own (see [`parted_risers`]).

use super::plausible::step_holding;
use super::profile::Profile;
use super::{DetectedStairs, StairsConfig};
use crate::points::Line2;
use crate::scene::Scene;
use glam::DVec2;

/// A riser's points lie this far either side of its front edge along the flight (its face,
/// the range noise, a voxel's centroid).
const RISER_BAND_M: f64 = 0.05;
/// Points right above the riser's top edge, from this high over it ...
const ABOVE_FROM_M: f64 = 0.06;
/// ... to this high: more than a quarter of the riser's count there is something standing on
/// the flight's top, not a riser.
const ABOVE_TO_M: f64 = 0.6;
/// The riser's points cover at least this fraction of the flight's width ...
const MIN_COVER: f64 = 0.5;
/// ... in bins this wide across the flight: about a rotating laser's sample spacing at 10 m.
pub(super) const COVER_BIN_M: f64 = 0.1;

/// Adds the steps whose risers stand one run past the flight's top (see the module docs);
/// `usable(i)` is true for the points the height map holds (not in a wall's slab, between the
/// floor and the height map's top).
pub(super) fn extend_top(
    st: &mut DetectedStairs,
    sc: &Scene,
    usable: impl Fn(usize) -> bool,
    c: &StairsConfig,
) {
    let line = Line2 {
        origin: st.start,
        dir: st.dir,
    };
    let half = st.width / 2.0;
    let foot = sc.floor + st.base;
    while st.steps < 64 {
        let k = f64::from(st.steps);
        let seen = Riser {
            front_m: k * st.run,
            heights_m: (foot + k * st.rise, foot + (k + 1.0) * st.rise),
        }
        .seen(sc, &line, half, &usable, c);
        let Some(on_riser) = seen.map(|r| r.len()) else {
            return;
        };
        st.steps += 1;
        st.landing = (st.landing - st.run).max(0.0);
        st.top_short = false;
        st.rules.push(format!(
            "step {} from its riser one run past the step below ({on_riser} points; its tread above the laser unseen)",
            st.steps
        ));
    }
}

/// A riser to look for: its front edge along a flight's line and the heights of the treads
/// below and above it (over the floor's, absolute).
pub(super) struct Riser {
    /// Its front edge along the line (m).
    pub front_m: f64,
    /// The tread below it and its own top edge.
    pub heights_m: (f64, f64),
}

impl Riser {
    /// The returns of a riser standing here (see the module docs: points on a face across the
    /// flight, `half` either side of `line`, covering [`MIN_COVER`] of it, its top edge at its
    /// height and nothing standing right above it), among the points `usable(i)` holds;
    /// `None` where none stands.
    pub(super) fn seen(
        &self,
        sc: &Scene,
        line: &Line2,
        half: f64,
        usable: impl Fn(usize) -> bool,
        c: &StairsConfig,
    ) -> Option<Vec<usize>> {
        let (below, top) = self.heights_m;
        let bins = ((2.0 * half / COVER_BIN_M).ceil() as usize).clamp(1, 1000);
        let (mut on_riser, mut above) = (Vec::new(), 0usize);
        let mut highest = f64::NEG_INFINITY;
        let mut covered = vec![false; bins];
        sc.index.for_each_near_line(
            line,
            self.front_m - RISER_BAND_M,
            self.front_m + RISER_BAND_M,
            half,
            |i, _, t, z| {
                if !usable(i) {
                    return;
                }
                if z > below + 0.02 && z <= top + 0.03 {
                    on_riser.push(i);
                    highest = highest.max(z);
                    let bin = ((t + half) / COVER_BIN_M)
                        .floor()
                        .clamp(0.0, (bins - 1) as f64);
                    covered[bin as usize] = true;
                } else if z > top + ABOVE_FROM_M && z <= top + ABOVE_TO_M {
                    above += 1;
                }
            },
        );
        let is_riser = on_riser.len() >= c.min_step_points
            && highest >= top - 0.035
            && covered.iter().filter(|&&b| b).count() as f64 >= MIN_COVER * bins as f64
            && above * 4 <= on_riser.len();
        is_riser.then_some(on_riser)
    }
}

/// The returns of an upper flight's risers that the blobs parted from the rest of it, on the
/// steps of its profile `p` that none of its returns `pts` (heights over the landing, `base`
/// over the floor) lie on, across the width of the flight below it (`lower`), heights over the
/// landing. Seen from the floor below, an upper flight's risers are lines a run apart, joined
/// to one blob by its side face; a riser whose returns end short of the side face (what stood
/// before it, its own sampling) is a blob of its own, too small to be a part, and leaves its
/// step with no support (office-495 of seeds 491-495: a 4-step upper flight whose third riser,
/// 12 returns 0.4-1.1 m from the side face, was left out, and the flight with it).
pub(super) fn parted_risers(
    p: &Profile,
    pts: &[(DVec2, f64)],
    lower: &DetectedStairs,
    base: f64,
    sc: &Scene,
    c: &StairsConfig,
) -> Vec<(DVec2, f64)> {
    let mut held = vec![false; p.steps as usize];
    for (q, z) in pts {
        if let Some(k) = step_holding(p, q.dot(p.dir), *z) {
            held[k] = true;
        }
    }
    let line = Line2 {
        origin: lower.start,
        dir: p.dir,
    };
    let foot = sc.floor + base;
    let mut out = Vec::new();
    for (k, _) in held.iter().enumerate().filter(|(_, &h)| !h) {
        let k = k as f64;
        let riser = Riser {
            front_m: p.front1 + k * p.run - lower.start.dot(p.dir),
            heights_m: (foot + k * p.rise, foot + (k + 1.0) * p.rise),
        };
        for i in riser
            .seen(sc, &line, lower.width / 2.0, |_| true, c)
            .unwrap_or_default()
        {
            let q = sc.points[i];
            out.push((DVec2::new(q.x as f64, q.y as f64), q.z as f64 - foot));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::points::XyIndex;
    use glam::{DVec2, Vec3};

    /// An upper flight found with 3 of its steps (rise 0.17 m, run 0.28 m, 1 m wide, on a
    /// landing 0.5 m up), climbing +X from x = 0.
    fn three_steps() -> DetectedStairs {
        DetectedStairs {
            top_short: false,
            steps: 3,
            rise: 0.17,
            run: 0.28,
            width: 1.0,
            dir: DVec2::X,
            start: DVec2::ZERO,
            landing: 1.0,
            base: 0.5,
            support: 100,
            confidence: 1.0,
            rules: Vec::new(),
        }
    }

    /// The steps after `extend_top` over these points (the floor at 0).
    fn extended(points: &[Vec3]) -> u32 {
        let index = XyIndex::new(points, DVec2::splat(-3.0), DVec2::splat(4.0), 0.25);
        let sc = Scene::with_one_index(points, &index, 0.0, 2.8);
        let mut st = three_steps();
        extend_top(&mut st, &sc, |_| true, &StairsConfig::default());
        st.steps
    }

    /// A riser's face at `x`, from `z0` to `z1`, across y -0.4..0.4 (a return every 5 cm).
    fn riser(x: f32, z0: f32, z1: f32) -> Vec<Vec3> {
        let mut p = Vec::new();
        for j in 0..17 {
            let mut z = z0;
            while z <= z1 + 1e-4 {
                p.push(Vec3::new(x, -0.4 + 0.05 * j as f32, z));
                z += 0.05;
            }
        }
        p
    }

    /// Regression: office-7's upper flight (4 steps) was read as 3: its top riser, 0.28 m past
    /// the third's and with no side face seen between them, was a blob of its own.
    #[test]
    fn a_riser_one_run_past_the_top_is_one_more_step() {
        // The fourth riser: from the third tread (0.5 + 0.51 m) to 0.5 + 0.68 m.
        let points = riser(0.84, 1.03, 1.18);
        assert_eq!(extended(&points), 4);
    }

    #[test]
    fn something_standing_past_the_top_is_no_step() {
        // A person on the landing there: a face from the tread up to 1.7 m.
        assert_eq!(extended(&riser(0.84, 1.03, 2.2)), 3);
        // A riser's face, but a run and a half past the top: no step of this flight.
        assert_eq!(extended(&riser(0.98, 1.03, 1.18)), 3);
        // Nothing there.
        assert_eq!(extended(&[]), 3);
    }

    /// An upper flight of 4 steps (rise 0.152 m, run 0.29 m) from x = 2 on the landing of a
    /// 3-step flight 1.24 m wide climbing +X from x = 0 (office-495 of seeds 491-495).
    fn upper_profile() -> Profile {
        Profile {
            dir: DVec2::X,
            rise: 0.152,
            run: 0.29,
            front1: 2.0,
            steps: 4,
            found: 3,
            score: 0.0,
            fit_score: 0.0,
        }
    }

    /// The parted risers' returns found for `scene` (absolute heights, the floor at 0) where
    /// the upper flight's own returns show its risers 1, 2 and 4.
    fn parted(scene: &[Vec3]) -> Vec<(DVec2, f64)> {
        let (rise, landing) = (0.152, 0.456);
        let own: Vec<(DVec2, f64)> = [0, 1, 3]
            .iter()
            .flat_map(|&k| {
                let (x, k) = (2.0 + 0.29 * f64::from(k), f64::from(k));
                riser(x as f32, 0.0, 0.0)
                    .into_iter()
                    .map(move |q| (DVec2::new(x, f64::from(q.y)), (k + 0.5) * rise))
            })
            .collect();
        let index = XyIndex::new(scene, DVec2::splat(-3.0), DVec2::splat(5.0), 0.25);
        let sc = Scene::with_one_index(scene, &index, 0.0, 2.8);
        let lower = DetectedStairs {
            steps: 3,
            rise,
            run: 0.29,
            width: 1.24,
            base: 0.0,
            ..three_steps()
        };
        let c = StairsConfig::default();
        parted_risers(&upper_profile(), &own, &lower, landing, &sc, &c)
    }

    #[test]
    fn a_riser_parted_from_its_upper_flight_supports_its_step() {
        // The third riser (at x = 2.58, from 0.456 + 0.304 m to 0.456 + 0.456 m), seen over
        // 0.8 m of the width only, a blob of its own.
        let third = riser(2.58, 0.80, 0.91);
        let found = parted(&third);
        assert_eq!(found.len(), third.len(), "{found:?}");
        assert!(
            found
                .iter()
                .all(|(q, z)| (q.x - 2.58).abs() < 1e-6 && *z > 0.32 && *z <= 0.46),
            "{found:?}"
        );
        // Seen over a quarter of the width: mixed pixels, a thing on the landing, no riser.
        let narrow: Vec<Vec3> = third.into_iter().filter(|p| p.y > 0.1).collect();
        assert!(parted(&narrow).is_empty());
        // A person standing there: a face on up to 1.7 m.
        assert!(parted(&riser(2.58, 0.80, 1.7)).is_empty());
    }

    /// Regression: hall-62's upper flight (seeds 61-65, 5 steps) was read as 6 from five
    /// mixed pixels along its top landing's front edge, one run past its fifth riser: they
    /// spanned 0.73 of its 1.26 m but covered 3 of its 13 bins.
    #[test]
    fn mixed_pixels_along_the_landing_edge_are_no_riser() {
        let (x, z) = (0.84, 1.16);
        let points: Vec<Vec3> = [-0.41, -0.38, -0.37, -0.21, 0.32]
            .iter()
            .map(|&y| Vec3::new(x, y, z))
            .collect();
        assert_eq!(extended(&points), 3);
        // A riser seen over half the width is one.
        let half_seen: Vec<Vec3> = riser(x, 1.03, 1.18)
            .into_iter()
            .filter(|p| p.y >= -0.02)
            .collect();
        assert_eq!(extended(&half_seen), 4);
    }
}
