//! Where the floor was seen: its footprint as a few rectangles.
//!
//! A registered cloud sees the floor only where the laser reached it: a corridor's floor
//! near the scan positions, a room's through its open door, and nothing behind closed doors
//! or beyond the last scan line at grazing incidence. One box around all of it (its extent)
//! would claim floor where none was seen, or, turned along one wall, miss a hall beside a
//! corridor. So the floor's points (within `surface_tolerance_m` of its height) are counted in
//! XY cells of a frame turned by the slab yaw; a cell with `footprint_min_points` of them is
//! seen floor; gaps up to `footprint_closing_m` across are closed (the floor between a
//! rotating laser's scan lines, and under what stands on it: chair legs, bins, a person's
//! feet); and the cells are covered by non-overlapping rectangles, largest first, until what
//! is left is smaller than `footprint_min_area_m2` (a floor patch no robot or person stands
//! on). The floor entity's box is the extent of the rectangles.

use super::FloorCeilingConfig;
use glam::Vec3;

/// The most cells of the footprint grid: the cell grows beyond this (a 200 m x 200 m floor at
/// 0.2 m), so that memory never depends on how far apart two stray points are.
const MAX_CELLS: usize = 1_000_000;
/// The most rectangles of one footprint: a floor of more parts than this is covered by its
/// largest ones (what is left is listed in the rule text).
const MAX_PARTS: usize = 64;

/// The floor's footprint: rectangles (min, max) in the frame turned by the slab yaw, largest
/// first, and how many of the seen cells they cover.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct FloorFootprint {
    pub parts: Vec<([f64; 2], [f64; 2])>,
    /// Seen floor cells (after closing) and how many of them the parts cover.
    pub seen_cells: usize,
    pub covered_cells: usize,
    /// The cell edge used (m).
    pub cell_m: f64,
}

impl FloorFootprint {
    /// The extent of the parts: (min, max) in the turned frame.
    pub fn extent(&self) -> Option<([f64; 2], [f64; 2])> {
        let mut it = self.parts.iter();
        let first = *it.next()?;
        Some(it.fold(first, |(lo, hi), (a, b)| {
            (
                [lo[0].min(a[0]), lo[1].min(a[1])],
                [hi[0].max(b[0]), hi[1].max(b[1])],
            )
        }))
    }
}

