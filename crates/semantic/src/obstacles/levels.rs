//! Things of different heights side by side, joined through the cells between them: a chair's
//! seat (0.45 m) beside a desk (0.75 m), two cabinets of 1.8 and 1.9 m against one wall. Their
//! tops step by more than `max_top_step_m`, but the laser's mixed pixels in the gap between
//! them (returns between the one and the other) leave cells whose tops climb from one to the
//! other by small steps, so the cluster takes both.
//!
//! Within a cluster, a level is a height that many cells' tops share (within half a step);
//! its core is a region of such cells as large as a thing the stage scores (patches under a
//! seat's width apart are one region: a surface seen from afar is seen in patches). Every
//! other cell goes to the nearest core (through the cluster's cells), and two regions whose
//! levels differ by more than a step stay apart where they meet along a short junction, no
//! longer than one thing's side ([`MAX_JUNCTION_M`]). The parts of one thing meet along its whole
//! width: a car's cabin (1.4 m) and its bonnet (1.0 m) along the windscreen, 1.6 m and more.

use super::cluster::{components_of, within_two_cells};
use super::junctions::{find, junction, MAX_JUNCTION_M};
use super::min_surface_cells;
use crate::image_frame::ImageFrame;
use std::collections::{HashMap, VecDeque};

/// Levels are found in a histogram of the cells' tops with bins this tall (the laser's range
/// noise is 1-3 cm).
const BIN_M: f64 = 0.02;
/// At most this many levels per cluster (a cap against pathological input).
const MAX_LEVELS: usize = 16;
/// A level's cells this far apart still make one core: a seat or a crate's top seen from afar
/// is patches of returns (grazing rays, its backrest's shadow) with empty cells between them,
/// which are no gap between things (under a seat's 0.45 m).
const CORE_REACH_M: f64 = 0.4;

/// `cells` (indices into `frame`'s grid, row-major) split into things of different heights
/// (see the module docs); `tops` holds every grid cell's top, `step` the largest step of a
/// top within one thing.
pub(super) fn split_levels(
    cells: Vec<usize>,
    tops: &[f32],
    frame: &ImageFrame,
    step: f64,
) -> Vec<Vec<usize>> {
    let cell_m = frame.resolution_m;
    let min_core = min_surface_cells(cell_m);
    if cells.len() < 2 * min_core {
        return vec![cells];
    }
    let top = |k: usize| tops[k] as f64;
    // 1. The levels and their cores.
    let reach = ((CORE_REACH_M / cell_m).round() as usize).max(2);
    let cores = cores(&cells, top, frame.width_px as usize, step, min_core, reach);
    if cores.len() < 2 {
        return vec![cells];
    }
    // 2. Every cell to its nearest core.
    let region = nearest_core(&cells, &cores, frame.width_px as usize);
    // 3. Regions joined where their levels are within a step, or where they meet along more
    //    than one thing's side.
    let mut parent: Vec<usize> = (0..cores.len()).collect();
    for a in 0..cores.len() {
        for b in a + 1..cores.len() {
            let apart = (cores[a].0 - cores[b].0).abs() > step;
            let junction = junction(&cells, &region, a, b, frame);
            let joined = match junction {
                None => false,
                Some(len) => !apart || len > MAX_JUNCTION_M,
            };
            if joined {
                let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
                parent[ra] = rb;
            }
        }
    }
    let mut groups: HashMap<usize, Vec<usize>> = HashMap::new();
    for (&k, &r) in cells.iter().zip(&region) {
        groups.entry(find(&mut parent, r)).or_default().push(k);
    }
    let mut out: Vec<Vec<usize>> = groups.into_values().collect();
    out.sort_by_key(|g| g[0]);
    out
}

/// The levels of the cells' tops and their cores: (level, the core's cells), each core a
/// region of at least `min_core` cells whose tops lie within half a step of its level, each
/// within `reach` cells of another.
fn cores(
    cells: &[usize],
    top: impl Fn(usize) -> f64,
    width: usize,
    step: f64,
    min_core: usize,
    reach: usize,
) -> Vec<(f64, Vec<usize>)> {
    let half = step / 2.0;
    let mut free: Vec<usize> = cells.to_vec();
    let mut out = Vec::new();
    for _ in 0..MAX_LEVELS {
        // The bin whose window of +-half a step holds most of the cells not yet on a level.
        let mut zs: Vec<f64> = free.iter().map(|&k| top(k)).collect();
        zs.sort_by(f64::total_cmp);
        let (Some(&lo), Some(&hi)) = (zs.first(), zs.last()) else {
            break;
        };
        let bins = (((hi - lo) / BIN_M).ceil() as usize + 1).min(100_000);
        let (mut best, mut best_count) = (lo, 0usize);
        for b in 0..bins {
            let z = lo + b as f64 * BIN_M;
            let a = zs.partition_point(|&v| v < z - half);
            let c = zs.partition_point(|&v| v <= z + half) - a;
            if c > best_count {
                (best, best_count) = (z, c);
            }
        }
        if best_count < min_core {
            break;
        }
        let on: Vec<usize> = free
            .iter()
            .copied()
            .filter(|&k| (top(k) - best).abs() <= half)
            .collect();
        free.retain(|&k| (top(k) - best).abs() > half);
        // Its cores: the regions of those cells large enough to be a thing.
        let regions = components_of(&on, width, reach);
        out.extend(
            regions
                .into_iter()
                .filter(|r| r.len() >= min_core)
                .map(|r| (best, r)),
        );
    }
    out
}

