//! Searches on the free-space grid: Dijkstra from where the robot stands (8-connected, no
//! corner cutting, a cost that grows near obstacles so that paths keep to the middle of
//! corridors and openings), the path to a cell, and its simplification into waypoints.

use super::grid::FreeGrid;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Near obstacles a step costs up to this many times its length (at zero clearance beyond the
/// inflation); a path so prefers a corridor's middle to its edge by a few metres at most.
const NEAR_OBSTACLE_COST: f64 = 2.0;

/// The distances (m, weighted) from one cell to every free cell, and the way back.
pub(crate) struct Reach {
    dist: Vec<f32>,
    parent: Vec<u32>,
}

#[derive(PartialEq)]
struct Item(f32, u32);

impl Eq for Item {}

impl Ord for Item {
    fn cmp(&self, other: &Self) -> Ordering {
        other.0.total_cmp(&self.0).then(other.1.cmp(&self.1))
    }
}

impl PartialOrd for Item {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Reach {
    /// Dijkstra from `start` over free cells; `comfort_m` is the clearance at which a cell costs
    /// nothing extra (the radius the robot sweeps turning in place).
    pub(crate) fn from(grid: &FreeGrid, start: usize, comfort_m: f64) -> Reach {
        let n = grid.len();
        let mut dist = vec![f32::INFINITY; n];
        let mut parent = vec![u32::MAX; n];
        let mut heap = BinaryHeap::new();
        if start < n && grid.is_free(start) {
            dist[start] = 0.0;
            heap.push(Item(0.0, start as u32));
        }
        let (nx, ny) = grid.dims();
        let cell = grid.cell_m();
        let penalty = |c: usize| {
            let short = ((comfort_m - grid.clearance_m(c)) / comfort_m.max(1e-9)).clamp(0.0, 1.0);
            1.0 + NEAR_OBSTACLE_COST * short
        };
        while let Some(Item(d, c)) = heap.pop() {
            let c = c as usize;
            if d > dist[c] {
                continue;
            }
            let (i, j) = ((c % nx) as isize, (c / nx) as isize);
            for (di, dj) in [
                (1, 0),
                (-1, 0),
                (0, 1),
                (0, -1),
                (1, 1),
                (1, -1),
                (-1, 1),
                (-1, -1),
            ] {
                let (a, b) = (i + di, j + dj);
                if a < 0 || b < 0 || a >= nx as isize || b >= ny as isize {
                    continue;
                }
                let m = b as usize * nx + a as usize;
                if !grid.is_free(m) {
                    continue;
                }
                let diagonal = di != 0 && dj != 0;
                if diagonal
                    && !(grid.is_free(j as usize * nx + a as usize)
                        && grid.is_free(b as usize * nx + i as usize))
                {
                    continue;
                }
                let step = if diagonal { cell * 2f64.sqrt() } else { cell };
                let nd = d + (step * penalty(m)) as f32;
                if nd < dist[m] {
                    dist[m] = nd;
                    parent[m] = c as u32;
                    heap.push(Item(nd, m as u32));
                }
            }
        }
        Reach { dist, parent }
    }

    /// The weighted distance to a cell (infinite when unreachable).
    pub(crate) fn cost(&self, cell: usize) -> f64 {
        self.dist.get(cell).map_or(f64::INFINITY, |&d| d as f64)
    }

    /// The cells from the start to `goal` (inclusive), or `None` when unreachable.
    pub(crate) fn path(&self, goal: usize) -> Option<Vec<usize>> {
        if !self.cost(goal).is_finite() {
            return None;
        }
        let mut p = vec![goal];
        let mut c = goal;
        while self.parent[c] != u32::MAX {
            c = self.parent[c] as usize;
            p.push(c);
        }
        p.reverse();
        Some(p)
    }
}

/// The path's points simplified (Douglas-Peucker): a point is dropped where the straight line
/// replacing it stays within `tolerance_m` of the path and on free cells.
pub(crate) fn simplify(grid: &FreeGrid, points: &[[f64; 2]], tolerance_m: f64) -> Vec<[f64; 2]> {
    if points.len() < 3 {
        return points.to_vec();
    }
    let mut keep = vec![false; points.len()];
    keep[0] = true;
    keep[points.len() - 1] = true;
    let mut stack = vec![(0, points.len() - 1)];
    while let Some((a, b)) = stack.pop() {
        if b <= a + 1 {
            continue;
        }
        let (pa, pb) = (points[a], points[b]);
        let (worst, worst_d) = (a + 1..b)
            .map(|k| (k, distance_to_segment(points[k], pa, pb)))
            .fold((a + 1, -1.0), |m, x| if x.1 > m.1 { x } else { m });
        if worst_d > tolerance_m || !grid.segment_free(pa, pb) {
            keep[worst] = true;
            stack.push((a, worst));
            stack.push((worst, b));
        }
    }
    points
        .iter()
        .zip(keep)
        .filter(|(_, k)| *k)
        .map(|(p, _)| *p)
        .collect()
}

fn distance_to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
}

/// The length of a polyline (m).
pub(crate) fn length_m(points: &[[f64; 2]]) -> f64 {
    points
        .windows(2)
        .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
        .sum()
}
