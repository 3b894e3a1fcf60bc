//! Internal helpers shared by the stages: the finite points in the map frame, an XY bucket
//! index over them, a simple 2D line type and robust statistics.

use glam::{DVec2, Vec3};

/// The finite input points, levelled into the map frame, with their input indices.
pub(crate) struct MapPoints {
    /// Positions in the map frame.
    pub points: Vec<Vec3>,
    /// For each point, its index in the input cloud.
    pub input_index: Vec<u32>,
}

/// An XY bucket index (compressed rows: bucket -> point indices) for neighbourhood queries.
pub(crate) struct XyIndex {
    min: DVec2,
    cell_m: f64,
    cols: usize,
    rows: usize,
    start: Vec<u32>,
    items: Vec<u32>,
    /// The points of `items`, in the same order: a cell's points lie together in memory, so a
    /// walk over cells reads them in sequence instead of gathering them from the whole cloud.
    at: Vec<Vec3>,
}

impl XyIndex {
    /// Buckets `points` (those inside `[min, max]`; others are left out) into cells of `cell_m`.
    pub fn new(points: &[Vec3], min: DVec2, max: DVec2, cell_m: f64) -> XyIndex {
        XyIndex::filtered(points, min, max, cell_m, |_| true)
    }

    /// As [`XyIndex::new`], for the points that pass `keep` only (indices stay those of `points`).
    pub fn filtered(
        points: &[Vec3],
        min: DVec2,
        max: DVec2,
        cell_m: f64,
        keep: impl Fn(&Vec3) -> bool,
    ) -> XyIndex {
        let cols = (((max.x - min.x) / cell_m).floor() as usize + 1).clamp(1, 1 << 16);
        let rows = (((max.y - min.y) / cell_m).floor() as usize + 1).clamp(1, 1 << 16);
        let cell_of = |p: &Vec3| -> Option<usize> {
            if !keep(p) {
                return None;
            }
            // (for a non-negative value the cast is the floor)
            let c = (p.x as f64 - min.x) / cell_m;
            let r = (p.y as f64 - min.y) / cell_m;
            (c >= 0.0 && r >= 0.0 && (c as usize) < cols && (r as usize) < rows)
                .then(|| r as usize * cols + c as usize)
        };
        let mut start = vec![0u32; cols * rows + 1];
        for p in points {
            if let Some(c) = cell_of(p) {
                start[c + 1] += 1;
            }
        }
        for i in 0..cols * rows {
            start[i + 1] += start[i];
        }
        let mut fill = start.clone();
        let mut items = vec![0u32; start[cols * rows] as usize];
        let mut at = vec![Vec3::ZERO; items.len()];
        for (i, p) in points.iter().enumerate() {
            if let Some(c) = cell_of(p) {
                items[fill[c] as usize] = i as u32;
                at[fill[c] as usize] = *p;
                fill[c] += 1;
            }
        }
        XyIndex {
            min,
            cell_m,
            cols,
            rows,
            start,
            items,
            at,
        }
    }

    /// Calls `f` with every indexed point near the rectangle along `line` from `s0` to `s1`,
    /// within `half_width` across; `f` gets the point index, its along- and across-coordinates
    /// and its height. Only the cells the (turned) rectangle overlaps are visited, row by row:
    /// a diagonal wall reads a strip of cells, not its bounding box.
    pub fn for_each_near_line(
        &self,
        line: &Line2,
        s0: f64,
        s1: f64,
        half_width: f64,
        mut f: impl FnMut(usize, f64, f64, f64),
    ) {
        let n = line.normal() * half_width;
        let (a, b) = (line.at(s0), line.at(s1));
        let corners = [a - n, b - n, b + n, a + n];
        let lo = corners.iter().fold(DVec2::INFINITY, |m, c| m.min(*c));
        let hi = corners.iter().fold(DVec2::NEG_INFINITY, |m, c| m.max(*c));
        let r0 = ((lo.y - self.min.y) / self.cell_m).floor().max(0.0);
        let r1 = ((hi.y - self.min.y) / self.cell_m).floor();
        // (NaN coordinates fail every comparison: nothing is visited)
        let visits = r0 <= r1 && r1 >= 0.0 && r0 < self.rows as f64;
        if !visits {
            return;
        }
        let r1 = (r1 as usize).min(self.rows - 1);
        for r in r0 as usize..=r1 {
            // The rectangle's x range within this row of cells (a little padding for rounding).
            let y0 = self.min.y + r as f64 * self.cell_m;
            let Some((x0, x1)) = x_range_in_strip(&corners, y0, y0 + self.cell_m) else {
                continue;
            };
            let c0 = ((x0 - 1e-6 - self.min.x) / self.cell_m).floor().max(0.0);
            let c1 = ((x1 + 1e-6 - self.min.x) / self.cell_m).floor();
            if c1 < 0.0 || c0 >= self.cols as f64 {
                continue;
            }
            let (c0, c1) = (c0 as usize, (c1 as usize).min(self.cols - 1));
            let from = self.start[r * self.cols + c0] as usize;
            let to = self.start[r * self.cols + c1 + 1] as usize;
            for (&i, p) in self.items[from..to].iter().zip(&self.at[from..to]) {
                let (s, d) = line.coords(DVec2::new(p.x as f64, p.y as f64));
                if s >= s0 && s <= s1 && d.abs() <= half_width {
                    f(i as usize, s, d, p.z as f64);
                }
            }
        }
    }
}

