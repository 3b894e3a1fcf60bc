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

use super::piers::{BODY_DEPTH_M, FLOOR_TOL_M, MAX_COLUMN_M, MIN_FLOOR_POINTS};
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
/// other and its back is seen (see the module docs).
pub(crate) fn is_free_standing_pier(w: &WallFit, walls: &[WallFit], sc: &Scene) -> bool {
    if w.length > MAX_COLUMN_M {
        return false;
    }
    let (b0, b1) = BEYOND_M;
    let free_start = free_past(w, -b1, -b0, sc);
    let free_end = free_past(w, w.length + b0, w.length + b1, sc);
    if free_start == free_end {
        return free_start;
    }
    let hidden = if free_start { w.end() } else { w.start() };
    let met = walls
        .iter()
        .any(|o| !std::ptr::eq(o, w) && meets(o, hidden));
    !met && back_seen(w, sc)
}

/// True if the floor is seen in the wall's footprint between `s0` and `s1` along it.
fn free_past(w: &WallFit, s0: f64, s1: f64, sc: &Scene) -> bool {
    let reach = if w.measured {
        w.thickness / 2.0
    } else {
        BODY_DEPTH_M
    };
    let mut n = 0;
    sc.index
        .for_each_near_line(&w.line, s0, s1, reach, |_, _, d, z| {
            let in_body = if w.measured {
                d.abs() <= w.thickness / 2.0
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
        is_free_standing_pier(&walls[0], &walls, &sc)
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
