//! A flight's top riser, seen alone. From the floor below, an upper flight shows its risers
//! (their faces turned to the laser) and, where the laser sees it, its side face; its treads
//! are above the laser. The risers stand a run apart in plan, and where the side face is
//! unseen near the top the height map's blobs (pixels within two of each other) part them: the
//! flight's blob ends a step short of its top, and the top riser is a blob of its own, too
//! small for a staircase. So each flight is looked at one run past its top step's front: a
//! riser standing there is one more step. A riser is points on a face across the flight
//! (covering at least half its width, in bins of 10 cm: a few mixed pixels strung along the
//! landing's front edge span the width but cover little of it), between its top tread's height
//! and one rise above it, its top edge at that rise, and nothing standing right above it (a
//! person on the landing, a cupboard, a wall beyond the flight stand higher).

use super::{DetectedStairs, StairsConfig};
use crate::points::Line2;
use crate::scene::Scene;

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
    let bins = ((st.width / COVER_BIN_M).ceil() as usize).clamp(1, 1000);
    while st.steps < 64 {
        let k = f64::from(st.steps);
        let front = k * st.run;
        let (lo, top) = (k * st.rise + 0.02, (k + 1.0) * st.rise);
        let (mut on_riser, mut above) = (0usize, 0usize);
        let mut highest = f64::NEG_INFINITY;
        let mut covered = vec![false; bins];
        sc.index.for_each_near_line(
            &line,
            front - RISER_BAND_M,
            front + RISER_BAND_M,
            half,
            |i, _, t, z| {
                if !usable(i) {
                    return;
                }
                let h = z - foot;
                if h > lo && h <= top + 0.03 {
                    on_riser += 1;
                    highest = highest.max(h);
                    let bin = ((t + half) / COVER_BIN_M)
                        .floor()
                        .clamp(0.0, (bins - 1) as f64);
                    covered[bin as usize] = true;
                } else if h > top + ABOVE_FROM_M && h <= top + ABOVE_TO_M {
                    above += 1;
                }
            },
        );
        let is_riser = on_riser >= c.min_step_points
            && highest >= top - 0.035
            && covered.iter().filter(|&&b| b).count() as f64 >= MIN_COVER * bins as f64
            && above * 4 <= on_riser;
        if !is_riser {
            return;
        }
        st.steps += 1;
        st.landing = (st.landing - st.run).max(0.0);
        st.top_short = false;
        st.rules.push(format!(
            "step {} from its riser one run past the step below ({on_riser} points; its tread above the laser unseen)",
            st.steps
        ));
    }
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
