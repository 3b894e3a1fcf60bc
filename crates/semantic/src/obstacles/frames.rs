//! Frames of overhead members: the beams of a car park's ceiling, the ducts and pipes under
//! them. Where they cross, their cells touch, and the laser's mixed pixels between a duct and
//! the beam above it step the cells' tops from one to the other by less than a surface's
//! step; so the whole frame is one cluster, and its box a slab under the whole ceiling. A
//! frame's cells fill little of its box and lie on a few lines: along each of the box's two
//! axes, the lines across which the cells run for at least half of the frame's extent are its
//! members. Each cell goes to the member it lies on; where two members cross, to the one whose
//! other cells stand higher (a duct passes under a beam: the crossing cells' tops are the
//! beam's); the duct's pieces between beams are joined again along their line afterwards (as
//! any duct that a beam cuts, see `merge`). Cells on no member stay together (a lamp).

use super::cluster::{cell_centres, components, slice_counts};
use crate::image_frame::ImageFrame;
use glam::DVec2;

/// A cluster is looked at as a frame only if its cells fill at most this fraction of its box
/// (a beam, a duct, a slab fill most of theirs) ...
pub(super) const MAX_FRAME_FILL: f64 = 0.5;
/// ... and it is at least this wide across (a member is narrower than a metre: beams and
/// ducts are 0.1-0.8 m across).
pub(super) const MIN_FRAME_ACROSS_M: f64 = 2.0;
/// A line is a member if its cells run along at least this fraction of the frame's extent.
const MIN_MEMBER_SHARE: f64 = 0.5;
/// A member is at most this wide (wider bands of cells are a slab, not a member).
const MAX_MEMBER_WIDTH_M: f64 = 1.5;

/// The cells `cells` (indices into `frame`'s grid, row-major) split into the members of a frame
/// whose box's first axis is `dir` (see the module docs), each member's pieces apart, and the
/// cells on no member; `None` if the cells show fewer than two members.
pub(super) fn split_frame(
    cells: &[usize],
    dir: DVec2,
    tops: &[f32],
    frame: &ImageFrame,
) -> Option<Vec<Vec<usize>>> {
    let w = frame.width_px as usize;
    let cell_m = frame.resolution_m;
    let centres = cell_centres(cells, frame);
    // 1. The members along each axis: runs of 1-cell lines across it holding cells along at
    //    least half of the extent along it.
    let mut bands: Vec<(usize, f64, f64)> = Vec::new(); // (axis, from, to) across the axis
    for (axis, d) in [dir, dir.perp()].into_iter().enumerate() {
        let along: Vec<f64> = centres.iter().map(|p| p.dot(d)).collect();
        let across: Vec<f64> = centres.iter().map(|p| p.perp_dot(d)).collect();
        let (Some((_, along_slices)), Some((lo, count))) =
            (slice_counts(&along, cell_m), slice_counts(&across, cell_m))
        else {
            return None;
        };
        let extent = along_slices.len() as f64 * cell_m;
        let n = count.len();
        let full = |i: usize| count[i] as f64 * cell_m >= MIN_MEMBER_SHARE * extent;
        let mut i = 0;
        while i < n {
            if !full(i) {
                i += 1;
                continue;
            }
            let start = i;
            // (one thinner line inside a member does not split it)
            while i < n && (full(i) || (i + 1 < n && full(i + 1))) {
                i += 1;
            }
            let (from, to) = (
                lo + (start as f64 - 0.5) * cell_m,
                lo + (i as f64 - 0.5) * cell_m,
            );
            if to - from <= MAX_MEMBER_WIDTH_M {
                bands.push((axis, from, to));
            }
        }
    }
    if bands.len() < 2 {
        return None;
    }
    // 2. The bands each cell lies on.
    let on = |p: DVec2| -> Vec<usize> {
        (0..bands.len())
            .filter(|&b| {
                let (axis, from, to) = bands[b];
                let d = if axis == 0 { dir } else { dir.perp() };
                (from..=to).contains(&p.perp_dot(d))
            })
            .collect()
    };
    let on_cells: Vec<Vec<usize>> = centres.iter().map(|&p| on(p)).collect();
    // 3. Each member's height: the median top of its cells on no other member.
    let height: Vec<f32> = (0..bands.len())
        .map(|b| {
            let mut t: Vec<f32> = cells
                .iter()
                .zip(&on_cells)
                .filter(|(_, o)| o.len() == 1 && o[0] == b)
                .map(|(&k, _)| tops[k])
                .collect();
            t.sort_by(f32::total_cmp);
            t.get(t.len() / 2).copied().unwrap_or(f32::MIN)
        })
        .collect();
    // 4. The cells to their members (the highest where members cross), the rest together.
    let mut groups: Vec<Vec<usize>> = vec![Vec::new(); bands.len() + 1];
    for (&k, o) in cells.iter().zip(&on_cells) {
        let g = o
            .iter()
            .copied()
            .max_by(|&a, &b| height[a].total_cmp(&height[b]))
            .unwrap_or(bands.len());
        groups[g].push(k);
    }
    // 5. Each group's pieces apart (a duct between beams, a member with a gap).
    let h = frame.height_px as usize;
    let mut out = Vec::new();
    for g in groups.into_iter().filter(|g| !g.is_empty()) {
        let mut mark = vec![false; w * h];
        for &k in &g {
            mark[k] = true;
        }
        out.extend(components(w, h, 2, |k| mark[k], |_, _| true));
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image_frame::pixel_center;

    /// Beams along y at x = 1, 4, 7 (0.4 m wide, tops 2.8 m),
    /// a duct along x at y = 3 (0.5 m wide, top 2.5 m) passing under them.
    #[test]
    fn beams_and_a_duct_under_them_are_split_into_their_members() {
        let frame = crate::obstacles::test_grid();
        let w = 100;
        let mut tops = vec![f32::MIN; 100 * 60];
        let mut cells = Vec::new();
        for row in 0..60 {
            for col in 0..100 {
                let p = pixel_center(&frame, col as f64, row as f64);
                let beam = [1.0, 4.0, 7.0].iter().any(|x| (p.x - x).abs() < 0.2);
                let duct = (p.y - 3.0).abs() < 0.25;
                if beam || duct {
                    let k = row * w + col;
                    tops[k] = if beam { 2.8 } else { 2.5 };
                    cells.push(k);
                }
            }
        }
        let groups = split_frame(&cells, DVec2::X, &tops, &frame).expect("a frame");
        // Three beams, and the duct in four pieces (before, between and after the beams).
        assert_eq!(
            groups.len(),
            7,
            "{:?}",
            groups.iter().map(Vec::len).collect::<Vec<_>>()
        );
        let beams = groups
            .iter()
            .filter(|g| g.iter().all(|&k| tops[k] > 2.7))
            .count();
        assert_eq!(beams, 3);
        assert!(groups
            .iter()
            .filter(|g| g.iter().all(|&k| tops[k] > 2.7))
            .all(|g| g.len() == 4 * 60));
    }

    #[test]
    fn a_slab_or_a_single_beam_is_no_frame() {
        let frame = crate::obstacles::test_grid();
        let tops = vec![2.8f32; 100 * 60];
        let beam: Vec<usize> = (0..60)
            .flat_map(|r| (10..14).map(move |c| r * 100 + c))
            .collect();
        assert!(split_frame(&beam, DVec2::Y, &tops, &frame).is_none());
        let slab: Vec<usize> = (0..30)
            .flat_map(|r| (0..30).map(move |c| r * 100 + c))
            .collect();
        assert!(split_frame(&slab, DVec2::X, &tops, &frame).is_none());
    }
}
