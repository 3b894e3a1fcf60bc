//! Wall corners: a wall whose face was seen up to a stretch short of the wall it runs into
//! (the corner seen at a grazing angle, where a realistic laser drops the returns, or hidden
//! by what stood before it) meets that wall, as the extent's corners do where the face is
//! seen up to them. Only across a stretch nobody saw through (no floor within a two-sided
//! wall's footprint, nothing behind a one-sided wall's face, as [`joins`](super::joins)
//! asks): a passage between the wall's end and the other wall shows the floor beyond.

use super::joins::seen_through;
use super::{WallConfig, WallFit};
use crate::points::undirected_angle_deg;
use crate::scene::Scene;
use glam::DVec2;

/// A wall this far across a wall's line at least is one it can run into (a collinear piece is
/// [`joins`](super::joins)' work).
const MIN_CORNER_ANGLE_DEG: f64 = 45.0;

/// An end this near the face of the wall it points at is the extent's to settle: it snaps to
/// a wall-high surface crossing its plane this near (the extent's corners).
const MIN_GAP_M: f64 = 0.15;

/// The face met must reach the wall's line within this of its own ends (the hidden bins beside
/// a corner keep a face's extent a few centimetres short of the corner; as the extent's
/// corners).
const REACH_TOLERANCE_M: f64 = 0.15;

/// Moves every wall's ends on to the face of the wall each points at, across a stretch of more
/// than `MIN_GAP_M` and up to `max_glimpse_gap_m` that nobody saw through (see the module docs). Runs before one-sided
/// walls are moved back from their face to their centre line (`walls`' lines are faces then);
/// such a wall's unseen face lies `assumed_thickness_m` behind its seen one.
pub(crate) fn extend_to_corners(
    walls: &mut [WallFit],
    sc: &Scene,
    c: &WallConfig,
    assumed_thickness_m: f64,
) {
    for i in 0..walls.len() {
        let w = &walls[i];
        let hit = |outward: DVec2, from: DVec2| {
            walls
                .iter()
                .enumerate()
                .filter(|(j, o)| {
                    *j != i && undirected_angle_deg(o.line.dir, w.line.dir) >= MIN_CORNER_ANGLE_DEG
                })
                .filter_map(|(_, o)| face_ahead(o, from, outward, assumed_thickness_m))
                .min_by(|a, b| a.total_cmp(b))
                .filter(|&gap| gap > MIN_GAP_M && gap <= c.max_glimpse_gap_m)
        };
        let after =
            hit(w.line.dir, w.end()).filter(|&g| !seen_through(w, w.length, w.length + g, sc));
        let before = hit(-w.line.dir, w.start()).filter(|&g| !seen_through(w, -g, 0.0, sc));
        if after.is_none() && before.is_none() {
            continue;
        }
        let (g0, g1) = (before.unwrap_or(0.0), after.unwrap_or(0.0));
        let w = &mut walls[i];
        w.line.origin = w.line.at(-g0);
        w.length += g0 + g1;
        w.rules.push(format!(
            "extended {:.2} m to the face of the wall it meets across a stretch nobody saw through",
            g0 + g1
        ));
    }
}

