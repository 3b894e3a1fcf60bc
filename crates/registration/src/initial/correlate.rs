//! The exhaustive yaw and translation search on the structure seen from above (correlative
//! scan matching, Olson 2009): the map's structure columns are rasterised into a likelihood
//! grid, and every yaw of a full circle and every sensor position of a window is scored by
//! the likelihood summed over the source's structure points.
//!
//! Every hypothesis is scored on the same source points against the same grid, so scores
//! compare fairly. The yaw step turns the farther source points (the 95th percentile of
//! their horizontal range) by about one cell, and the likelihood of a cell's neighbours (half
//! of the cell's own) tolerates that and the translation's quantisation.

use glam::{DVec2, Vec2};
use rayon::prelude::*;

/// The fewest yaw hypotheses (30 degree steps) and the most (0.5 degree steps).
const YAW_STEPS: (usize, usize) = (12, 720);
/// The longest side of the likelihood grid, in cells: a larger scene is not searched (at
/// 0.25 m cells, 1 km).
const MAX_GRID_SIDE: usize = 4096;
/// Per yaw, the best translations kept, at least this many cells apart.
const PER_YAW: usize = 3;
const PER_YAW_SEPARATION_CELLS: i64 = 4;

/// A pose hypothesis of the search: the yaw applied to the levelled source and the sensor's
/// horizontal position in the world.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Hypothesis {
    /// Yaw about the world's z axis, radians.
    pub(crate) yaw_rad: f64,
    /// The sensor's world x, y.
    pub(crate) sensor_xy: DVec2,
    /// Mean likelihood of the source's structure points (0..1).
    pub(crate) score: f64,
}

/// The search's outcome: hypotheses (best first, up to `PER_YAW` per yaw) and the number of
/// yaws tried.
pub(crate) struct Sweep {
    pub(crate) hypotheses: Vec<Hypothesis>,
    pub(crate) yaw_steps: usize,
}

/// Searches the yaw and sensor position of `source` (structure points of the levelled source,
/// relative to its sensor) against `map` (structure points in the world): sensor positions
/// within `reach` of `centre` (the previous scan's sensor) and inside the map's extent, where
/// `reach` is the 95th percentile of the source's horizontal ranges. `None` if either side
/// is empty or the grid would be absurdly large.
pub(crate) fn sweep(source: &[Vec2], map: &[Vec2], centre: DVec2, cell_m: f64) -> Option<Sweep> {
    if source.is_empty() || map.is_empty() {
        return None;
    }
    let reach = reach(source, cell_m);
    // Points beyond twice the reach are few and far: they would only widen the grid.
    let source: Vec<DVec2> = source
        .iter()
        .map(|p| p.as_dvec2())
        .filter(|p| p.length() <= 2.0 * reach)
        .collect();
    let pad = 2.0 * reach + 2.0 * cell_m;
    // Sensor positions: within the reach of the previous sensor (consecutive scans of a
    // sequence overlap: the sensor moved by less than what it sees; searching the whole map
    // instead finds the identical rooms of a floor, measured worse on generated buildings)
    // and within the map's extent.
    let (lo, hi) = map.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p.as_dvec2()), hi.max(p.as_dvec2())),
    );
    let win_lo = lo.max(centre - reach).min(centre);
    let win_hi = hi.min(centre + reach).max(centre);
    let grid = Grid::new(win_lo - pad, win_hi + pad, cell_m)?;
    let likelihood = grid.likelihood(map);
    let window = (grid.cell_of(win_lo), grid.cell_of(win_hi));
    let yaw_steps = ((std::f64::consts::TAU / (cell_m / reach).atan()).ceil() as usize)
        .clamp(YAW_STEPS.0, YAW_STEPS.1);
    let norm = 2.0 * source.len() as f64;
    let grid = &grid;
    let mut hypotheses: Vec<Hypothesis> = (0..yaw_steps)
        .into_par_iter()
        .flat_map_iter(|k| {
            let yaw = std::f64::consts::TAU * k as f64 / yaw_steps as f64;
            let rot = DVec2::from_angle(yaw);
            let offsets: Vec<isize> = source
                .iter()
                .map(|p| {
                    let q = (rot.rotate(*p) / cell_m).round();
                    q.y as isize * grid.width as isize + q.x as isize
                })
                .collect();
            best_translations(&likelihood, &offsets, grid, window)
                .into_iter()
                .map(move |(cell, sum)| Hypothesis {
                    yaw_rad: yaw,
                    sensor_xy: grid.centre_of(cell),
                    score: sum as f64 / norm,
                })
        })
        .collect();
    hypotheses.sort_by(|a, b| b.score.total_cmp(&a.score));
    Some(Sweep {
        hypotheses,
        yaw_steps,
    })
}

/// The 95th percentile of the horizontal ranges of `source` (structure points relative to
/// the sensor), at least a cell; a cell for none.
pub(crate) fn reach(source: &[Vec2], cell_m: f64) -> f64 {
    let mut ranges: Vec<f32> = source.iter().map(|p| p.length()).collect();
    ranges.sort_by(f32::total_cmp);
    let r = ranges.get(ranges.len() * 95 / 100).copied().unwrap_or(0.0) as f64;
    r.max(cell_m)
}

