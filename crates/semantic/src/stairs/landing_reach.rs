//! A landing read on past its blob. Seen from below (a laser under the landing's height), a
//! top landing shows its side face and its end face, not its top, and the height map's blobs
//! part the side face where something in front of it (a person) shadows it: hall-261 of seeds
//! 261-265, a landing 1.31 m up, 0.91 m deep, its blob ending at a person's shadow 0.38 m along
//! it. So each flight's top level is read on from where its landing ends, along the highest
//! return across its width in bins of [`BIN_M`]: the landing goes on while that stays level
//! with it (its side face's top edge, or its top), and ends where it falls (the floor beyond,
//! the end face's foot past its edge), rises (an upper flight's treads, something standing on
//! it), the floor is seen in the middle half of its width (a landing hides the floor under it:
//! mixed-265 of seeds 261-265, a person's streak past a landing's end, its top level with the
//! landing, over the floor), or nothing is seen for more than a gap of [`LANDING_GAP_M`] (a
//! wall's slab, which the height map leaves out, or the end of what the scans saw).

use super::top_end::LANDING_GAP_M;
use super::{DetectedStairs, StairsConfig};
use crate::points::Line2;
use crate::scene::Scene;

/// The bins along the flight past its landing's end.
const BIN_M: f64 = 0.1;

/// How far past its landing's end a flight's top level is read at most (a landing is about as
/// deep as the stair is wide, 1-2 m).
const REACH_M: f64 = 2.0;

/// The highest return across the width is level with the landing within this share of a rise
/// (a side face's top edge is sampled a few centimetres under the edge; a rise over it is
/// the next flight's tread).
const LEVEL_RISES: f64 = 0.5;