/// The footprint of the floor at height `z` (map frame) in the frame turned by `yaw` (rad);
/// `None` where fewer than 10 points lie on the floor.
pub(crate) fn floor_footprint(
    points: &[Vec3],
    z: f64,
    yaw: f64,
    c: &FloorCeilingConfig,
) -> Option<FloorFootprint> {
    // 1. The floor's points in the turned frame.
    let (s, co) = yaw.sin_cos();
    let uv: Vec<[f64; 2]> = points
        .iter()
        .filter(|p| (p.z as f64 - z).abs() <= c.surface_tolerance_m)
        .map(|p| {
            let (x, y) = (p.x as f64, p.y as f64);
            [co * x + s * y, -s * x + co * y]
        })
        .collect();
    if uv.len() < 10 {
        return None;
    }
    // 2. The grid: the points' extent padded by the closing radius (cells grown where it
    //    would exceed `MAX_CELLS`).
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in &uv {
        lo = [lo[0].min(p[0]), lo[1].min(p[1])];
        hi = [hi[0].max(p[0]), hi[1].max(p[1])];
    }
    let pad = c.footprint_closing_m;
    let (lo, hi) = ([lo[0] - pad, lo[1] - pad], [hi[0] + pad, hi[1] + pad]);
    let (w, h) = (hi[0] - lo[0], hi[1] - lo[1]);
    let cell = c
        .footprint_cell_m
        .max(((w * h) / MAX_CELLS as f64).sqrt() * 1.01);
    let nx = ((w / cell).floor() as usize + 1).max(1);
    let ny = ((h / cell).floor() as usize + 1).max(1);
    let mut count = vec![0u32; nx * ny];
    // Per cell, the extent of its points (min u, min v, max u, max v): a part's edges are
    // where its points end, not where its cells do.
    let mut bounds = vec![
        [
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY
        ];
        nx * ny
    ];
    for p in &uv {
        let i = (((p[0] - lo[0]) / cell) as usize).min(nx - 1);
        let j = (((p[1] - lo[1]) / cell) as usize).min(ny - 1);
        let k = j * nx + i;
        count[k] = count[k].saturating_add(1);
        let b = &mut bounds[k];
        *b = [
            b[0].min(p[0]),
            b[1].min(p[1]),
            b[2].max(p[0]),
            b[3].max(p[1]),
        ];
    }
    // 3. Seen cells, closed over gaps up to `footprint_closing_m` (a dilation by half of it,
    //    then an erosion: inside the padding, so that seen cells all stay).
    let seen: Vec<bool> = count
        .iter()
        .map(|&n| n as usize >= c.footprint_min_points)
        .collect();
    let r = (c.footprint_closing_m / (2.0 * cell)).round() as usize;
    let closed = erode(&dilate(&seen, nx, ny, r), nx, ny, r);
    let seen_cells = closed.iter().filter(|&&v| v).count();
    // 4. Rectangles, largest first, until the rest is smaller than the least area.
    let min_cells = (c.footprint_min_area_m2 / (cell * cell)).ceil().max(1.0) as usize;
    let mut left = closed.clone();
    let mut parts = Vec::new();
    let mut covered_cells = 0;
    while parts.len() < MAX_PARTS {
        let Some((i0, j0, i1, j1)) = largest_rectangle(&left, nx, ny) else {
            break;
        };
        let n = (i1 - i0) * (j1 - j0);
        if n < min_cells {
            break;
        }
        for j in j0..j1 {
            left[j * nx + i0..j * nx + i1].fill(false);
        }
        covered_cells += n;
        // The extent of the part's points, within its cells (cells filled by the closing
        // alone add no extent): a part ends where the floor was seen, not where its cells do.
        let mut e = [
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ];
        for j in j0..j1 {
            for b in &bounds[j * nx + i0..j * nx + i1] {
                e = [
                    e[0].min(b[0]),
                    e[1].min(b[1]),
                    e[2].max(b[2]),
                    e[3].max(b[3]),
                ];
            }
        }
        // An edge moves in to its points only where no seen floor lies beyond it: between two
        // parts the floor goes on (no gap may open between them).
        let seen_beyond = |cells: &mut dyn Iterator<Item = usize>| {
            let mut any = false;
            for k in cells {
                any |= closed[k];
            }
            any
        };
        let open = [
            i0 > 0 && seen_beyond(&mut (j0..j1).map(|j| j * nx + i0 - 1)),
            j0 > 0 && seen_beyond(&mut (i0..i1).map(|i| (j0 - 1) * nx + i)),
            i1 < nx && seen_beyond(&mut (j0..j1).map(|j| j * nx + i1)),
            j1 < ny && seen_beyond(&mut (i0..i1).map(|i| j1 * nx + i)),
        ];
        let cells_edge = [
            lo[0] + i0 as f64 * cell,
            lo[1] + j0 as f64 * cell,
            lo[0] + i1 as f64 * cell,
            lo[1] + j1 as f64 * cell,
        ];
        let edge = |k: usize| {
            if open[k] || !e[k].is_finite() {
                cells_edge[k]
            } else {
                e[k]
            }
        };
        let part = ([edge(0), edge(1)], [edge(2), edge(3)]);
        parts.push(part);
    }
    Some(FloorFootprint {
        parts,
        seen_cells,
        covered_cells,
        cell_m: cell,
    })
}

/// Square dilation by `r` cells (separable: rows, then columns).
fn dilate(m: &[bool], nx: usize, ny: usize, r: usize) -> Vec<bool> {
    morph(m, nx, ny, r, true)
}

