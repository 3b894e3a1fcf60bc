//! Rows of pillars: the Hough transform joins the faces of pillars in line into one segment, and
//! the face tests see a wall face at every pillar (one pillar standing free is
//! [`super::free_pier`]'s). What no wall shows is the floor seen deep inside its body (more than
//! the faces' noise behind the face, where a wall's body would hide it) between the pillars, with
//! no face in front of it (the floor is seen through a glass wall's body too, but so is its face)
//! or with surfaces seen inside a measured body too (a pillar's side, seen through a gap narrower
//! than two bins, puts returns on the face line in every bin over the gap; a glass wall's body
//! shows nothing between its faces); nor a stretch where the floor is seen right in front of the
//! face line and nothing of the face from the floor to the ceiling (a doorway has its lintel above,
//! a wall hidden behind something has the floor in front hidden too; the floor between pillars,
//! seen at grazing angles through the gap, may leave no return in a thin measured body). So the
//! candidate is cut wherever either is seen; if every piece is no longer than a column is wide and
//! stands free at both ends (cut on both sides), the candidate is a row of columns.

use super::support::HEAD_HEIGHT_M;
use super::WallFit;
use crate::scene::Scene;

/// Structural columns are at most this wide across: square and round columns of buildings are
/// 0.3-0.8 m, and a free-standing pier of up to 1 m is still a column to move around.
pub(crate) const MAX_COLUMN_M: f64 = 1.0;
/// A one-sided wall's body lies this far behind its face (where the floor is looked for).
pub(super) const BODY_DEPTH_M: f64 = 0.2;
/// Floor points a free end shows at least (fewer are noise or mixed pixels).
pub(super) const MIN_FLOOR_POINTS: usize = 5;
/// Floor points lie within this of the floor height (the laser's range noise is 1-2 cm).
pub(super) const FLOOR_TOL_M: f64 = 0.04;

/// The floor is seen in the body this far inside it at least: behind a one-sided wall's face,
/// or inside either face of a measured wall (the faces' noise is 1-3 cm, registration adds a
/// few more).
const DEEP_M: f64 = 0.06;
/// Pieces are cut in bins this long along the wall.
const ROW_BIN_M: f64 = 0.1;
/// Floor points a bin shows in the body to cut the wall there (one is a stray return) ...
const MIN_CUT_POINTS: usize = 2;
/// ... with fewer face points than this below head height (as many are a face seen: a glass
/// wall's; fewer are mixed pixels or a pillar's edge), or as many points above the floor and
/// below head height deep inside a measured wall's faces (a surface inside the body: the body
/// is open there; behind a one-sided face they may be a thin wall's back face, as a glass
/// partition's, seen through it).
const MAX_CUT_FACE_POINTS: usize = 5;
/// The most bins looked at (a cap against absurd lengths).
const MAX_BINS: usize = 1_000_000;
/// Returns this near the ceiling are the ceiling's (its range noise at grazing angles), not a
/// face's.
const CEILING_BAND_M: f64 = 0.15;
/// The floor right in front of the face line: from beyond the face's noise to where anything
/// standing against the wall (a cabinet hiding its face) would stand.
const FRONT_M: (f64, f64) = (0.05, 0.35);