/// Reads the flight's top level on past its landing's end (see the module docs); `usable(i)`
/// is true for the points the height map holds. More than `min_step_points` floor returns in a
/// bin show the floor.
pub(super) fn reach_on(
    st: &mut DetectedStairs,
    sc: &Scene,
    usable: impl Fn(usize) -> bool,
    c: &StairsConfig,
) {
    let top_step_end = f64::from(st.steps) * st.run;
    let end = top_step_end + st.landing;
    let top = sc.floor + st.base + f64::from(st.steps) * st.rise;
    let line = Line2 {
        origin: st.start + st.dir * end,
        dir: st.dir,
    };
    const BINS: usize = (REACH_M / BIN_M) as usize;
    // (each bin's highest return, how far along its returns level with the landing reach, and
    // its floor returns in the middle half of the width)
    let mut highest = [f64::NEG_INFINITY; BINS];
    let mut level_to = [f64::NEG_INFINITY; BINS];
    let mut floor = [0usize; BINS];
    sc.index
        .for_each_near_line(&line, 0.0, REACH_M, st.width / 2.0, |i, s, t, z| {
            if !(0.0..REACH_M).contains(&s) {
                return;
            }
            let k = ((s / BIN_M) as usize).min(BINS - 1);
            if (z - sc.floor).abs() <= 0.03 && t.abs() <= st.width / 4.0 {
                floor[k] += 1;
            }
            if !usable(i) {
                return;
            }
            highest[k] = highest[k].max(z);
            if (z - top).abs() <= LEVEL_RISES * st.rise {
                level_to[k] = level_to[k].max(s);
            }
        });
    let mut reached = 0.0;
    for k in 0..BINS {
        if floor[k] > c.min_step_points {
            break;
        }
        if highest[k].is_finite() {
            if (highest[k] - top).abs() > LEVEL_RISES * st.rise {
                break;
            }
            reached = level_to[k];
        } else if (k + 1) as f64 * BIN_M - reached > LANDING_GAP_M {
            break;
        }
    }
    // (less than a gap is the landing's end face's top edge, or a stray; and a landing is one
    // where it runs on more than 0.1 m past the top step, as `plausible` reads it)
    if reached < LANDING_GAP_M || st.landing + reached <= 0.1 {
        return;
    }
    st.landing += reached;
    st.rules.push(format!(
        "its top level read on {reached:.2} m past its blob: the highest return across it level with the landing (its side face's top edge seen from below)"
    ));
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::points::XyIndex;
    use glam::{DVec2, Vec3};

    /// A 4-step flight (0.17 x 0.28 m, 1 m wide across y -0.5..0.5) climbing +X from x = 0,
    /// its top step ending at x = 1.12, its landing (0.68 m up) seen to `landing_m` past it.
    /// The cloud: the floor beyond `end_x` (every 4 cm), the landing's side face at y = -0.5
    /// from the top step to `end_x` and its end face there (every 2 cm, from the floor to the
    /// landing's height: its top unseen, above the laser), and `more`. The landing after
    /// `reach_on`.
    fn reached(landing_m: f64, end_x: f32, more: &[Vec3]) -> f64 {
        let top = 0.68f32;
        let mut points: Vec<Vec3> = more.to_vec();
        for i in 0..60 {
            for j in 0..40 {
                let (x, y) = (end_x + 0.02 + 0.04 * i as f32, -1.0 + 0.04 * j as f32);
                points.push(Vec3::new(x, y, 0.0));
            }
        }
        for k in 0..=34 {
            let z = 0.02 * k as f32;
            let mut x = 1.12f32;
            while x <= end_x {
                points.push(Vec3::new(x, -0.5, z.min(top)));
                x += 0.02;
            }
            for j in 0..50 {
                points.push(Vec3::new(end_x, -0.49 + 0.02 * j as f32, z.min(top)));
            }
        }
        let index = XyIndex::new(&points, DVec2::splat(-1.0), DVec2::splat(5.0), 0.25);
        let sc = Scene::with_one_index(&points, &index, 0.0, 2.8);
        let mut st = DetectedStairs::straight(0.0, 4, 0.17, 0.28);
        st.landing = landing_m;
        reach_on(&mut st, &sc, |_| true, &StairsConfig::default());
        st.landing
    }

    /// Regression (hall-261 of seeds 261-265): a top landing 0.91 m deep whose top the laser
    /// never saw, its blob parted 0.38 m along it by a person's shadow on its side face, read
    /// 0.38 m deep; its end face was left as a partial-height wall 1.3 m high.
    #[test]
    fn a_landing_seen_by_its_side_face_reads_on_to_its_end_face() {
        let landing = reached(0.38, 2.03, &[]);
        assert!((landing - 0.91).abs() < 0.06, "landing {landing}");
    }

    #[test]
    fn a_landing_ends_where_the_floor_or_something_higher_stands() {
        // Read to its end already: the floor beyond.
        let landing = reached(0.91, 2.03, &[]);
        assert!((landing - 0.91).abs() < 1e-9, "landing {landing}");
        // A person standing on it 0.2 m past where its blob ends: up to 1.7 m.
        let person: Vec<Vec3> = (0..60)
            .map(|k| Vec3::new(1.72, -0.1, 0.03 * k as f32))
            .collect();
        let landing = reached(0.38, 2.03, &person);
        assert!(landing < 0.62, "landing {landing}");
        // An upper flight's riser right past its end: its edge a rise over the landing.
        let riser: Vec<Vec3> = (0..10)
            .flat_map(|k| {
                (0..50)
                    .map(move |j| Vec3::new(1.52, -0.49 + 0.02 * j as f32, 0.68 + 0.017 * k as f32))
            })
            .collect();
        let landing = reached(0.38, 2.03, &riser);
        assert!((landing - 0.38).abs() < 1e-9, "landing {landing}");
        // Regression (mixed-265 of seeds 261-265): a person's streak 0.05-0.25 m past the end
        // face, along the flight's side, its top level with the landing, over the floor.
        let streak: Vec<Vec3> = (0..10)
            .flat_map(|i| {
                (0..35).map(move |k| Vec3::new(2.08 + 0.02 * i as f32, -0.45, 0.02 * k as f32))
            })
            .collect();
        let landing = reached(0.91, 2.03, &streak);
        assert!((landing - 0.91).abs() < 1e-9, "landing {landing}");
    }
}