/// Square erosion by `r` cells; outside the grid counts as empty.
fn erode(m: &[bool], nx: usize, ny: usize, r: usize) -> Vec<bool> {
    morph(m, nx, ny, r, false)
}

/// Dilation (`any`) or erosion (all) over a (2r+1)-square window, by running counts.
fn morph(m: &[bool], nx: usize, ny: usize, r: usize, any: bool) -> Vec<bool> {
    if r == 0 {
        return m.to_vec();
    }
    let pass = |src: &[bool], len: usize, lines: usize, at: &dyn Fn(usize, usize) -> usize| {
        let mut out = vec![false; src.len()];
        for l in 0..lines {
            // Number of set cells in the window around k (cells outside the grid are unset).
            let mut n = 0usize;
            for k in 0..r.min(len) {
                n += usize::from(src[at(l, k)]);
            }
            for k in 0..len {
                if k + r < len {
                    n += usize::from(src[at(l, k + r)]);
                }
                if k > r {
                    n -= usize::from(src[at(l, k - r - 1)]);
                }
                out[at(l, k)] = if any { n > 0 } else { n == 2 * r + 1 };
            }
        }
        out
    };
    let rows = pass(m, nx, ny, &|j, i| j * nx + i);
    pass(&rows, ny, nx, &|i, j| j * nx + i)
}