/// True if `w` (before one-sided walls are moved to their centre lines) is a row of piers: cut
/// wherever the floor is seen deep in its body and its face (within `face_tolerance_m`) is not seen
/// below head height or something else is seen deep in its measured body too, or the floor is seen
/// in front of it and its face at no height, every piece is at most a column wide and has such a
/// cut on both sides (within the wall or up to a column's width past its ends).
pub(crate) fn is_row_of_piers(w: &WallFit, sc: &Scene, face_tolerance_m: f64) -> bool {
    // 1. Per bin, from a column's width before the start to as far past the end: floor points
    //    deep in the body and in front of the face line, face points below head height and at
    //    any height under the ceiling's band, other points deep in a measured body below head
    //    height.
    let reach = MAX_COLUMN_M;
    let n = (((w.length + 2.0 * reach) / ROW_BIN_M).ceil() as usize).clamp(1, MAX_BINS);
    let mut floor_in_body = vec![0usize; n];
    let mut face = vec![0usize; n];
    let mut floor_in_front = vec![0usize; n];
    let mut face_any_height = vec![0usize; n];
    let mut seen_in_body = vec![0usize; n];
    let faces: Vec<f64> = if w.measured {
        w.faces.clone()
    } else {
        vec![0.0]
    };
    let half = w.thickness / 2.0;
    let body = if w.measured { half } else { BODY_DEPTH_M };
    let depth = body.max(half + FRONT_M.1) + face_tolerance_m;
    sc.index
        .for_each_near_line(&w.line, -reach, w.length + reach, depth, |_, s, d, z| {
            let k = ((s + reach) / ROW_BIN_M).floor();
            if k < 0.0 || k as usize >= n {
                return;
            }
            let (k, above_floor) = (k as usize, z - sc.floor);
            let inside = if w.measured {
                d.abs() <= half - DEEP_M.min(half / 2.0)
            } else {
                (DEEP_M..=BODY_DEPTH_M).contains(&(-w.free_side * d))
            };
            // Off the face line on a free side: outside either face of a measured wall.
            let front = if w.measured {
                d.abs() - half
            } else {
                w.free_side * d
            };
            let on_floor = above_floor.abs() <= FLOOR_TOL_M;
            if inside && on_floor {
                floor_in_body[k] += 1;
            }
            if w.measured && inside && above_floor > 0.1 && above_floor < HEAD_HEIGHT_M {
                seen_in_body[k] += 1;
            }
            if on_floor && (FRONT_M.0..=FRONT_M.1).contains(&front) {
                floor_in_front[k] += 1;
            }
            if above_floor > 0.1 && faces.iter().any(|f| (d - f).abs() <= face_tolerance_m) {
                if z < sc.ceiling - CEILING_BAND_M {
                    face_any_height[k] += 1;
                }
                if above_floor < HEAD_HEIGHT_M {
                    face[k] += 1;
                }
            }
        });
    // A face "not seen at any height" holds under a quarter of what the candidate's faces
    // typically hold per bin: the mixed pixels at two pillars' edges spill returns into the
    // gap between them (9-15 % of a face's in hall-10's 0.28 m gaps). A glass pane in an
    // opaque wall (8 % of the beams return) is cut too, but the wall's pieces are longer than
    // a column.
    let mut seen: Vec<usize> = face_any_height
        .iter()
        .copied()
        .filter(|&f| f >= MAX_CUT_FACE_POINTS)
        .collect();
    seen.sort_unstable();
    let typical = seen.get(seen.len() / 2).copied().unwrap_or(0);
    let unseen = MAX_CUT_FACE_POINTS.max(typical / 4);
    let cut: Vec<bool> = (0..n)
        .map(|k| {
            (floor_in_body[k] >= MIN_CUT_POINTS
                && (face[k] < MAX_CUT_FACE_POINTS || seen_in_body[k] >= MAX_CUT_FACE_POINTS))
                || (floor_in_front[k] >= MIN_FLOOR_POINTS && face_any_height[k] < unseen)
        })
        .collect();
    // 2. The pieces between cuts that overlap the wall: each short, with a cut on both sides.
    let (first, last) = (
        (reach / ROW_BIN_M).round() as usize,
        (((reach + w.length) / ROW_BIN_M).ceil() as usize).min(n),
    );
    let mut pieces = 0;
    let mut k = 0;
    while k < n {
        if cut[k] {
            k += 1;
            continue;
        }
        let start = k;
        while k < n && !cut[k] {
            k += 1;
        }
        if k <= first || start >= last {
            continue; // a piece wholly beyond the wall's ends
        }
        let free_both = start > 0 && k < n;
        if !free_both || (k - start) as f64 * ROW_BIN_M > MAX_COLUMN_M {
            return false;
        }
        pieces += 1;
    }
    pieces >= 1
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::points::XyIndex;
    use glam::{DVec2, Vec3};

    /// A one-sided wall's face along y = 0 from x = 0 to `length`, free space at y < 0.
    fn face(length: f64) -> WallFit {
        WallFit::one_sided(DVec2::ZERO, DVec2::new(length, 0.0), -1.0)
    }

    /// Floor points on a 5 cm grid over x in [-2, 6], y in [-1, 1] where `solid` is false, and
    /// face points on y = 0 at heights 0.2..1.8 where `faced` is true.
    fn cloud(solid: impl Fn(f64, f64) -> bool, faced: impl Fn(f64) -> bool) -> Vec<Vec3> {
        let mut points = crate::walls::test_floor((-2.0, -1.0), (160, 40), solid);
        for i in 0..160 {
            let x = -2.0 + i as f64 * 0.05 + 0.025;
            if faced(x) {
                for k in 0..9 {
                    points.push(Vec3::new(x as f32, 0.0, 0.2 + k as f32 * 0.2));
                }
            }
        }
        points
    }

    fn row_of_piers(points: &[Vec3], w: &WallFit) -> bool {
        let index = XyIndex::new(points, DVec2::splat(-3.0), DVec2::splat(7.0), 0.25);
        let sc = Scene::with_one_index(points, &index, 0.0, 3.0);
        is_row_of_piers(w, &sc, 0.03)
    }

    #[test]
    fn pillars_in_a_row_with_the_floor_seen_between_them_are_no_wall() {
        // Four 0.48 m pillars 0.875 m apart (0.395 m gaps), their faces on y = 0.
        let pillar = |x: f64| (0..4).any(|k| (x - 0.24 - k as f64 * 0.875).abs() <= 0.24);
        let points = cloud(|x, y| y > 0.0 && y < 0.48 && pillar(x), pillar);
        assert!(row_of_piers(&points, &face(3.105)));
    }

    #[test]
    fn a_wall_with_a_doorway_or_a_glass_wall_is_no_row_of_piers() {
        // A 5 m wall with a 0.9 m doorway: the floor is seen in its body there, but the pieces
        // either side are 2 m and 2.1 m long.
        let wall = |x: f64| (0.0..=5.0).contains(&x) && !(2.0..2.9).contains(&x);
        let points = cloud(|x, y| y > 0.0 && y < 0.2 && wall(x), wall);
        assert!(!row_of_piers(&points, &face(5.0)));
        // A glass wall: the floor seen through its body everywhere, its face too.
        let points = cloud(|_, _| false, |x| (0.0..=5.0).contains(&x));
        assert!(!row_of_piers(&points, &face(5.0)));
        // The same pillars' faces without the floor seen between them (nothing seen behind
        // the row), the face seen above head height along all of it: a wall whose face lost
        // its returns below head height in places stands as one piece.
        let pillar = |x: f64| (0..4).any(|k| (x - 0.24 - k as f64 * 0.875).abs() <= 0.24);
        let mut points = cloud(|x, y| y > 0.0 && y < 0.48 && x > 0.0 && x < 3.1, pillar);
        points.extend(above_head(0.0, 3.1));
        assert!(!row_of_piers(&points, &face(3.105)));
    }

    /// A wall `thickness_m` thick, both faces seen (at y = 0 and y = `thickness_m`), from x = 0
    /// to `length`.
    fn measured(length: f64, thickness_m: f64) -> WallFit {
        let y = thickness_m / 2.0;
        let mut w = WallFit::one_sided(DVec2::new(0.0, y), DVec2::new(length, y), -1.0);
        (w.thickness, w.measured, w.faces) = (thickness_m, true, vec![-y, y]);
        w
    }

    /// Points on `x` from y = 0 to 0.44 every 4 cm at heights 0.2..1.8 (a pillar's side face).
    fn side_face(x: f64) -> impl Iterator<Item = Vec3> {
        (0..12)
            .flat_map(|i| (0..9).map(move |h| (i, h)))
            .map(move |(i, h)| Vec3::new(x as f32, 0.04 * i as f32, 0.2 + 0.2 * h as f32))
    }

    #[test]
    fn pillars_whose_gaps_are_narrower_than_two_bins_are_no_wall() {
        // Four 0.44 m pillars with 0.16 m gaps (hall-123's row), seen from both sides, every
        // gap starting 2 cm into a bin: each bin over a gap holds a pillar's side face, seen
        // through the gap from one face line to the other, with returns on both. The floor is
        // seen deep in the gaps' bodies too: the body is open there, whatever stands on the
        // face lines.
        let pillar = |x: f64| (0..4).any(|k| (x - 0.2 - k as f64 * 0.6).abs() <= 0.22);
        let mut points = cloud(|x, y| y > 0.0 && y < 0.44 && pillar(x), pillar);
        for k in 0..4 {
            let x0 = k as f64 * 0.6 - 0.02;
            points.extend(side_face(x0).chain(side_face(x0 + 0.44)));
            points.extend((0..9).flat_map(|i| {
                (0..9).map(move |h| {
                    Vec3::new(
                        (x0 + 0.025 + 0.05 * i as f64) as f32,
                        0.44,
                        0.2 + 0.2 * h as f32,
                    )
                })
            }));
        }
        assert!(row_of_piers(&points, &measured(2.24, 0.44)));
    }

    #[test]
    fn a_glass_partitions_back_pane_seen_through_its_face_is_no_gap() {
        // A 0.15 m glass partition seen from one side: its face and its back pane (in the body
        // a one-sided face assumes) are seen along all of it, the floor through it in 0.6 m of
        // every metre (hidden behind desks elsewhere). office-3's partition was cut into short
        // pieces where its back pane counted as something seen inside a body.
        let mut points = cloud(
            |x, y| y > 0.0 && x.rem_euclid(1.0) >= 0.6,
            |x| (0.0..=5.0).contains(&x),
        );
        points.extend((0..100).flat_map(|i| {
            (0..9).map(move |h| {
                Vec3::new((0.025 + 0.05 * i as f64) as f32, 0.15, 0.2 + 0.2 * h as f32)
            })
        }));
        assert!(!row_of_piers(&points, &face(5.0)));
    }

    /// Face points on y = 0 at heights 2.0..2.8 from x0 to x1, every 5 cm.
    fn above_head(x0: f64, x1: f64) -> Vec<Vec3> {
        let n = ((x1 - x0) / 0.05) as usize;
        (0..n)
            .flat_map(|i| (0..5).map(move |k| (i, k)))
            .map(|(i, k)| {
                Vec3::new(
                    (x0 + 0.025 + i as f64 * 0.05) as f32,
                    0.0,
                    2.0 + 0.2 * k as f32,
                )
            })
            .collect()
    }

    #[test]
    fn pillars_with_nothing_between_them_up_to_the_ceiling_are_no_wall() {
        // The same pillars with no floor seen behind the row (hidden, or too thin a body for
        // a return), but the floor seen in front of the gaps and no face in them at any
        // height: hall-7's pillars, whose row was a wall, read as a 2.8 m wall.
        let pillar = |x: f64| (0..4).any(|k| (x - 0.24 - k as f64 * 0.875).abs() <= 0.24);
        let mut points = cloud(|x, y| y > 0.0 && y < 0.48 && x > 0.0 && x < 3.1, pillar);
        for k in 0..4 {
            let x0 = k as f64 * 0.875;
            points.extend(above_head(x0, x0 + 0.48));
        }
        assert!(row_of_piers(&points, &face(3.105)));
        // With a lintel over the gaps (doorways), it is a wall.
        points.extend(above_head(0.0, 3.1));
        assert!(!row_of_piers(&points, &face(3.105)));
    }
}
