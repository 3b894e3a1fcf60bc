//! A cluster's fringe: the specks its two-cell reach strung onto it. Where one thing stands
//! near another (a chair pushed under a desk, a cabinet behind it), the laser's mixed pixels
//! leave returns in the gap between them, a cell or a few here and there. Each lies within two
//! cells of the next, so the clustering (which bridges the gaps a sparse scan leaves in one
//! surface) strings them into a trail from the one thing to the other, and the box around the
//! trail reaches over the neighbour: a desk's box a metre too deep, which then takes in the chair
//! beside it and in the simulated world closes the passage behind it.
//!
//! A surface the laser saw is a piece of touching cells (8-connected) at least
//! [`MIN_SURFACE_M2`](super::MIN_SURFACE_M2) large, or a small piece within the reach of such a piece (a leg under a seat, the
//! half of a seat beyond an unseen row). A small piece that only other small pieces tie to
//! the body is fringe, and not part of the thing. A cluster with no such body (a chair seen as
//! its four legs, a crate seen in specks) is all kept.

use super::cluster::components_of;
use super::min_surface_cells;
use std::collections::HashSet;

/// Pieces within this many cells of a surface are part of its thing (the clustering's reach).
const REACH_CELLS: isize = 2;

/// `cells` (a cluster's cells, indices into a grid `width` wide at `cell_m`) without their
/// fringe (see the module docs); all of them if no piece is as large as a surface or the
/// surfaces hold less than half the cells.
pub(super) fn without_fringe(cells: Vec<usize>, width: usize, cell_m: f64) -> Vec<usize> {
    let min_cells = min_surface_cells(cell_m);
    if cells.len() < 2 * min_cells {
        return cells;
    }
    // 1. The pieces of touching cells, and the surfaces among them.
    let pieces = components_of(&cells, width, 1);
    let (surfaces, small): (Vec<_>, Vec<_>) =
        pieces.into_iter().partition(|p| p.len() >= min_cells);
    let on_surfaces: usize = surfaces.iter().map(Vec::len).sum();
    if small.is_empty() || 2 * on_surfaces < cells.len() {
        return cells;
    }
    // 2. The small pieces within reach of a surface are kept with it.
    let surface: HashSet<usize> = surfaces.iter().flatten().copied().collect();
    let near_surface = |k: usize| {
        let (x, y) = ((k % width) as isize, (k / width) as isize);
        (-REACH_CELLS..=REACH_CELLS).any(|dy| {
            (-REACH_CELLS..=REACH_CELLS).any(|dx| {
                let (nx, ny) = (x + dx, y + dy);
                nx >= 0
                    && ny >= 0
                    && nx < width as isize
                    && surface.contains(&(ny as usize * width + nx as usize))
            })
        })
    };
    let mut kept: Vec<usize> = surfaces.into_iter().flatten().collect();
    for piece in small {
        if piece.iter().any(|&k| near_surface(k)) {
            kept.extend(piece);
        }
    }
    kept.sort_unstable();
    kept
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Cells of a 30-wide grid from (column, row) pairs.
    fn grid(cells: &[(usize, usize)]) -> Vec<usize> {
        cells.iter().map(|&(x, y)| y * 30 + x).collect()
    }

    fn block(x0: usize, x1: usize, y0: usize, y1: usize) -> Vec<(usize, usize)> {
        (y0..=y1)
            .flat_map(|y| (x0..=x1).map(move |x| (x, y)))
            .collect()
    }

    #[test]
    fn a_trail_of_specks_off_a_desk_is_fringe_a_leg_beside_it_is_not() {
        // A desk 1.5 x 0.9 m (10 cm cells), a leg seen one cell off its edge, then specks
        // two cells apart running 0.8 m away from it.
        let mut cells = block(0, 14, 0, 8);
        cells.push((16, 4));
        cells.extend([(5, 10), (6, 12), (6, 13), (7, 15), (8, 17)]);
        let kept = without_fringe(grid(&cells), 30, 0.1);
        assert_eq!(kept.len(), 15 * 9 + 2, "{kept:?}");
        assert!(kept.contains(&(4 * 30 + 16)) && kept.contains(&(10 * 30 + 5)));
        assert!(!kept.contains(&(12 * 30 + 6)) && !kept.contains(&(17 * 30 + 8)));
    }

    #[test]
    fn a_thing_seen_only_in_specks_or_in_two_surfaces_is_kept_whole() {
        // A chair seen as its four legs and a few seat returns: no surface, all kept.
        let legs = grid(&[(0, 0), (4, 0), (0, 4), (4, 4), (2, 2), (2, 1)]);
        assert_eq!(without_fringe(legs.clone(), 30, 0.1), legs);
        // A car's two halves either side of an unseen row, and a speck between them.
        let mut car = block(0, 9, 0, 4);
        car.extend(block(0, 9, 7, 11));
        car.push((3, 5));
        let mut car = grid(&car);
        car.sort_unstable();
        assert_eq!(without_fringe(car.clone(), 30, 0.1), car);
    }
}
