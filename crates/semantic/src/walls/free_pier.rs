//! Free-standing piers: a pillar's face is a wall face from the floor to the ceiling, but only
//! as wide as the pillar, and the floor is seen past its ends. Walls meet other walls, stand at
//! the edge of a doorway, or run on behind what hid them; a stretch no longer than a column is
//! wide with the floor seen along its line beyond both ends stands free, and is a column (left
//! to the obstacles stage), not a wall.
//!
//! Where something stands by the pillar (a car parked beside it), the floor past that end is
//! hidden. The stretch is still a column if no other wall meets it at that end (no corner, no
//! wall it would be a piece of) and its body is no deeper than a column: the floor is seen
//! behind it within a column's width (a one-sided wall's back is not seen; a pillar's is, from
//! the poses on its other side, a body thicker than any wall).
//!
//! Under a beam, the Hough segment and the wall's extent follow the beam's face past the pillar:
//! the stretch of the candidate where its face is seen below head height is looked at so then.

use super::piers::{BODY_DEPTH_M, FLOOR_TOL_M, MAX_COLUMN_M, MIN_FLOOR_POINTS};
use super::support::{HEAD_HEIGHT_M, UPPER_FACE_M};
use super::WallFit;
use crate::scene::Scene;

/// The floor is looked for this far beyond each end (from 5 cm, beyond the end's own noise).
const BEYOND_M: (f64, f64) = (0.05, 0.35);
/// Another wall whose line passes this near an end (beyond its own half thickness) meets the
/// stretch there: a corner, or the rest of a wall the stretch is a piece of.
const MEET_M: f64 = 0.5;
/// The floor behind a one-sided stretch is looked for in bins this long along it ...
const BEHIND_BIN_M: f64 = 0.1;
/// ... and must be seen in this share of them at least.
const MIN_BEHIND_SHARE: f64 = 0.5;

/// True if `w` (before one-sided walls are moved to their centre lines: `w.line` is the face
/// of a one-sided wall) is no longer than a column and stands free: the floor is seen where its
/// body would continue past both ends, or past one end while no other wall of `walls` meets the
/// other and its back is seen (see the module docs). So is `w` if the stretch of it where its
/// face is seen below head height is such a column, the rest of it seen above head height only
/// (see [`standing_stretch`]).
pub(crate) fn is_free_standing_pier(
    w: &WallFit,
    walls: &[WallFit],
    sc: &Scene,
    face_tolerance_m: f64,
) -> bool {
    stands_free(w, w, walls, sc)
        || standing_stretch(w, sc, face_tolerance_m)
            .is_some_and(|stretch| stands_free(&stretch, w, walls, sc))
}

/// True if `piece` (of the wall `own` in `walls`, or all of it) is no longer than a column
/// and stands free (see [`is_free_standing_pier`]).
fn stands_free(piece: &WallFit, own: &WallFit, walls: &[WallFit], sc: &Scene) -> bool {
    if piece.length > MAX_COLUMN_M {
        return false;
    }
    let (b0, b1) = BEYOND_M;
    let free_start = free_past(piece, -b1, -b0, sc);
    let free_end = free_past(piece, piece.length + b0, piece.length + b1, sc);
    if free_start == free_end {
        return free_start;
    }
    let hidden = if free_start {
        piece.end()
    } else {
        piece.start()
    };
    let met = walls
        .iter()
        .any(|o| !std::ptr::eq(o, own) && meets(o, hidden));
    !met && back_seen(piece, sc)
}

/// Face points below head height in a bin of [`BEHIND_BIN_M`] this many at least stand there
/// (fewer are a stray return or a person's passing).
const MIN_STANDING_POINTS: usize = 2;

