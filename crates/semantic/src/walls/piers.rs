//! Free-standing piers: a pillar's face is a wall face from the floor to the ceiling, but only
//! as wide as the pillar, and the floor is seen past both of its ends. Walls meet other walls,
//! stand at the edge of a doorway, or run on behind what hid them; a stretch no longer than a
//! column is wide with the floor seen along its line beyond both ends stands free, and is a
//! column (left to the obstacles stage), not a wall.

use super::WallFit;
use crate::scene::Scene;

/// Structural columns are at most this wide across: square and round columns of buildings are
/// 0.3-0.8 m, and a free-standing pier of up to 1 m is still a column to move around.
pub(crate) const MAX_COLUMN_M: f64 = 1.0;
/// The floor is looked for this far beyond each end (from 5 cm, beyond the end's own noise).
const BEYOND_M: (f64, f64) = (0.05, 0.35);
/// ... within this distance behind a one-sided wall's face (where its body would be).
const BODY_DEPTH_M: f64 = 0.2;
/// Floor points a free end shows at least (fewer are noise or mixed pixels).
const MIN_FLOOR_POINTS: usize = 5;
/// Floor points lie within this of the floor height (the laser's range noise is 1-2 cm).
const FLOOR_TOL_M: f64 = 0.04;

/// True if `w` (before one-sided walls are moved to their centre lines: `w.line` is the face
/// of a one-sided wall) is no longer than a column and the floor is seen where its body would
/// continue past both ends.
pub(crate) fn is_free_standing_pier(w: &WallFit, sc: &Scene) -> bool {
    if w.length > MAX_COLUMN_M {
        return false;
    }
    let (b0, b1) = BEYOND_M;
    free_past(w, -b1, -b0, sc) && free_past(w, w.length + b0, w.length + b1, sc)
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
        .for_each_near_line(sc.points, &w.line, s0, s1, reach, |i, _, d| {
            let in_body = if w.measured {
                d.abs() <= w.thickness / 2.0
            } else {
                let behind = -w.free_side * d;
                (0.0..=BODY_DEPTH_M).contains(&behind)
            };
            if in_body && (sc.z(i) - sc.floor).abs() <= FLOOR_TOL_M {
                n += 1;
            }
        });
    n >= MIN_FLOOR_POINTS
}
