//! Where two things of different heights meet, and how long that junction is: a seat, a crate
//! or a cabinet meets its neighbour along its own side, while the parts of one thing meet along
//! its whole width (a car's cabin and its bonnet along the windscreen, a pickup's cab and its
//! bed).
//!
//! Occupied cells join one cluster only where their tops differ by at most `max_top_step_m`
//! (see the `obstacles` module), so a thing whose parts step by more than that, with no returns
//! between them climbing from the one to the other (a boxy cabin over a body, seen from below
//! its roof), is two clusters side by side or more. Clusters meeting along a thing's width are
//! one thing ([`join_meeting`]); the parts of a cluster found at different levels stay together
//! where they meet along more than a thing's side ([`MAX_JUNCTION_M`], [`super::levels`]).

use super::cluster::{cell_centres, within_two_cells};
use super::fit::{convex_hull, min_area_rect};
use crate::image_frame::ImageFrame;
use std::collections::{HashMap, HashSet};

/// Two regions at different levels meeting along at most this are two things: a seat, a crate
/// or a cabinet meets its neighbour along its own side (0.35-0.6 m, a cell more for the grid),
/// while the parts of one thing meet along its width (a car's, 1.6 m or more).
pub(super) const MAX_JUNCTION_M: f64 = 0.8;

/// Clusters the tops' step kept apart are one thing where they meet along at least this: no
/// returns climb between them, so the junction must be a thing's width, not merely longer than
/// a seat's side. A car's cabin meets its bonnet along 1.6-1.9 m; a chair's seat seen as its
/// front edge, 0.4 m before a desk's cluster that took in its backrest, meets that cluster
/// along 0.8 m (the office-43 part of `tops`' tests).
const MIN_APART_JUNCTION_M: f64 = 1.2;

/// `clusters` (cells, indices into `frame`'s grid, row-major; disjoint) with those meeting
/// along at least [`MIN_APART_JUNCTION_M`] joined, in turn (the parts of one thing: see the
/// module docs); cells up to two apart meet.
pub(super) fn join_meeting(clusters: Vec<Vec<usize>>, frame: &ImageFrame) -> Vec<Vec<usize>> {
    let width = frame.width_px as usize;
    let cell_m = frame.resolution_m;
    // Only clusters spanning more than a junction can meet along one.
    let long_enough = |c: &[usize]| {
        let (mut x0, mut x1, mut y0, mut y1) = (usize::MAX, 0, usize::MAX, 0);
        for &k in c {
            (x0, x1) = (x0.min(k % width), x1.max(k % width));
            (y0, y1) = (y0.min(k / width), y1.max(k / width));
        }
        let (dx, dy) = ((x1 - x0 + 1) as f64, (y1 - y0 + 1) as f64);
        (dx * dx + dy * dy).sqrt() * cell_m >= MIN_APART_JUNCTION_M - cell_m
    };
    let mut label: HashMap<usize, usize> = HashMap::new();
    for (n, c) in clusters.iter().enumerate() {
        if c.len() > 1 && long_enough(c) {
            label.extend(c.iter().map(|&k| (k, n)));
        }
    }
    // 1. The pairs of clusters with cells up to two apart.
    let mut pairs: HashSet<(usize, usize)> = HashSet::new();
    for (&k, &a) in &label {
        for j in within_two_cells(k, width) {
            if let Some(&b) = label.get(&j) {
                if a < b {
                    pairs.insert((a, b));
                }
            }
        }
    }
    let mut pairs: Vec<(usize, usize)> = pairs.into_iter().collect();
    pairs.sort_unstable();
    // 2. Those meeting along a thing's width are one.
    let mut parent: Vec<usize> = (0..clusters.len()).collect();
    for (a, b) in pairs {
        let cells: Vec<usize> = clusters[a].iter().chain(&clusters[b]).copied().collect();
        let region: Vec<usize> = clusters[a]
            .iter()
            .map(|_| 0)
            .chain(clusters[b].iter().map(|_| 1))
            .collect();
        if junction(&cells, &region, 0, 1, frame)
            .is_some_and(|len| len + 1e-9 >= MIN_APART_JUNCTION_M)
        {
            let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
            parent[ra] = rb;
        }
    }
    let mut groups: Vec<Vec<usize>> = vec![Vec::new(); clusters.len()];
    for (n, c) in clusters.into_iter().enumerate() {
        let r = find(&mut parent, n);
        groups[r].extend(c);
    }
    groups.retain(|g| !g.is_empty());
    groups
}