/// The x range of the convex polygon `corners` (in order) within the strip `y0 <= y <= y1`:
/// its corners inside the strip and its edges' crossings of the strip's borders.
fn x_range_in_strip(corners: &[DVec2], y0: f64, y1: f64) -> Option<(f64, f64)> {
    let (mut x0, mut x1) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut take = |x: f64| {
        x0 = x0.min(x);
        x1 = x1.max(x);
    };
    for (k, p) in corners.iter().enumerate() {
        if p.y >= y0 && p.y <= y1 {
            take(p.x);
        }
        let q = corners[(k + 1) % corners.len()];
        for y in [y0, y1] {
            if (p.y - y) * (q.y - y) < 0.0 {
                take(p.x + (q.x - p.x) * (y - p.y) / (q.y - p.y));
            }
        }
    }
    (x0 <= x1).then_some((x0, x1))
}

/// A 2D line through `origin` with unit direction `dir`; `normal` is `dir` turned left (the
/// map frame's lines along walls, shared with the evaluation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Line2 {
    /// A point on the line.
    pub origin: DVec2,
    /// Its unit direction.
    pub dir: DVec2,
}

impl Line2 {
    /// The line from `a` towards `b` (x axis if they coincide).
    pub fn through(a: DVec2, b: DVec2) -> Line2 {
        let d = b - a;
        let dir = if d.length() > 1e-12 {
            d.normalize()
        } else {
            DVec2::X
        };
        Line2 { origin: a, dir }
    }

    /// The left normal.
    pub fn normal(&self) -> DVec2 {
        self.dir.perp()
    }

    /// The point at along-coordinate `s`.
    pub fn at(&self, s: f64) -> DVec2 {
        self.origin + self.dir * s
    }

    /// Along- and across- (left positive) coordinates of `q`.
    pub fn coords(&self, q: DVec2) -> (f64, f64) {
        let v = q - self.origin;
        (v.dot(self.dir), v.dot(self.normal()))
    }

    /// The same line moved `offset` to the left.
    pub fn shifted(&self, offset: f64) -> Line2 {
        Line2 {
            origin: self.origin + self.normal() * offset,
            dir: self.dir,
        }
    }

    /// Direction angle in radians.
    pub fn angle(&self) -> f64 {
        self.dir.y.atan2(self.dir.x)
    }
}

/// The angle between two undirected directions, in degrees (0..=90).
pub fn undirected_angle_deg(a: DVec2, b: DVec2) -> f64 {
    let c = a
        .normalize_or_zero()
        .dot(b.normalize_or_zero())
        .abs()
        .min(1.0);
    c.acos().to_degrees()
}

/// Counts of `values` in `n` bins of `bin_m` from `lo` (values outside them left out), each
/// summed with its `half` neighbours on either side (clipped at the ends): how many values lie
/// within about `half` bins of each bin (a histogram's peaks of faces or lines).
pub(crate) fn window_counts(
    values: &[f64],
    lo: f64,
    bin_m: f64,
    n: usize,
    half: usize,
) -> Vec<usize> {
    let mut cumulative = vec![0usize; n + 1];
    for v in values {
        // (for a non-negative value the cast is the floor)
        let b = (v - lo) / bin_m;
        if b >= 0.0 && (b as usize) < n {
            cumulative[b as usize + 1] += 1;
        }
    }
    for i in 0..n {
        cumulative[i + 1] += cumulative[i];
    }
    (0..n)
        .map(|i| cumulative[(i + half + 1).min(n)] - cumulative[i.saturating_sub(half)])
        .collect()
}

