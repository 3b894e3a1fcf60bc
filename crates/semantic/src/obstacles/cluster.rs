//! Clusters of unexplained points: an XY occupancy grid per height band, each cell's top, and
//! the connected components of the occupied cells whose tops join (see the `obstacles` module).

use crate::image_frame::{pixel_center, ImageFrame};
use glam::DVec2;
use std::collections::HashSet;

/// The points of one height band bucketed by grid cell (compressed rows), and which cells are
/// occupied by enough of them.
pub(crate) struct BandGrid {
    pub width: usize,
    pub height: usize,
    start: Vec<u32>,
    items: Vec<u32>,
}

impl BandGrid {
    /// Buckets the points `members` (indices into `cells_of`, whose entries are the points'
    /// cells, `u32::MAX` for none) by cell.
    pub fn new(frame: &ImageFrame, members: &[u32], cell_of: &[u32]) -> BandGrid {
        let (width, height) = (frame.width_px as usize, frame.height_px as usize);
        let n = width * height;
        let mut count = vec![0u32; n + 1];
        for &i in members {
            count[cell_of[i as usize] as usize + 1] += 1;
        }
        for k in 0..n {
            count[k + 1] += count[k];
        }
        let mut fill = count.clone();
        let mut items = vec![0u32; members.len()];
        for &i in members {
            let k = cell_of[i as usize] as usize;
            items[fill[k] as usize] = i;
            fill[k] += 1;
        }
        BandGrid {
            width,
            height,
            start: count,
            items,
        }
    }

    /// The points in cell `k`.
    pub fn points(&self, k: usize) -> &[u32] {
        &self.items[self.start[k] as usize..self.start[k + 1] as usize]
    }

    /// How many points cell `k` holds.
    pub fn count(&self, k: usize) -> usize {
        (self.start[k + 1] - self.start[k]) as usize
    }

    /// Per cell, the height of its highest point (`f32::MIN` for an empty cell).
    pub fn tops(&self, z_of: impl Fn(u32) -> f32) -> Vec<f32> {
        (0..self.width * self.height)
            .map(|k| {
                self.points(k)
                    .iter()
                    .map(|&i| z_of(i))
                    .fold(f32::MIN, f32::max)
            })
            .collect()
    }
}

/// The centres (map frame) of the grid cells `cells` (indices into `frame`'s grid, row-major).
pub(super) fn cell_centres(cells: &[usize], frame: &ImageFrame) -> Vec<DVec2> {
    let w = frame.width_px as usize;
    cells
        .iter()
        .map(|&k| pixel_center(frame, (k % w) as f64, (k / w) as f64))
        .collect()
}

/// The grid cells (indices, row-major, `width` wide) up to two cells from cell `k` along
/// either axis, `k` itself included: the cells that join `k`'s cluster. (Rows past the grid's
/// end are the caller's to ignore: they are looked up, never indexed.)
pub(super) fn within_two_cells(k: usize, width: usize) -> impl Iterator<Item = usize> {
    let (x, y) = ((k % width) as isize, (k / width) as isize);
    (-2..=2isize).flat_map(move |dy| {
        (-2..=2isize).filter_map(move |dx| {
            let (nx, ny) = (x + dx, y + dy);
            (nx >= 0 && ny >= 0 && nx < width as isize).then(|| ny as usize * width + nx as usize)
        })
    })
}

/// `values` counted in slices `cell_m` wide, the first centred on the smallest: that smallest
/// value and the counts; `None` for no values.
pub(super) fn slice_counts(values: &[f64], cell_m: f64) -> Option<(f64, Vec<usize>)> {
    slice_sums(values, |_| 1, cell_m)
}