/// The stretch of `w` from the first to the last bin where its face is seen below head height,
/// up to [`UPPER_FACE_M`] at least (a parked car's flank or wheel on the face's line, seen
/// under it only, is no face: see `support`), as a wall of its own, where it is shorter than
/// `w` by a bin or more (the rest of `w` is its face seen above head height only: the Hough
/// segment and the extent follow a beam's face past the pillar under it) and no longer than a
/// column. A pillar under a beam, a parked car
/// beside each, the floor past its ends and under the beam hidden (garage-144 of seeds 141-145:
/// 0.6 m of a pillar's face and 0.8 m of the beam's beyond it, a 1.37 m wall), stands free as
/// the pillar it is. A wall hidden below head height along most of its length by what stands
/// before it does not: where it goes on, its body hides the floor past the stretch's end, and
/// its face is seen above what stands before it (a car, a cabinet) below head height too.
/// Cars parked either side of the beam's line past the pillar (garage-153 of seeds 151-155),
/// a wheel and flank on the line seen up to 1.2 m, stretched the pillar's 0.6 m to 1.7 m.
fn standing_stretch(w: &WallFit, sc: &Scene, face_tolerance_m: f64) -> Option<WallFit> {
    if w.length <= BEHIND_BIN_M {
        return None;
    }
    let faces: Vec<f64> = if w.measured {
        w.faces.clone()
    } else {
        vec![0.0]
    };
    let n = ((w.length / BEHIND_BIN_M).ceil() as usize).max(1);
    // (face points below head height per bin, and those of them from `UPPER_FACE_M` up)
    let (mut standing, mut high) = (vec![0usize; n], vec![0usize; n]);
    sc.index.for_each_near_line(
        &w.line,
        0.0,
        w.length,
        w.thickness / 2.0 + face_tolerance_m,
        |_, s, d, z| {
            let above_floor = z - sc.floor;
            if above_floor > 0.1
                && above_floor < HEAD_HEIGHT_M
                && faces.iter().any(|f| (d - f).abs() <= face_tolerance_m)
            {
                let k = ((s / BEHIND_BIN_M).floor().max(0.0) as usize).min(n - 1);
                standing[k] += 1;
                high[k] += usize::from(above_floor >= UPPER_FACE_M);
            }
        },
    );
    let stands = |k: &usize| standing[*k] >= MIN_STANDING_POINTS && high[*k] > 0;
    let first = (0..n).find(stands)?;
    let last = (0..n).rev().find(stands)?;
    let (s0, s1) = (
        first as f64 * BEHIND_BIN_M,
        ((last + 1) as f64 * BEHIND_BIN_M).min(w.length),
    );
    if s1 - s0 > MAX_COLUMN_M || s1 - s0 > w.length - BEHIND_BIN_M {
        return None;
    }
    let mut stretch = w.clone();
    stretch.line.origin = w.line.at(s0);
    stretch.length = s1 - s0;
    Some(stretch)
}

/// True if the floor is seen in the wall's footprint between `s0` and `s1` along it: a
/// measured wall's body, at least [`BODY_DEPTH_M`] wide about its line (a body measured a few
/// centimetres thick holds too few returns of a floor seen at grazing angles: garage-481 of
/// seeds 481-485, a pillar's face under a beam measured 0.11 m thick, 4 floor returns past its
/// free end), or the band behind a one-sided wall's face.
fn free_past(w: &WallFit, s0: f64, s1: f64, sc: &Scene) -> bool {
    let half = (w.thickness / 2.0).max(BODY_DEPTH_M / 2.0);
    let reach = if w.measured { half } else { BODY_DEPTH_M };
    let mut n = 0;
    sc.index
        .for_each_near_line(&w.line, s0, s1, reach, |_, _, d, z| {
            let in_body = if w.measured {
                d.abs() <= half
            } else {
                let behind = -w.free_side * d;
                (0.0..=BODY_DEPTH_M).contains(&behind)
            };
            if in_body && (z - sc.floor).abs() <= FLOOR_TOL_M {
                n += 1;
            }
        });
    n >= MIN_FLOOR_POINTS
}

/// True if `o`'s line, between its ends, passes within [`MEET_M`] of `p` (beyond half its
/// thickness).
fn meets(o: &WallFit, p: glam::DVec2) -> bool {
    let (t, d) = o.line.coords(p);
    let along = t - t.clamp(0.0, o.length);
    along.hypot(d) <= MEET_M + o.thickness / 2.0
}