/// For each of `cells`, the index of the core it is nearest to through the cells (breadth
/// first, cells up to two apart connected).
fn nearest_core(cells: &[usize], cores: &[(f64, Vec<usize>)], width: usize) -> Vec<usize> {
    let pos: HashMap<usize, usize> = cells.iter().enumerate().map(|(i, &k)| (k, i)).collect();
    let mut region = vec![usize::MAX; cells.len()];
    let mut queue = VecDeque::new();
    for (r, (_, core)) in cores.iter().enumerate() {
        for k in core {
            if let Some(&i) = pos.get(k) {
                region[i] = r;
                queue.push_back(i);
            }
        }
    }
    while let Some(i) = queue.pop_front() {
        for n in within_two_cells(cells[i], width) {
            if let Some(&j) = pos.get(&n) {
                if region[j] == usize::MAX {
                    region[j] = region[i];
                    queue.push_back(j);
                }
            }
        }
    }
    // (cells no core reaches cannot exist: the cluster is connected; kept with the first)
    region
        .iter()
        .map(|&r| if r == usize::MAX { 0 } else { r })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image_frame::pixel_center;
    use glam::DVec2;

    /// The grid's cells where `top` gives a height, and every cell's top.
    fn scene(frame: &ImageFrame, top: impl Fn(DVec2) -> Option<f32>) -> (Vec<usize>, Vec<f32>) {
        let w = frame.width_px as usize;
        let mut tops = vec![f32::MIN; w * frame.height_px as usize];
        let mut cells = Vec::new();
        for (k, t) in tops.iter_mut().enumerate() {
            if let Some(z) = top(pixel_center(frame, (k % w) as f64, (k / w) as f64)) {
                *t = z;
                cells.push(k);
            }
        }
        (cells, tops)
    }

    /// The y of cell `k`'s centre.
    fn row_y(frame: &ImageFrame, k: usize) -> f64 {
        pixel_center(frame, 0.0, (k / frame.width_px as usize) as f64).y
    }

    /// `cells` split in two (asserted, with a step of 0.1 m); the part holding a cell `in_seat`.
    fn seat_split_off(
        cells: Vec<usize>,
        tops: &[f32],
        frame: &ImageFrame,
        in_seat: impl Fn(usize) -> bool,
    ) -> Vec<usize> {
        let parts = split_levels(cells, tops, frame, 0.1);
        assert_eq!(
            parts.len(),
            2,
            "{:?}",
            parts.iter().map(Vec::len).collect::<Vec<_>>()
        );
        parts
            .into_iter()
            .find(|p| p.iter().any(|&k| in_seat(k)))
            .expect("seat")
    }

    #[test]
    fn a_seat_joined_to_a_desk_by_mixed_pixels_is_split_off() {
        let frame = crate::obstacles::test_grid();
        // A desk 1.4 x 0.8 m (top 0.76) and a seat 0.45 m square (0.5) 0.1 m off its long
        // side, with a row of cells between them climbing from the seat to the desk.
        let (cells, tops) = scene(&frame, |p| {
            if p.x > 2.0 && p.x < 3.4 && p.y > 2.0 && p.y < 2.8 {
                Some(0.76)
            } else if p.x > 2.5 && p.x < 2.95 && p.y > 1.45 && p.y < 1.9 {
                Some(0.5)
            } else if (p.y - 1.95).abs() < 0.05 && p.x > 2.5 && p.x < 2.95 {
                Some(0.5 + (p.x as f32 - 2.5) * 0.6)
            } else {
                None
            }
        });
        let y = |k: usize| row_y(&frame, k);
        // The seat's part holds the seat's 20 cells and none of the desk's.
        let seat = seat_split_off(cells, &tops, &frame, |k| y(k) < 1.9);
        assert_eq!(seat.iter().filter(|&&k| y(k) < 1.9).count(), 20, "{seat:?}");
        assert!(seat.iter().all(|&k| y(k) < 2.0), "{seat:?}");
    }

    /// Regression (office-34 of seeds 31-35: a chair at a desk went into the desk's box): the
    /// seat seen from afar is two patches of returns 0.4 m apart with lower returns (its legs)
    /// between them, neither patch a thing's surface on its own.
    #[test]
    fn a_seat_seen_in_patches_beside_a_desk_is_split_off() {
        let frame = crate::obstacles::test_grid();
        let (cells, tops) = scene(&frame, |p| {
            let (x, y) = (p.x, p.y);
            if x > 2.0 && x < 3.5 && y > 2.0 && y < 2.8 {
                // The desk: its top, 0.8 m deep.
                Some(0.62)
            } else if y > 2.9 && y < 3.1 && (x > 2.2 && x < 2.4 || x > 2.6 && x < 2.8) {
                // The seat's two patches, 2 x 2 cells each, 0.4 m apart (centres).
                Some(0.36)
            } else if y > 2.9 && y < 3.1 && x > 2.4 && x < 2.6 {
                // Between them, returns off its legs.
                Some(0.2)
            } else if (x - 2.15).abs() < 0.05 && y > 2.8 && y < 2.9 {
                // Mixed pixels climbing from the seat to the desk at one end.
                Some(0.49)
            } else {
                None
            }
        });
        let y = |k: usize| row_y(&frame, k);
        let seat = seat_split_off(cells, &tops, &frame, |k| y(k) > 2.9);
        assert!(seat.iter().all(|&k| y(k) > 2.8), "{seat:?}");
    }

    #[test]
    fn a_car_whose_cabin_meets_its_bonnet_along_its_width_stays_whole() {
        let frame = crate::obstacles::test_grid();
        let (cells, tops) = scene(&frame, crate::obstacles::test_car_top);
        let n = cells.len();
        let parts = split_levels(cells, &tops, &frame, 0.1);
        assert_eq!(
            parts.len(),
            1,
            "{:?}",
            parts.iter().map(Vec::len).collect::<Vec<_>>()
        );
        assert_eq!(parts[0].len(), n);
    }
}