/// The largest all-set rectangle (cells `i0..i1` x `j0..j1`), by the histogram method:
/// O(cells).
fn largest_rectangle(m: &[bool], nx: usize, ny: usize) -> Option<(usize, usize, usize, usize)> {
    let mut height = vec![0usize; nx];
    let mut best: Option<(usize, (usize, usize, usize, usize))> = None;
    let mut stack: Vec<usize> = Vec::with_capacity(nx + 1);
    for j in 0..ny {
        for i in 0..nx {
            height[i] = if m[j * nx + i] { height[i] + 1 } else { 0 };
        }
        stack.clear();
        for i in 0..=nx {
            let h = if i < nx { height[i] } else { 0 };
            while let Some(&top) = stack.last() {
                if height[top] <= h {
                    break;
                }
                stack.pop();
                let left = stack.last().map_or(0, |&l| l + 1);
                let area = height[top] * (i - left);
                if area > 0 && best.is_none_or(|(a, _)| area > a) {
                    best = Some((area, (left, j + 1 - height[top], i, j + 1)));
                }
            }
            stack.push(i);
        }
    }
    best.map(|(_, r)| r)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Floor points every `step` m over the rectangles, at z = 0.
    fn floor(rects: &[([f64; 2], [f64; 2])], step: f64) -> Vec<Vec3> {
        let mut v = Vec::new();
        for (lo, hi) in rects {
            let (nx, ny) = (
                ((hi[0] - lo[0]) / step) as usize,
                ((hi[1] - lo[1]) / step) as usize,
            );
            for i in 0..=nx {
                for j in 0..=ny {
                    let (x, y) = (lo[0] + i as f64 * step, lo[1] + j as f64 * step);
                    v.push(Vec3::new(x as f32, y as f32, 0.0));
                }
            }
        }
        v
    }

    fn area(f: &FloorFootprint) -> f64 {
        f.parts
            .iter()
            .map(|(lo, hi)| (hi[0] - lo[0]) * (hi[1] - lo[1]))
            .sum()
    }

    #[test]
    fn an_l_shaped_floor_is_two_rectangles_not_its_extent() {
        // A corridor 20 m x 2.5 m and a hall 5 m x 6 m beside its start: 80 m2 of floor in an
        // extent of 20 m x 8.5 m = 170 m2.
        let pts = floor(&[([0.0, 0.0], [20.0, 2.5]), ([0.0, 2.5], [5.0, 8.5])], 0.05);
        let c = FloorCeilingConfig::default();
        let f = floor_footprint(&pts, 0.0, 0.0, &c).expect("floor");
        assert_eq!(f.parts.len(), 2, "{:?}", f.parts);
        // 80 m2 within a cell (0.2 m) along the parts' 20 m inner edge, where they meet on a
        // cell boundary; far from the extent's 170 m2.
        let a = area(&f);
        assert!((a - 80.0).abs() < 4.5, "area {a}");
        let (lo, hi) = f.extent().expect("extent");
        assert!(lo[0] < 0.1 && hi[0] > 19.9 && hi[1] > 8.4, "{lo:?} {hi:?}");
        // The outer edges are where the points end (within 5 cm), and the two parts meet
        // with no gap between them (a robot drives from one onto the other).
        assert!(
            lo[0] > -0.05 && lo[1] > -0.05 && hi[0] < 20.05,
            "{lo:?} {hi:?}"
        );
        let [(a0, a1), (b0, b1)] = [f.parts[0], f.parts[1]];
        let touch = |p0: [f64; 2], p1: [f64; 2], q0: [f64; 2], q1: [f64; 2]| {
            (p1[1] - q0[1]).abs() < 1e-9 && p0[0] < q1[0] && q0[0] < p1[0]
        };
        assert!(
            touch(a0, a1, b0, b1) || touch(b0, b1, a0, a1),
            "{:?}",
            f.parts
        );
    }

    #[test]
    fn gaps_between_scan_lines_are_closed_but_a_far_patch_stays_apart() {
        // Floor points on lines 0.3 m apart (a laser's lines at grazing incidence) over
        // 10 m x 3 m, and a 1 m x 1 m patch 5 m away (a room seen through a door).
        let lines: Vec<Vec3> = (0..=10)
            .flat_map(|k| (0..=200).map(move |i| Vec3::new(i as f32 * 0.05, k as f32 * 0.3, 0.0)))
            .collect();
        let patch = floor(&[([15.0, 0.0], [16.0, 1.0])], 0.05);
        let all: Vec<Vec3> = lines.into_iter().chain(patch).collect();
        let c = FloorCeilingConfig::default();
        let f = floor_footprint(&all, 0.0, 0.0, &c).expect("floor");
        // The lined floor is one part of about 30 m2; the patch is another, not bridged.
        let a = area(&f);
        assert!((a - 31.0).abs() < 3.0, "area {a}: {:?}", f.parts);
        assert!(
            f.parts
                .iter()
                .all(|(lo, hi)| hi[0] <= 10.5 || lo[0] >= 14.5),
            "{:?}",
            f.parts
        );
    }

    #[test]
    fn points_off_the_floor_height_are_not_floor() {
        let mut pts = floor(&[([0.0, 0.0], [4.0, 4.0])], 0.05);
        // A table top 0.75 m up over 4 m x 4 m more.
        pts.extend(
            floor(&[([4.0, 0.0], [8.0, 4.0])], 0.05)
                .into_iter()
                .map(|p| p + Vec3::Z * 0.75),
        );
        let f = floor_footprint(&pts, 0.0, 0.0, &FloorCeilingConfig::default()).expect("floor");
        let (_, hi) = f.extent().expect("extent");
        assert!(hi[0] < 4.2, "{hi:?}");
    }

    #[test]
    fn largest_rectangle_of_a_plus_sign() {
        // 5 x 5, a plus of width 1 (middle row and column) and a 2 x 3 block in a corner.
        let mut m = vec![false; 25];
        for k in 0..5 {
            m[2 * 5 + k] = true;
            m[k * 5 + 2] = true;
        }
        assert_eq!(largest_rectangle(&m, 5, 5), Some((0, 2, 5, 3)));
        assert_eq!(largest_rectangle(&[false; 4], 2, 2), None);
        let closed = erode(&dilate(&m, 5, 5, 1), 5, 5, 1);
        assert!(closed[2 * 5 + 2] && !closed[0]);
    }
}