/// How far from `from` along `outward` the nearer face of wall `o` crosses the way, if it does
/// within `o`'s extent; 0 if `from` lies in `o`'s body already (the wall meets it). A wall seen
/// from one side has its unseen face `assumed_m` behind its seen one.
fn face_ahead(o: &WallFit, from: DVec2, outward: DVec2, assumed_m: f64) -> Option<f64> {
    let within = |q: DVec2| {
        let (s, _) = o.line.coords(q);
        s >= -REACH_TOLERANCE_M && s <= o.length + REACH_TOLERANCE_M
    };
    // The body's faces across o's line.
    let (lo, hi) = if o.measured {
        o.faces
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &f| {
                (a.min(f), b.max(f))
            })
    } else {
        let back = -o.free_side * assumed_m;
        (back.min(0.0), back.max(0.0))
    };
    if lo > hi {
        return None;
    }
    let (_, d) = o.line.coords(from);
    if d >= lo && d <= hi {
        return within(from).then_some(0.0);
    }
    let closing = outward.dot(o.line.normal());
    // Heading towards the body: its nearer face, `lo` from below or `hi` from above.
    let face = if d < lo { lo } else { hi };
    let t = (face - d) / closing;
    (t > 0.0 && t.is_finite() && within(from + outward * t)).then_some(t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::points::XyIndex;
    use glam::Vec3;

    fn one_sided(from: DVec2, to: DVec2, free_side: f64) -> WallFit {
        WallFit {
            thickness: 0.0,
            z_range: (0.0, 2.5),
            ..WallFit::one_sided(from, to, free_side)
        }
    }

    /// The outer wall's face at y 17.46 seen from the lobby (at y > 17.46: its left), from
    /// x -0.25 to `to_x`.
    fn outer_seen_from_the_lobby(to_x: f64) -> WallFit {
        one_sided(DVec2::new(-0.25, 17.46), DVec2::new(to_x, 17.46), 1.0)
    }

    /// The lobby's east wall of garage-535 (seeds 531-535), its face at x 4.0 (the lobby at
    /// x < 4: its left), seen from y 19.7 down to 18.0: the 0.55 m on to the outer wall at the
    /// corner was seen at a grazing angle, nothing behind it. Returns the east wall after
    /// [`extend_to_corners`] with `outer` and the points `behind`.
    fn lobby_east(outer: WallFit, behind: &[Vec3]) -> WallFit {
        lobby_east_to(18.0, outer, behind)
    }

    /// [`lobby_east`] with the east wall's face seen down to `end_y`.
    fn lobby_east_to(end_y: f64, outer: WallFit, behind: &[Vec3]) -> WallFit {
        let index = XyIndex::new(behind, DVec2::splat(-5.0), DVec2::splat(30.0), 0.5);
        let sc = Scene::with_one_index(behind, &index, 0.0, 2.5);
        let mut walls = vec![
            one_sided(DVec2::new(4.0, 19.7), DVec2::new(4.0, end_y), -1.0),
            outer,
        ];
        extend_to_corners(&mut walls, &sc, &WallConfig::default(), 0.25);
        walls.swap_remove(0)
    }

    fn assert_ends(w: &WallFit, start_y: f64, end_y: f64) {
        assert!(
            (w.start().y - start_y).abs() < 1e-9 && (w.end().y - end_y).abs() < 1e-9,
            "{:?} {:?}",
            w.start(),
            w.end()
        );
    }

    #[test]
    fn a_wall_ending_short_of_the_wall_it_meets_across_an_unseen_stretch_reaches_it() {
        // A T junction and an L corner (the outer wall's face seen up to the corner).
        for to_x in [20.0, 4.0] {
            assert_ends(
                &lobby_east(outer_seen_from_the_lobby(to_x), &[]),
                19.7,
                17.46,
            );
        }
        // The outer wall seen from the garage only (its face at y 17.21, the garage at its
        // right): the east wall meets its unseen face, an assumed thickness behind.
        let seen_from_the_garage =
            one_sided(DVec2::new(-0.25, 17.21), DVec2::new(20.0, 17.21), -1.0);
        assert_ends(&lobby_east(seen_from_the_garage, &[]), 19.7, 17.46);
    }

    #[test]
    fn a_wall_ending_short_of_another_across_a_passage_seen_through_keeps_its_end() {
        // The floor behind the face in the stretch: a passage into the next room.
        let floor: Vec<Vec3> = (0..10)
            .flat_map(|i| {
                (0..8).map(move |j| Vec3::new(4.1 + 0.05 * i as f32, 17.5 + 0.05 * j as f32, 0.0))
            })
            .collect();
        assert_ends(
            &lobby_east(outer_seen_from_the_lobby(20.0), &floor),
            19.7,
            18.0,
        );
        // A wall whose line passes the end farther off than its extent reaches meets nothing.
        assert_ends(&lobby_east(outer_seen_from_the_lobby(3.0), &[]), 19.7, 18.0);
    }

    /// Regression: a partition's end a few millimetres inside the corridor wall it meets (both
    /// faces of that wall seen) ran on through the wall's body to its far face (mixed-533 of
    /// seeds 531-535: two partitions 0.25 m into the corridor).
    #[test]
    fn a_wall_ending_inside_the_wall_it_meets_stays_there() {
        // Both faces seen: at y 17.23 and 17.46.
        let corridor = WallFit {
            thickness: 0.23,
            measured: true,
            faces: vec![-0.115, 0.115],
            ..one_sided(DVec2::new(-0.25, 17.345), DVec2::new(20.0, 17.345), 1.0)
        };
        assert_ends(&lobby_east(corridor.clone(), &[]), 19.7, 17.46);
        assert_ends(&lobby_east_to(17.45, corridor, &[]), 19.7, 17.45);
    }
}
