//! What of a prerequisite segment its wall's fit left out. A segment of the projection may
//! follow two things in line: a wall and a beam running on from its corner (garage-5 of seeds
//! 1-10: a lobby's 2.25 m wall and a 17 m beam over pillars, one 11.85 m segment once mixed
//! pixels were dropped from the scans, the lobby wall's own segment before). The fit settles on
//! the one whose face holds the most returns and measures it alone; the other would have no
//! prerequisite left. So each part of the segment beyond the settled extent, long enough to be
//! more than the ends a corner trims, is fitted as a segment of its own.
//!
//! The fit can also settle on both, and be dropped as a beam, more of its length seen through
//! or bare below head height than standing (garage-132 of seeds 131-135: one 19.25 m segment
//! along a 17 m beam over pillars and the 2.4 m lobby wall in its line; the beam's two faces
//! set the fit's, and the wall's face, between them, read as seen through). Each stretch of it
//! where something stands below head height all along, long enough as above, is then fitted
//! on its own: the wall's; a pillar under the beam is too short.

use super::fit::{fit_wall, fit_wall_noting, Settled};
use super::support::{BIN_M, HEAD_HEIGHT_M};
use super::{WallConfig, WallFit};
use crate::merge::Segment;
use crate::points::Line2;
use crate::scene::Scene;

/// The shortest part of a segment left out of its fit's extent that is fitted on its own:
/// longer than the ends a corner trims (a wall's thickness or two) and than a pillar's side.
const MIN_REST_M: f64 = 1.0;

/// Returns this high over the floor and up to head height stand (see `standing_stretches`):
/// over the floor's noise and what lies on it.
const STANDING_FROM_M: f64 = 0.3;

/// Empty bins running for at most this many stay within a standing stretch (a wall's face seen
/// with gaps from afar).
const MAX_GAP_BINS: usize = 2;

/// The most bins along a fit (a cap against absurd lengths: 100 km).
const MAX_BINS: f64 = 1e6;

/// The walls along one prerequisite segment: the wall its fit settles on, if any, and those
/// along the parts of the segment the settled extent left out (see the module docs).
pub(super) fn fit_walls_along(seg: &Segment, sc: &Scene, c: &WallConfig) -> Vec<WallFit> {
    let mut settled = None;
    let mut walls: Vec<WallFit> = fit_wall_noting(seg, sc, c, &mut settled)
        .into_iter()
        .collect();
    if let Some(s) = settled {
        for rest in rests(seg, &s.line, (s.lo, s.hi)) {
            walls.extend(fit_wall(&rest, sc, c));
        }
        // A fit dropped as a beam: the stretches of it where something stands.
        if s.beam {
            for (from, to) in standing_stretches(sc, &s) {
                let part = Segment {
                    a_m: s.line.at(from).to_array(),
                    b_m: s.line.at(to).to_array(),
                };
                walls.extend(fit_wall(&part, sc, c));
            }
        }
    }
    walls
}

/// The stretches `(from, to)` along a fit dropped as a beam (`s`) where something stands
/// within its faces' reach: returns between [`STANDING_FROM_M`] and head height over the floor
/// in every [`BIN_M`] bin but gaps of [`MAX_GAP_BINS`], at least [`MIN_REST_M`] long. Under a
/// beam the floor is seen between its pillars; a wall in its line stands along all of its
/// length.
fn standing_stretches(sc: &Scene, s: &Settled) -> Vec<(f64, f64)> {
    let n = ((s.hi - s.lo) / BIN_M).ceil().clamp(1.0, MAX_BINS) as usize;
    let mut occupied = vec![false; n];
    let (z0, z1) = (sc.floor + STANDING_FROM_M, sc.floor + HEAD_HEIGHT_M);
    sc.upright
        .for_each_near_line(&s.line, s.lo, s.hi, s.half_width, |_, t, _, z| {
            if z >= z0 && z <= z1 {
                let k = (((t - s.lo) / BIN_M).max(0.0) as usize).min(n - 1);
                occupied[k] = true;
            }
        });
    let mut out = Vec::new();
    let mut run: Option<(usize, usize)> = None; // [from, to)
    for (k, &o) in occupied.iter().enumerate() {
        match (o, run) {
            (true, Some((from, to))) if k - to <= MAX_GAP_BINS => run = Some((from, k + 1)),
            (true, _) => {
                out.extend(run);
                run = Some((k, k + 1));
            }
            (false, _) => {}
        }
    }
    out.extend(run);
    out.into_iter()
        .map(|(from, to)| {
            (
                s.lo + from as f64 * BIN_M,
                (s.lo + to as f64 * BIN_M).min(s.hi),
            )
        })
        .filter(|(from, to)| to - from >= MIN_REST_M)
        .collect()
}