/// The best [`PER_YAW`] sensor cells of `window` for one yaw (offsets of the source points
/// from the sensor's cell, as indices into the grid), with their summed likelihood.
fn best_translations(
    likelihood: &[u8],
    offsets: &[isize],
    grid: &Grid,
    (lo, hi): ((i64, i64), (i64, i64)),
) -> Vec<((i64, i64), u32)> {
    let mut best: Vec<((i64, i64), u32)> = Vec::with_capacity(PER_YAW + 1);
    for y in lo.1..=hi.1 {
        for x in lo.0..=hi.0 {
            let at = (y * grid.width as i64 + x) as isize;
            // The grid is padded by twice the reach: every offset stays inside it.
            let sum: u32 = offsets
                .iter()
                .map(|o| likelihood[(at + o) as usize] as u32)
                .sum();
            if best.len() == PER_YAW && sum <= best[PER_YAW - 1].1 {
                continue;
            }
            let near = |c: &(i64, i64)| {
                (c.0 - x).abs() < PER_YAW_SEPARATION_CELLS
                    && (c.1 - y).abs() < PER_YAW_SEPARATION_CELLS
            };
            match best.iter().position(|(c, _)| near(c)) {
                Some(i) if best[i].1 >= sum => continue,
                Some(i) => {
                    best.remove(i);
                }
                None => {}
            }
            let at = best.partition_point(|(_, s)| *s >= sum);
            best.insert(at, ((x, y), sum));
            best.truncate(PER_YAW);
        }
    }
    best
}

/// A square grid over a rectangle of the horizontal plane.
struct Grid {
    origin: DVec2,
    cell_m: f64,
    width: usize,
    height: usize,
}

impl Grid {
    fn new(lo: DVec2, hi: DVec2, cell_m: f64) -> Option<Grid> {
        let size = ((hi - lo) / cell_m).ceil() + 1.0;
        let side = MAX_GRID_SIDE as f64;
        if !(size.x.is_finite() && size.y.is_finite() && size.x <= side && size.y <= side) {
            return None;
        }
        Some(Grid {
            origin: lo,
            cell_m,
            width: size.x as usize,
            height: size.y as usize,
        })
    }

    fn cell_of(&self, p: DVec2) -> (i64, i64) {
        let c = ((p - self.origin) / self.cell_m).floor();
        (c.x as i64, c.y as i64)
    }

    fn centre_of(&self, (x, y): (i64, i64)) -> DVec2 {
        self.origin + (DVec2::new(x as f64, y as f64) + 0.5) * self.cell_m
    }

    /// 2 in every cell holding a structure point, 1 in their eight neighbours, else 0.
    fn likelihood(&self, points: &[Vec2]) -> Vec<u8> {
        let mut grid = vec![0u8; self.width * self.height];
        let (w, h) = (self.width as i64, self.height as i64);
        for p in points {
            let (x, y) = self.cell_of(p.as_dvec2());
            for dy in -1..=1 {
                for dx in -1..=1 {
                    let (cx, cy) = (x + dx, y + dy);
                    if (0..w).contains(&cx) && (0..h).contains(&cy) {
                        let v = if dx == 0 && dy == 0 { 2 } else { 1 };
                        let cell = &mut grid[(cy * w + cx) as usize];
                        *cell = (*cell).max(v);
                    }
                }
            }
        }
        grid
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The outline of an L-shaped room (no symmetry), every 5 cm.
    fn l_room() -> Vec<Vec2> {
        let corners = [
            (0.0, 0.0),
            (6.0, 0.0),
            (6.0, 3.0),
            (2.5, 3.0),
            (2.5, 5.0),
            (0.0, 5.0),
        ];
        let mut out = Vec::new();
        for i in 0..corners.len() {
            let a = Vec2::from(corners[i]);
            let b = Vec2::from(corners[(i + 1) % corners.len()]);
            let n = ((b - a).length() / 0.05) as usize;
            out.extend((0..n).map(|k| a + (b - a) * k as f32 / n as f32));
        }
        out
    }

    #[test]
    fn the_true_yaw_and_position_score_best() {
        let map = l_room();
        // The sensor at (4.2, 1.6) turned by 130 degrees: the source sees the room from there.
        let (sensor, yaw) = (DVec2::new(4.2, 1.6), 130f64.to_radians());
        let back = DVec2::from_angle(-yaw);
        let source: Vec<Vec2> = map
            .iter()
            .map(|p| back.rotate(p.as_dvec2() - sensor).as_vec2())
            .collect();
        let sweep = sweep(&source, &map, DVec2::new(1.0, 1.0), 0.25).expect("searched");
        let best = sweep.hypotheses[0];
        let dyaw = (best.yaw_rad - yaw + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
            - std::f64::consts::PI;
        assert!(dyaw.abs().to_degrees() < 3.0, "{best:?}");
        assert!((best.sensor_xy - sensor).length() < 0.3, "{best:?}");
        assert!(best.score > 0.8, "{best:?}");
    }

    #[test]
    fn empty_sides_are_not_searched() {
        assert!(sweep(&[], &l_room(), DVec2::ZERO, 0.25).is_none());
        assert!(sweep(&l_room(), &[], DVec2::ZERO, 0.25).is_none());
    }
}
