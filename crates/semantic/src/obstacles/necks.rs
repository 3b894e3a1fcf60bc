//! Things side by side, joined by a few cells: two parked cars 0.7 m apart, pillars in a row.
//! The laser's mixed pixels between them (returns along rays grazing one, between it and the
//! other), and the smear of a registration, leave an occupied cell here and there in the gap,
//! and cells up to two apart join, so the two are one cluster. Across the gap, the cluster is
//! a neck: cut into one-cell slices along either axis of its box, the slices in the gap hold a
//! few cells where those through either thing hold many. A cluster is cut at its thinnest such
//! neck with enough of it on both sides to be a thing (`MIN_SIDE_M`), and the parts are cut
//! again; the cells of the neck are left out (stray returns, not a thing). Things seen from
//! below their tops are hollow outlines, whose slices hold as few cells as the gap's: their
//! clusters are then cut where the slices' returns, not their cells, show the gap
//! ([`split_at_gaps_in_returns`]).

use super::cluster::{cell_centres, slice_sums};
use super::fit::{convex_hull, min_area_rect};
use crate::image_frame::ImageFrame;
use glam::DVec2;

/// A slice is a neck if it holds at most this fraction of the cells of the cluster's typical
/// slice (the median) ...
const NECK_SHARE: f64 = 0.25;
/// ... with at least this much of the cluster, in slices fuller than a neck's, on each side
/// (an obstacle the stage scores is over 0.3 m across).
pub(super) const MIN_SIDE_M: f64 = 0.3;
/// Cuts at most this deep (a row of pillars is a few cuts; a cap against pathological input).
const MAX_DEPTH: usize = 8;

/// Two things side by side seen from below their tops (parked cars: hollow outlines, a slice
/// through one holds its two faces' cells, as many as a slice through the gap holds of the
/// mixed pixels strung across it) show the gap in their returns: a face's cell holds dozens, a
/// mixed pixel's one or two. A slice is such a gap if it holds at most this share of the returns
/// of the typical slice (on garage-322 of seeds 321-325, under 0.1) ...
const GAP_RETURNS_SHARE: f64 = 0.1;
/// ... with at least this much on each side, each side a thing a metre across or more (a car is
/// 1.7-2.0 m): a light stretch of a thing's own near one end (a car's far corner seen by a few
/// grazing rays) leaves less than that beyond it.
const GAP_MIN_SIDE_M: f64 = 1.0;
/// ... and the gap this wide at least: parked cars stand apart by what their doors need (0.5 m
/// or more); a light stretch within a car, where its faces were seen thinly, is narrower
/// (garage-195 of seeds 191-195: a car cut in two where its halves abut).
const GAP_MIN_WIDTH_M: f64 = 0.4;

/// `cells` (indices into `frame`'s grid, row-major) cut at their necks (see the module docs).
pub(super) fn split_at_necks(cells: Vec<usize>, frame: &ImageFrame) -> Vec<Vec<usize>> {
    let mut out = Vec::new();
    let by_cells = Necks {
        weight: &|_| 1,
        share: NECK_SHARE,
        min_side_m: MIN_SIDE_M,
        min_width_m: 0.0,
    };
    split(cells, frame, &by_cells, 0, &mut out);
    out
}

/// How slices are weighed and how light a neck is.
pub(super) struct Necks<'a> {
    /// A cell's weight in its slice (1: slices count cells).
    pub weight: &'a dyn Fn(usize) -> usize,
    /// A neck weighs at most this fraction of the median slice.
    pub share: f64,
    /// ... with at least this much of the cluster, in slices heavier than a neck's, on each side.
    pub min_side_m: f64,
    /// ... and its run of light slices this wide at least.
    pub min_width_m: f64,
}

/// `cells` cut where their slices hold at most [`GAP_RETURNS_SHARE`] of the returns of the
/// typical slice along [`GAP_MIN_WIDTH_M`] or more, [`GAP_MIN_SIDE_M`] of the cluster on each
/// side (`returns`: a cell's returns):
/// two things side by side joined by mixed pixels across the gap.
pub(super) fn split_at_gaps_in_returns(
    cells: Vec<usize>,
    frame: &ImageFrame,
    returns: &dyn Fn(usize) -> usize,
) -> Vec<Vec<usize>> {
    let by_returns = Necks {
        weight: returns,
        share: GAP_RETURNS_SHARE,
        min_side_m: GAP_MIN_SIDE_M,
        min_width_m: GAP_MIN_WIDTH_M,
    };
    split_at_weighed_necks(cells, frame, &by_returns)
}

/// `cells` cut where their slices, weighed as `necks` says, are necks (see the module docs).
pub(super) fn split_at_weighed_necks(
    cells: Vec<usize>,
    frame: &ImageFrame,
    necks: &Necks,
) -> Vec<Vec<usize>> {
    let mut out = Vec::new();
    split(cells, frame, necks, 0, &mut out);
    out
}