/// The length along which regions `a` and `b` meet: on each side, the longer side of the
/// rectangle around its cells within two cells of the other region (plus a cell), and of the two
/// sides the shorter (each side's reach runs two cells past the other's ends); `None` where they
/// do not meet. Cells up to two apart join one cluster, so two regions running side by side two
/// cells apart (a car's side face and its cabin) meet along their whole length.
pub(super) fn junction(
    cells: &[usize],
    region: &[usize],
    a: usize,
    b: usize,
    frame: &ImageFrame,
) -> Option<f64> {
    let width = frame.width_px as usize;
    let of: HashMap<usize, usize> = cells
        .iter()
        .zip(region)
        .filter(|(_, &r)| r == a || r == b)
        .map(|(&k, &r)| (k, r))
        .collect();
    let near_other = |k: usize, r: usize| {
        within_two_cells(k, width).any(|j| of.get(&j).is_some_and(|&o| o != r))
    };
    let side = |r: usize| -> Option<f64> {
        let meets: Vec<usize> = of
            .iter()
            .filter(|(&k, &o)| o == r && near_other(k, o))
            .map(|(&k, _)| k)
            .collect();
        let (_, _, size) = min_area_rect(&convex_hull(&cell_centres(&meets, frame)), &[], &[])?;
        Some(size[0] + frame.resolution_m)
    };
    Some(side(a)?.min(side(b)?))
}

/// The root of `i`'s set (union-find, halving the path).
pub(super) fn find(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image_frame::pixel_center;
    use crate::obstacles::{components, test_grid};
    use glam::DVec2;

    /// The clusters of the grid's cells where `top` gives a height, cells up to two apart
    /// joined where their tops differ by at most 0.1 m (as the stage clusters them), then
    /// joined where they meet.
    fn clusters(top: impl Fn(DVec2) -> Option<f32>) -> (Vec<Vec<usize>>, Vec<Vec<usize>>) {
        let frame = test_grid();
        let w = frame.width_px as usize;
        let tops: Vec<f32> = (0..w * frame.height_px as usize)
            .map(|k| top(pixel_center(&frame, (k % w) as f64, (k / w) as f64)).unwrap_or(f32::MIN))
            .collect();
        let step = |a: usize, b: usize| (tops[a] - tops[b]).abs() <= 0.1;
        let found = components(w, frame.height_px as usize, 2, |k| tops[k] > 0.0, step);
        (found.clone(), join_meeting(found, &frame))
    }

    /// Regression (garage-6 of seeds 1-10: 11 of its 18 cars were reported as two boxes or
    /// more): a boxy cabin over a car's body steps 0.44 m with no return between, so the two
    /// are clusters of their own; they meet along the car's width.
    #[test]
    fn a_cars_cabin_and_bonnet_clustered_apart_are_one_thing() {
        let (before, after) = clusters(crate::obstacles::test_car_top);
        assert_eq!(
            before.len(),
            3,
            "the cabin and the two ends clustered apart"
        );
        assert_eq!(after.len(), 1);
        assert_eq!(after[0].len(), 44 * 18);
    }

    #[test]
    fn a_seat_beside_a_desk_meeting_along_its_side_stays_apart() {
        // A desk 1.4 x 0.7 m (top 0.76) and a seat 0.5 m square (0.45) against its long side,
        // and a cabinet 1.1 x 0.4 m (1.9) 0.1 m off the desk's short side.
        let (before, after) = clusters(|p| {
            if p.x > 2.0 && p.x < 3.4 && p.y > 2.0 && p.y < 2.7 {
                Some(0.76)
            } else if p.x > 2.5 && p.x < 3.0 && p.y > 1.5 && p.y < 2.0 {
                Some(0.45)
            } else if p.x > 3.5 && p.x < 3.9 && p.y > 1.8 && p.y < 2.9 {
                Some(1.9)
            } else {
                None
            }
        });
        assert_eq!(before.len(), 3);
        let mut sizes: Vec<usize> = after.iter().map(Vec::len).collect();
        sizes.sort_unstable();
        assert_eq!(sizes, vec![25, 44, 98]);
    }
}