/// The `q`-quantile (0..=1) of `v` (reordered in place, in linear time); `None` if empty.
pub(crate) fn quantile(v: &mut [f64], q: f64) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    let i = ((v.len() - 1) as f64 * q.clamp(0.0, 1.0)).round() as usize;
    Some(*v.select_nth_unstable_by(i, f64::total_cmp).1)
}

/// Median of `v` (reordered in place); `None` if empty.
pub(crate) fn median(v: &mut [f64]) -> Option<f64> {
    quantile(v, 0.5)
}

/// Least-squares slope and intercept of `y = a + b x`; `None` for fewer than 2 distinct x.
pub(crate) fn linear_fit(xy: &[(f64, f64)]) -> Option<(f64, f64)> {
    let n = xy.len() as f64;
    if xy.len() < 2 {
        return None;
    }
    let mx = xy.iter().map(|p| p.0).sum::<f64>() / n;
    let my = xy.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = xy.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = xy.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    if sxx < 1e-12 {
        return None;
    }
    let b = sxy / sxx;
    Some((my - b * mx, b))
}

/// Total-least-squares line through weighted 2D points: centroid and unit direction.
pub(crate) fn fit_line(points: &[DVec2]) -> Option<(DVec2, DVec2)> {
    if points.len() < 2 {
        return None;
    }
    let n = points.len() as f64;
    let c = points.iter().copied().sum::<DVec2>() / n;
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for p in points {
        let d = *p - c;
        sxx += d.x * d.x;
        sxy += d.x * d.y;
        syy += d.y * d.y;
    }
    let angle = 0.5 * (2.0 * sxy).atan2(sxx - syy);
    let dir = DVec2::new(angle.cos(), angle.sin());
    (sxx + syy > 1e-12).then_some((c, dir))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn index_finds_points_near_a_line() {
        let pts: Vec<Vec3> = (0..100)
            .map(|i| Vec3::new(i as f32 * 0.1, (i % 3) as f32 * 0.1, 0.5 + i as f32 * 0.01))
            .collect();
        let idx = XyIndex::new(&pts, DVec2::new(0.0, 0.0), DVec2::new(10.0, 1.0), 0.5);
        let line = Line2::through(DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0));
        let mut n = 0;
        idx.for_each_near_line(&line, 2.0, 4.0, 0.05, |i, s, d, z| {
            assert!((2.0..=4.0).contains(&s) && d.abs() <= 0.05);
            assert_eq!(z, pts[i].z as f64, "the height handed over is the point's");
            n += 1;
        });
        assert_eq!(n, 7);
    }

    #[test]
    fn a_diagonal_strip_visits_the_same_points_as_a_full_scan() {
        // A grid of points, a thin strip at 30 degrees: the row-clipped walk must pass exactly
        // the points the plain test passes.
        let pts: Vec<Vec3> = (0..200 * 200)
            .map(|k| Vec3::new((k % 200) as f32 * 0.05, (k / 200) as f32 * 0.05, 0.0))
            .collect();
        let idx = XyIndex::new(&pts, DVec2::ZERO, DVec2::splat(10.0), 0.25);
        let dir = DVec2::new(30f64.to_radians().cos(), 30f64.to_radians().sin());
        let line = Line2 {
            origin: DVec2::new(1.0, 2.0),
            dir,
        };
        let mut seen = Vec::new();
        idx.for_each_near_line(&line, -0.5, 7.0, 0.12, |i, _, _, _| seen.push(i));
        let want: Vec<usize> = (0..pts.len())
            .filter(|&i| {
                let (s, d) = line.coords(DVec2::new(pts[i].x as f64, pts[i].y as f64));
                (-0.5..=7.0).contains(&s) && d.abs() <= 0.12
            })
            .collect();
        seen.sort_unstable();
        assert!(want.len() > 500, "{}", want.len());
        assert_eq!(seen, want);
    }

    #[test]
    fn fits() {
        let (a, b) = linear_fit(&[(0.0, 1.0), (1.0, 3.0), (2.0, 5.0)]).expect("fit");
        assert!((a - 1.0).abs() < 1e-12 && (b - 2.0).abs() < 1e-12);
        let (_, dir) = fit_line(&[
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(2.0, 2.0),
        ])
        .expect("fit");
        assert!((undirected_angle_deg(dir, DVec2::new(1.0, 1.0))).abs() < 1e-6);
        assert_eq!(median(&mut [3.0, 1.0, 2.0]), Some(2.0));
    }
}