fn split(
    cells: Vec<usize>,
    frame: &ImageFrame,
    necks: &Necks,
    depth: usize,
    out: &mut Vec<Vec<usize>>,
) {
    let pts = cell_centres(&cells, frame);
    let weights: Vec<usize> = cells.iter().map(|&k| (necks.weight)(k)).collect();
    let axes = min_area_rect(&convex_hull(&pts), &[], &[]).map(|(_, d, _)| [d, d.perp()]);
    let cut = match axes {
        Some(axes) if depth < MAX_DEPTH => axes
            .iter()
            .filter_map(|&d| neck(&pts, &weights, d, frame.resolution_m, necks))
            .min_by(|a, b| a.0.total_cmp(&b.0)),
        _ => None,
    };
    let Some((_, d, from, to)) = cut else {
        out.push(cells);
        return;
    };
    let (mut below, mut above) = (Vec::new(), Vec::new());
    for (&k, p) in cells.iter().zip(&pts) {
        let s = p.dot(d);
        if s < from {
            below.push(k);
        } else if s > to {
            above.push(k);
        }
    }
    split(below, frame, necks, depth + 1, out);
    split(above, frame, necks, depth + 1, out);
}

/// The thinnest neck of the cells at `pts` (weighing `weights`) across direction `d`: (its
/// share of the median slice, `d`, and the span along `d` it covers); `None` if there is none.
fn neck(
    pts: &[DVec2],
    weights: &[usize],
    d: DVec2,
    cell_m: f64,
    necks: &Necks,
) -> Option<(f64, DVec2, f64, f64)> {
    let share = necks.share;
    let s: Vec<f64> = pts.iter().map(|p| p.dot(d)).collect();
    let (lo, count) = slice_sums(&s, |i| weights[i], cell_m)?;
    let n = count.len();
    let mut full: Vec<usize> = count.iter().copied().filter(|&c| c > 0).collect();
    full.sort_unstable();
    let median = *full.get(full.len() / 2)? as f64;
    let thin = |i: usize| count[i] as f64 <= share * median;
    let side = (necks.min_side_m / cell_m).round() as usize;
    // Slices fuller than a neck's before each slice, and after it.
    let mut before = vec![0usize; n + 1];
    for i in 0..n {
        before[i + 1] = before[i] + usize::from(!thin(i));
    }
    // The runs of thin slices: each slice's run's first and last slice.
    let mut first = vec![0usize; n];
    for i in 0..n {
        first[i] = if i > 0 && thin(i - 1) {
            first[i - 1]
        } else {
            i
        };
    }
    let mut last = vec![0usize; n];
    for i in (0..n).rev() {
        last[i] = if i + 1 < n && thin(i + 1) {
            last[i + 1]
        } else {
            i
        };
    }
    let wide = |i: usize| (last[i] - first[i] + 1) as f64 * cell_m + 1e-9 >= necks.min_width_m;
    let mut best: Option<(f64, usize)> = None;
    for i in 0..n {
        let after = before[n] - before[i + 1];
        if thin(i) && wide(i) && before[i] >= side && after >= side {
            let share = count[i] as f64 / median;
            if best.is_none_or(|b| share < b.0) {
                best = Some((share, i));
            }
        }
    }
    let (share, i) = best?;
    // The neck: the run of thin slices around the thinnest one.
    let (a, b) = (first[i], last[i]);
    let at = |j: usize| lo + j as f64 * cell_m;
    Some((share, d, at(a) - cell_m / 2.0, at(b) + cell_m / 2.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image_frame::pixel_center;

    /// The cells whose centres `inside` holds.
    fn cells(frame: &ImageFrame, inside: impl Fn(DVec2) -> bool) -> Vec<usize> {
        let w = frame.width_px as usize;
        (0..w * frame.height_px as usize)
            .filter(|&k| inside(pixel_center(frame, (k % w) as f64, (k / w) as f64)))
            .collect()
    }

    #[test]
    fn two_cars_joined_by_a_few_stray_cells_are_cut_apart() {
        let frame = crate::obstacles::test_grid();
        // Two cars 1.8 x 4.5 m, 0.7 m apart along x; a line of stray cells across the gap.
        let car = |p: DVec2, x0: f64| p.x > x0 && p.x < x0 + 1.8 && p.y > 0.5 && p.y < 5.0;
        let stray = |p: DVec2| p.x > 2.8 && p.x < 3.5 && (p.y - 2.05).abs() < 0.05;
        let all = cells(&frame, |p| car(p, 1.0) || car(p, 3.5) || stray(p));
        let parts = split_at_necks(all, &frame);
        assert_eq!(
            parts.len(),
            2,
            "{:?}",
            parts.iter().map(Vec::len).collect::<Vec<_>>()
        );
        assert!(
            parts.iter().all(|p| p.len() == 18 * 45),
            "{:?}",
            parts.iter().map(Vec::len).collect::<Vec<_>>()
        );
    }

    #[test]
    fn a_table_with_a_chair_at_its_side_or_an_l_shaped_desk_stays_whole() {
        let frame = crate::obstacles::test_grid();
        // A 1.4 x 0.8 m table with a 0.45 m chair against its long side.
        let table = |p: DVec2| p.x > 2.0 && p.x < 3.4 && p.y > 2.0 && p.y < 2.8;
        let chair = |p: DVec2| p.x > 2.5 && p.x < 2.95 && p.y > 1.55 && p.y <= 2.0;
        assert_eq!(
            split_at_necks(cells(&frame, |p| table(p) || chair(p)), &frame).len(),
            1
        );
        // An L: 2 x 0.8 m and 0.8 x 1.6 m.
        let l = |p: DVec2| {
            (p.x > 2.0 && p.x < 4.0 && p.y > 2.0 && p.y < 2.8)
                || (p.x > 2.0 && p.x < 2.8 && p.y > 2.8 && p.y < 4.4)
        };
        assert_eq!(split_at_necks(cells(&frame, l), &frame).len(), 1);
    }

    /// Regression (garage-322 of seeds 321-325): two cars 0.8 m apart, seen from below their
    /// tops (hollow outlines: their faces' cells, dozens of returns each), joined by mixed
    /// pixels strung across the gap along a metre (a return or two a cell). Counting cells, a
    /// slice through the gap is as full as one through a car; counting returns, it is a gap. A
    /// desk seen by its four legs (many returns) and its top's underside (one a cell) stays
    /// whole: most of its slices are the top's, so the typical slice is light too; so does one
    /// car seen thinly along a stretch narrower than a gap between parked cars.
    #[test]
    fn two_hollow_cars_joined_by_mixed_pixels_are_cut_at_the_gap_and_one_car_or_a_desk_is_not() {
        let frame = crate::obstacles::test_grid();
        let w = frame.width_px as usize;
        let centre = |k: usize| pixel_center(&frame, (k % w) as f64, (k / w) as f64);
        // Outlines 1.8 x 4.4 m, a cell thick, from x = 1.0 and x = 3.6; strays across the gap.
        let outline = |p: DVec2, x0: f64| {
            let inside =
                |m: f64| p.x > x0 + m && p.x < x0 + 1.8 - m && p.y > 0.5 + m && p.y < 4.9 - m;
            inside(0.0) && !inside(0.1)
        };
        let stray = |p: DVec2| {
            p.x > 2.8 && p.x < 3.6 && p.y > 0.6 && p.y < 1.6 && (p.y * 10.0) as i64 % 2 == 0
        };
        let returns = |k: usize| {
            let p = centre(k);
            if outline(p, 1.0) || outline(p, 3.6) {
                40
            } else if stray(p) {
                1
            } else {
                0
            }
        };
        let all = cells(&frame, |p| outline(p, 1.0) || outline(p, 3.6) || stray(p));
        // (the cells alone show no neck)
        assert_eq!(split_at_necks(all.clone(), &frame).len(), 1);
        let parts = split_at_gaps_in_returns(all, &frame, &returns);
        assert_eq!(
            parts.len(),
            2,
            "{:?}",
            parts.iter().map(Vec::len).collect::<Vec<_>>()
        );
        for part in &parts {
            let xs: Vec<f64> = part.iter().map(|&k| centre(k).x).collect();
            let span = xs.iter().copied().fold(f64::MIN, f64::max)
                - xs.iter().copied().fold(f64::MAX, f64::min);
            assert!(span < 1.85, "a part {span} m across");
        }
        // One car whose faces were seen thinly along 0.2 m of its middle: narrower than a gap
        // between parked cars, not cut (garage-195 of seeds 191-195).
        let thin_middle = |k: usize| {
            let p = centre(k);
            if (p.y - 2.7).abs() < 0.1 {
                1
            } else {
                40
            }
        };
        let car = cells(&frame, |p| outline(p, 1.0));
        assert_eq!(split_at_gaps_in_returns(car, &frame, &thin_middle).len(), 1);
        // A desk 1.6 x 0.8 m: legs at its corners, its top's underside between them.
        let desk = |p: DVec2| p.x > 2.0 && p.x < 3.6 && p.y > 2.0 && p.y < 2.8;
        let leg = |p: DVec2| (p.x < 2.1 || p.x > 3.5) && (p.y < 2.1 || p.y > 2.7);
        let desk_returns = |k: usize| if leg(centre(k)) { 60 } else { 1 };
        let desk_cells = cells(&frame, desk);
        assert_eq!(
            split_at_gaps_in_returns(desk_cells, &frame, &desk_returns).len(),
            1
        );
    }
}
