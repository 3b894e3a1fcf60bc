//! Wall joins: collinear walls with a gap between them that the scans did not see through
//! are one wall (a wall runs on behind the partitions that meet it and behind whatever hid
//! it), while a gap that shows its floor (a corridor between two rooms' walls) is real.

use super::{WallConfig, WallFit};
use crate::points::undirected_angle_deg;
use crate::scene::Scene;

/// Joins collinear walls across a gap of up to `max_join_gap_m` through which the scans saw
/// nothing (no floor within a two-sided wall's footprint, nothing behind a one-sided wall's
/// face): a wall runs on behind the partitions that meet it and behind whatever hid it, while
/// a real gap (a corridor between two rooms' walls) shows its floor.
pub(crate) fn merge_through_gaps(
    walls: &mut Vec<WallFit>,
    sc: &Scene,
    c: &WallConfig,
    max_angle_deg: f64,
) {
    loop {
        let mut join = None;
        'search: for i in 0..walls.len() {
            for j in 0..walls.len() {
                if i == j {
                    continue;
                }
                let (a, b) = (&walls[i], &walls[j]);
                if undirected_angle_deg(a.line.dir, b.line.dir) > max_angle_deg {
                    continue;
                }
                let tol = c.duplicate_offset_m + (a.thickness + b.thickness) / 4.0;
                let (s0, d0) = a.line.coords(b.start());
                let (s1, d1) = a.line.coords(b.end());
                if d0.abs() > tol || d1.abs() > tol {
                    continue;
                }
                // b must lie beyond one of a's ends, within the gap: after its end, or before
                // its start (the two walls' directions need not agree).
                let (lo, hi) = (s0.min(s1), s0.max(s1));
                let (gap, hidden) = if lo > a.length {
                    (lo - a.length, (a.length, lo))
                } else {
                    (-hi, (hi, 0.0))
                };
                if gap > 0.0 && gap <= c.max_join_gap_m && !seen_through(a, hidden.0, hidden.1, sc)
                {
                    join = Some((i, j, (lo.min(0.0), hi.max(a.length)), gap));
                    break 'search;
                }
            }
        }
        let Some((i, j, (lo, hi), gap)) = join else {
            return;
        };
        let b = walls.remove(j);
        let a = &mut walls[if j < i { i - 1 } else { i }];
        let length = hi - lo;
        a.coverage = (a.coverage * a.length + b.coverage * b.length) / length.max(1e-9);
        a.line.origin = a.line.at(lo);
        a.length = length;
        a.support += b.support;
        a.rules.push(format!(
            "joined with a collinear piece across {gap:.2} m through which nothing was seen"
        ));
    }
}

/// True if the scans saw through wall `w` between `s0` and `s1` along it: floor within its
/// footprint (two faces), or anything behind its face (one face; `w.line` is the face here).
pub(crate) fn seen_through(w: &WallFit, s0: f64, s1: f64, sc: &Scene) -> bool {
    let mut n = 0;
    sc.index.for_each_near_line(
        &w.line,
        s0 + 0.05,
        s1 - 0.05,
        w.thickness / 2.0 + 1.0,
        |_, _, d, z| {
            let hit = if w.measured {
                (z - sc.floor).abs() <= 0.04 && d.abs() <= w.thickness / 2.0 - 0.02
            } else {
                let behind = -w.free_side * d;
                behind >= 0.05 && z >= sc.floor - 0.05 && z <= sc.ceiling - 0.05
            };
            n += usize::from(hit);
        },
    );
    n >= 5
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::points::XyIndex;
    use glam::{DVec2, Vec3};

    fn one_sided(from: DVec2, to: DVec2) -> WallFit {
        WallFit {
            thickness: 0.2,
            z_range: (0.0, 2.5),
            ..WallFit::one_sided(from, to, 1.0)
        }
    }

    /// Regression: collinear pieces of one wall whose directions point away from each other
    /// (the second lies before the first one's start) were never joined.
    #[test]
    fn collinear_pieces_pointing_away_from_each_other_join_across_an_unseen_gap() {
        let points: Vec<Vec3> = Vec::new();
        let index = XyIndex::new(&points, DVec2::splat(-10.0), DVec2::splat(10.0), 0.5);
        let sc = Scene::with_one_index(&points, &index, 0.0, 2.5);
        let c = WallConfig::default();
        for flip in [false, true] {
            // [4.8 -> 9] and [4.2 -> 1.4]: 0.6 m apart, nothing seen through the gap.
            let mut walls = vec![
                one_sided(DVec2::new(4.8, 0.0), DVec2::new(9.0, 0.0)),
                one_sided(DVec2::new(4.2, 0.0), DVec2::new(1.4, 0.0)),
            ];
            if flip {
                walls.reverse();
            }
            merge_through_gaps(&mut walls, &sc, &c, 3.0);
            assert_eq!(walls.len(), 1, "flip {flip}");
            let (a, b) = (walls[0].start(), walls[0].end());
            let (lo, hi) = (a.x.min(b.x), a.x.max(b.x));
            assert!(
                (lo - 1.4).abs() < 1e-9 && (hi - 9.0).abs() < 1e-9,
                "{lo} {hi}"
            );
            assert!((walls[0].length - 7.6).abs() < 1e-9);
        }
    }
}