/// True if `w`'s back is seen: a measured wall's is (both faces are); behind a one-sided
/// stretch's body, the floor is seen within a column's width along most of it.
fn back_seen(w: &WallFit, sc: &Scene) -> bool {
    if w.measured {
        return true;
    }
    let n = ((w.length / BEHIND_BIN_M).ceil() as usize).max(1);
    let mut seen = vec![false; n];
    let depth = (BODY_DEPTH_M, MAX_COLUMN_M + BEYOND_M.1);
    sc.index
        .for_each_near_line(&w.line, 0.0, w.length, depth.1, |_, s, d, z| {
            let behind = -w.free_side * d;
            if (depth.0..=depth.1).contains(&behind) && (z - sc.floor).abs() <= FLOOR_TOL_M {
                let k = ((s / BEHIND_BIN_M).floor().max(0.0) as usize).min(n - 1);
                seen[k] = true;
            }
        });
    seen.iter().filter(|&&b| b).count() as f64 >= MIN_BEHIND_SHARE * n as f64
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::points::XyIndex;
    use glam::{DVec2, Vec3};

    /// Floor points on a 5 cm grid over x in [-2, 3], y in [-1, 2] where `solid` is false.
    fn floor(solid: impl Fn(f64, f64) -> bool) -> Vec<Vec3> {
        crate::walls::test_floor((-2.0, -1.0), (100, 60), solid)
    }

    fn pier(points: &[Vec3], w: &WallFit, others: &[WallFit]) -> bool {
        let index = XyIndex::new(points, DVec2::splat(-3.0), DVec2::splat(4.0), 0.25);
        let sc = Scene::with_one_index(points, &index, 0.0, 3.0);
        let mut walls = vec![w.clone()];
        walls.extend_from_slice(others);
        is_free_standing_pier(&walls[0], &walls, &sc, 0.03)
    }

    /// A 0.5 m pillar's face on y = 0 from x = 0 to 0.5, seen from y < 0.
    fn face() -> WallFit {
        WallFit::one_sided(DVec2::ZERO, DVec2::new(0.5, 0.0), -1.0)
    }

    fn pillar(x: f64, y: f64) -> bool {
        (0.0..0.5).contains(&x) && (0.0..0.5).contains(&y)
    }

    /// Regression (garage-98): a pillar with a car parked beside it, the floor past that end
    /// never seen, was a 0.51 m wall from the floor to the ceiling.
    #[test]
    fn a_pillar_with_a_car_beside_it_is_no_wall() {
        let car = |x: f64, y: f64| (0.55..1.5).contains(&x) && (-0.5..1.5).contains(&y);
        let points = floor(|x, y| pillar(x, y) || car(x, y));
        assert!(pier(&points, &face(), &[]));
        // Hidden past both ends: nothing says it stands free.
        let points = floor(|x, y| pillar(x, y) || car(x, y) || car(x + 1.6, y));
        assert!(!pier(&points, &face(), &[]));
    }

    /// Face points on y = 0 every 5 cm from `x0` to `x1` and from `z0` to `z1` (m).
    fn face_points(x: (f64, f64), z: (f64, f64)) -> Vec<Vec3> {
        let mut points = Vec::new();
        let mut xi = x.0 + 0.025;
        while xi < x.1 {
            let mut zi = z.0;
            while zi <= z.1 {
                points.push(Vec3::new(xi as f32, 0.0, zi as f32));
                zi += 0.05;
            }
            xi += 0.05;
        }
        points
    }

    /// Regression (garage-144 of seeds 141-145): a pillar under a beam, a car parked beside
    /// each, was a 1.37 m wall from the floor to the ceiling: the beam's face past the pillar
    /// made it longer than a column, the floor under the beam hidden by the cars. The stretch
    /// where its face is seen below head height, the pillar's, stands free.
    #[test]
    fn a_pillar_under_a_beam_with_a_car_beside_it_is_no_wall() {
        let car = |x: f64, y: f64| (0.55..1.5).contains(&x) && (-0.5..1.5).contains(&y);
        let mut points = floor(|x, y| pillar(x, y) || car(x, y));
        points.extend(face_points((0.0, 0.5), (0.2, 2.6)));
        points.extend(face_points((0.5, 1.3), (2.3, 2.6)));
        let beam_and_pillar = WallFit::one_sided(DVec2::ZERO, DVec2::new(1.3, 0.0), -1.0);
        assert!(pier(&points, &beam_and_pillar, &[]));
        // A wall that goes on past the stretch, its body hiding the floor there and nothing
        // seen behind it, stays a wall.
        let wall = |x: f64, y: f64| (0.0..1.3).contains(&x) && (0.0..1.5).contains(&y);
        let mut points = floor(|x, y| wall(x, y) || car(x, y));
        points.extend(face_points((0.0, 0.5), (0.2, 2.6)));
        points.extend(face_points((0.5, 1.3), (2.3, 2.6)));
        assert!(!pier(&points, &beam_and_pillar, &[]));
        // A car's wheel and flank on the beam's line past the pillar, seen up to 1.2 m only
        // (garage-153 of seeds 151-155), leave it the pillar it is.
        let mut points = floor(|x, y| pillar(x, y) || car(x, y) || (0.5..2.5).contains(&x));
        points.extend(face_points((0.0, 0.5), (0.2, 2.6)));
        points.extend(face_points((0.5, 2.5), (2.3, 2.6)));
        points.extend(face_points((0.9, 1.6), (0.3, 1.2)));
        let longer = WallFit::one_sided(DVec2::ZERO, DVec2::new(2.5, 0.0), -1.0);
        assert!(pier(&points, &longer, &[]));
        // Its face seen below head height along more than a column's width: no pillar.
        let mut points = floor(|x, y| pillar(x, y) || car(x, y));
        points.extend(face_points((0.0, 1.3), (0.2, 2.6)));
        assert!(!pier(&points, &beam_and_pillar, &[]));
    }

    /// Regression (garage-481 of seeds 481-485): a pillar under a beam, cars parked past one
    /// end, the floor past the other seen at grazing angles only, was a 1.02 m wall from the
    /// floor to the ceiling. Its face and a few returns inside the pillar measured it 0.11 m
    /// thick, and that body held 4 of the floor's returns past its free end, one row of them.
    #[test]
    fn a_pillar_measured_thin_past_a_sparse_floor_is_no_wall() {
        let car = |x: f64, y: f64| (0.55..1.5).contains(&x) && (-0.5..1.5).contains(&y);
        // The floor sampled every 10 cm, nowhere under the pillar or the car.
        let mut points: Vec<Vec3> = (0..50)
            .flat_map(|i| {
                (0..30).map(move |j| (-2.0 + 0.05 + 0.1 * i as f64, -1.0 + 0.05 + 0.1 * j as f64))
            })
            .filter(|&(x, y)| !pillar(x, y) && !car(x, y))
            .map(|(x, y)| Vec3::new(x as f32, y as f32, 0.0))
            .collect();
        points.extend(face_points((0.0, 0.5), (0.2, 2.6)));
        points.extend(face_points((0.5, 1.3), (2.3, 2.6)));
        let mut measured = WallFit::one_sided(DVec2::new(0.0, 0.055), DVec2::new(1.3, 0.055), 0.0);
        (measured.measured, measured.thickness) = (true, 0.11);
        measured.faces = vec![-0.055, 0.055];
        assert!(pier(&points, &measured, &[]));
        // Hidden past both ends, it stays a wall.
        points.retain(|p| p.z > 0.0 || p.x > 0.0);
        assert!(!pier(&points, &measured, &[]));
    }

    #[test]
    fn a_short_wall_meeting_another_or_with_no_back_seen_stays_a_wall() {
        let car = |x: f64, y: f64| (0.55..1.5).contains(&x) && (-0.5..1.5).contains(&y);
        // A wall meets the hidden end (a stub at a corner, a doorway's jamb past its end).
        let corner = WallFit::one_sided(DVec2::new(0.55, -1.0), DVec2::new(0.55, 0.0), 1.0);
        let points = floor(|x, y| pillar(x, y) || car(x, y));
        assert!(!pier(&points, &face(), &[corner]));
        // Nothing seen behind the face (a one-sided wall's body and the room beyond it).
        let points = floor(|x, y| (0.0..0.5).contains(&x) && y >= 0.0 || car(x, y));
        assert!(!pier(&points, &face(), &[]));
        // Seen free past both ends, it is a column as before.
        let points = floor(pillar);
        assert!(pier(&points, &face(), &[]));
    }
}