/// [`slice_counts`] with value `i` weighing `weight(i)`: the sums of the weights per slice.
pub(super) fn slice_sums(
    values: &[f64],
    weight: impl Fn(usize) -> usize,
    cell_m: f64,
) -> Option<(f64, Vec<usize>)> {
    let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if hi < lo {
        return None;
    }
    let n = (((hi - lo) / cell_m).round() as usize + 1).min(1_000_000);
    let mut sum = vec![0usize; n];
    for (i, v) in values.iter().enumerate() {
        sum[(((v - lo) / cell_m).round() as usize).min(n - 1)] += weight(i);
    }
    Some((lo, sum))
}

/// The connected components of the cells for which `occupied` holds, each a list of cell
/// indices (row-major). Cells up to `reach` cells apart (Chebyshev) are connected, so that the
/// gaps a sparse scan leaves in one surface do not split it, if `joins` holds for them (the
/// first argument is the cell reached from).
pub(crate) fn components(
    width: usize,
    height: usize,
    reach: usize,
    occupied: impl Fn(usize) -> bool,
    joins: impl Fn(usize, usize) -> bool,
) -> Vec<Vec<usize>> {
    let mut seen = vec![false; width * height];
    let mut out = Vec::new();
    let r = reach.max(1) as isize;
    for first in 0..width * height {
        if seen[first] || !occupied(first) {
            continue;
        }
        seen[first] = true;
        let mut stack = vec![first];
        let mut cells = Vec::new();
        while let Some(k) = stack.pop() {
            cells.push(k);
            let (x, y) = ((k % width) as isize, (k / width) as isize);
            for dy in -r..=r {
                for dx in -r..=r {
                    let (nx, ny) = (x + dx, y + dy);
                    if nx < 0 || ny < 0 || nx >= width as isize || ny >= height as isize {
                        continue;
                    }
                    let n = ny as usize * width + nx as usize;
                    if !seen[n] && occupied(n) && joins(k, n) {
                        seen[n] = true;
                        stack.push(n);
                    }
                }
            }
        }
        out.push(cells);
    }
    out
}

/// The connected components (cells up to `reach` apart) of `cells`, a non-empty set of cells of
/// a grid `width` wide.
pub(super) fn components_of(cells: &[usize], width: usize, reach: usize) -> Vec<Vec<usize>> {
    let member: HashSet<usize> = cells.iter().copied().collect();
    // Over the bounding rows and columns only, so that a small cluster costs little.
    let (c0, c1) = cells.iter().fold((usize::MAX, 0), |(a, b), &k| {
        (a.min(k % width), b.max(k % width))
    });
    let r0 = cells.iter().map(|&k| k / width).min().unwrap_or(0);
    let r1 = cells.iter().map(|&k| k / width).max().unwrap_or(0);
    let (w, h) = (c1 + 1 - c0, r1 + 1 - r0);
    let to_global = |k: usize| (k / w + r0) * width + k % w + c0;
    components(w, h, reach, |k| member.contains(&to_global(k)), |_, _| true)
        .into_iter()
        .map(|r| r.into_iter().map(to_global).collect())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn components_join_cells_within_reach_only() {
        // Row 0: cells 0, 1 and 3 occupied (a one-cell gap), cell 7 far off.
        let occ = [0usize, 1, 3, 7];
        let one = components(8, 1, 1, |k| occ.contains(&k), |_, _| true);
        assert_eq!(one.len(), 3, "{one:?}");
        let two = components(8, 1, 2, |k| occ.contains(&k), |_, _| true);
        assert_eq!(two.len(), 2, "{two:?}");
        assert_eq!(two[0].len(), 3);
    }

    #[test]
    fn components_split_where_the_join_test_fails() {
        // Cells 0-5 in a row, tops 0.75 (a desk) then 0.45 (a chair's seat) from cell 3 on.
        let top: [f64; 6] = [0.75, 0.75, 0.75, 0.45, 0.45, 0.45];
        let parts = components(6, 1, 2, |_| true, |a, b| (top[a] - top[b]).abs() <= 0.1);
        assert_eq!(parts.len(), 2, "{parts:?}");
        assert!(parts.iter().all(|p| p.len() == 3), "{parts:?}");
    }
}