/// The parts of `seg` beyond the extent `(lo, hi)` along `line`, each at least
/// [`MIN_REST_M`] long, on the segment itself.
fn rests(seg: &Segment, line: &Line2, (lo, hi): (f64, f64)) -> Vec<Segment> {
    let (a, b) = (seg.a(), seg.b());
    let (ta, tb) = (line.coords(a).0, line.coords(b).0);
    if (tb - ta).abs() < f64::EPSILON {
        return Vec::new();
    }
    // The point of the segment at `t` along the line.
    let at = |t: f64| a + (b - a) * ((t - ta) / (tb - ta));
    let (t0, t1) = (ta.min(tb), ta.max(tb));
    [(t0, t1.min(lo)), (t0.max(hi), t1)]
        .into_iter()
        .filter(|(from, to)| to - from >= MIN_REST_M)
        .map(|(from, to)| Segment {
            a_m: at(from).to_array(),
            b_m: at(to).to_array(),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::points::XyIndex;
    use glam::{DVec2, Vec3};

    #[test]
    fn the_rests_are_the_long_parts_of_the_segment_beyond_the_extent() {
        let seg = Segment {
            a_m: [0.0, 8.4],
            b_m: [0.0, 1.0],
        };
        // The line (slightly off the segment, as a fit's face line is) from y = 0 upwards.
        let line = Line2::through(DVec2::new(0.05, 0.0), DVec2::new(0.05, 1.0));
        let ys =
            |r: &[Segment]| -> Vec<[f64; 2]> { r.iter().map(|s| [s.a_m[1], s.b_m[1]]).collect() };
        // Settled on y 1.0..6.0: the rest 6.0..8.4 (a point of the segment, from its start).
        assert_eq!(ys(&rests(&seg, &line, (1.0, 6.0))), vec![[6.0, 8.4]]);
        // Settled in the middle: both ends, if long enough.
        assert_eq!(ys(&rests(&seg, &line, (2.5, 7.6))), vec![[1.0, 2.5]]);
        assert_eq!(
            ys(&rests(&seg, &line, (2.0, 7.4))),
            vec![[1.0, 2.0], [7.4, 8.4]]
        );
        // Settled over it all, or beyond: nothing.
        assert!(rests(&seg, &line, (0.8, 8.6)).is_empty());
        for s in rests(&seg, &line, (1.0, 6.0)) {
            assert!(s.a_m[0].abs() < 1e-12 && s.b_m[0].abs() < 1e-12, "{s:?}");
        }
    }

    /// The ceiling of [`lobby_wall_and_beam`].
    const CEILING: f32 = 2.9;

    /// garage-5 (seeds 1-10): a lobby's wall meets its south wall at a corner, and a beam over
    /// the garage runs on from that corner in the wall's line (see the test below).
    fn lobby_wall_and_beam() -> Vec<Vec3> {
        let (ceiling, step) = (CEILING, 0.05);
        // The lobby's wall: x 0..0.25, y 18..20.25, its face x = 0 seen from the lobby (x < 0).
        // Its south wall: y 17.75..18, x -3..0.25. The beam: x -0.25..0.25, y 0..17.75, from
        // 2.5 m up, seen from both sides with the floor under it, on pillars.
        let lobby_wall = |x: f64, y: f64| (0.0..0.25).contains(&x) && (18.0..20.25).contains(&y);
        let south_wall = |x: f64, y: f64| (-3.0..0.25).contains(&x) && (17.75..18.0).contains(&y);
        // Pillars under the beam, 0.5 m square.
        let pillars = [0.5, 2.25, 4.0, 5.75, 7.5, 9.25, 11.0, 12.75, 14.5, 16.25];
        let pillar =
            |x: f64, y: f64| x.abs() < 0.25 && pillars.iter().any(|&p| (p..p + 0.5).contains(&y));
        let solid = |x: f64, y: f64| lobby_wall(x, y) || south_wall(x, y) || pillar(x, y);
        let mut points = super::super::test_floor((-3.0, 0.0), (120, 405), solid);
        let ceiling_points: Vec<Vec3> = points
            .iter()
            .map(|p| Vec3::new(p.x, p.y, ceiling))
            .collect();
        points.extend(ceiling_points);
        let face = |n: usize, at: &dyn Fn(f64) -> (f64, f64), heights: std::ops::Range<usize>| {
            let mut out = Vec::new();
            for i in 0..n {
                let (x, y) = at(0.025 + step * i as f64);
                for k in heights.clone() {
                    out.push(Vec3::new(x as f32, y as f32, (step * k as f64) as f32));
                }
            }
            out
        };
        points.extend(face(45, &|t| (0.0, 18.0 + t), 1..58));
        points.extend(face(60, &|t| (-3.0 + t, 17.75), 1..58));
        points.extend(face(355, &|t| (-0.25, t), 50..58));
        points.extend(face(355, &|t| (0.25, t), 50..58));
        for p in pillars {
            for x in [-0.25, 0.25] {
                points.extend(face(10, &|t| (x, p + t), 1..50));
            }
            for y in [p, p + 0.5] {
                points.extend(face(10, &|t| (-0.25 + t, y), 1..50));
            }
        }
        // A laser's noise: the faces are no exact planes.
        let mut rng = cloud::Rng::new(5);
        for p in &mut points {
            *p += Vec3::new(
                (0.005 * rng.gaussian()) as f32,
                (0.005 * rng.gaussian()) as f32,
                (0.005 * rng.gaussian()) as f32,
            );
        }
        points
    }

    /// The scene of `points` over [`lobby_wall_and_beam`]'s area.
    fn scene<'a>(points: &'a [Vec3], index: &'a XyIndex) -> Scene<'a> {
        Scene::with_one_index(points, index, 0.0, f64::from(CEILING))
    }

    /// garage-5 (seeds 1-10): one segment along the lobby's wall and the beam; the fit settles
    /// on the beam (its two faces' returns outnumber the wall's one face's) and drops it as no
    /// wall. The lobby's wall is the rest of the segment, fitted on its own.
    #[test]
    fn a_wall_in_line_with_a_beam_past_its_corner_is_found_along_their_one_segment() {
        let points = lobby_wall_and_beam();
        let index = XyIndex::new(&points, DVec2::new(-3.5, -0.5), DVec2::new(3.5, 21.0), 0.25);
        let sc = scene(&points, &index);
        let c = WallConfig::default();
        let seg = Segment {
            a_m: [0.0, 0.1],
            b_m: [0.0, 20.2],
        };
        let walls = fit_walls_along(&seg, &sc, &c);
        assert_eq!(walls.len(), 1, "{walls:?}");
        let ys = [walls[0].start().y, walls[0].end().y];
        let (s, e) = (ys[0].min(ys[1]), ys[0].max(ys[1]));
        assert!((s - 18.0).abs() < 0.2 && (e - 20.25).abs() < 0.2, "{s} {e}");
    }

    /// garage-132 (seeds 131-135): where the fit settles on the beam and the lobby's wall both
    /// (the beam's faces set its faces; the wall's face, between them, reads as seen through)
    /// and drops them as a beam, the wall is the one stretch along them where something stands
    /// below head height all along; the beam's pillars (0.5 m) are too short.
    #[test]
    fn along_a_fit_dropped_as_a_beam_a_wall_in_its_line_stands() {
        let points = lobby_wall_and_beam();
        let index = XyIndex::new(&points, DVec2::new(-3.5, -0.5), DVec2::new(3.5, 21.0), 0.25);
        let sc = scene(&points, &index);
        let settled = Settled {
            line: Line2::through(DVec2::new(0.0, 0.1), DVec2::new(0.0, 20.2)),
            lo: 0.0,
            hi: 20.1,
            half_width: 0.28,
            beam: true,
        };
        let stretches = standing_stretches(&sc, &settled);
        assert_eq!(stretches.len(), 1, "{stretches:?}");
        let (from, to) = stretches[0];
        // Along the line from y = 0.1: the wall from y 18.0 (its south wall's face at 17.75
        // stands too) to 20.25.
        assert!(
            (from - 17.65).abs() < 0.15 && (to - 20.1).abs() < 0.05,
            "{from} {to}"
        );
    }
}
