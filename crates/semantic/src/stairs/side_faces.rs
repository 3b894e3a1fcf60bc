//! A flight seen from its side only, joined by clutter into one part with other things (a desk
//! standing in front of its side face, a person's streak of returns across the floor to parked
//! cars), shows no profile: along any direction the clutter's heights mix with its steps'. Its
//! side face is still a straight line of returns in plan, denser than what lies either side of
//! it (a vertical face stacks returns), and square to the walls as the staircase is. Where a
//! part shows no staircase, each such line is tried as a part of its own.

use super::StairsConfig;
use crate::points::window_counts;
use glam::DVec2;

/// Returns within this of a face's line in plan are on it (a side face sampled far away and
/// at grazing angles, by scans registered to each other).
const HALF_WIDTH_M: f64 = 0.075;

/// What lies this far either side of a face's line is compared with it.
const BESIDE_M: f64 = 0.25;

/// A face holds at least this many times the returns of the band beside it on either side.
const DENSER: usize = 2;

/// A gap along a face's line wider than this ends it (a side face's stepped top edge is one
/// line; a laser's sampling of it leaves gaps of a few centimetres).
const GAP_M: f64 = 0.3;

/// The histogram's bin across the lines.
const BIN_M: f64 = 0.01;

/// The most histogram bins across a part (10 km).
const MAX_BINS: usize = 1_000_000;

/// A face holding this share of a part's returns is the part itself, already tried.
const WHOLE_PART: f64 = 0.9;

/// A straight face of a part, in plan: the returns within [`HALF_WIDTH_M`] of the line along
/// `dir` at `across_m` (`dir.perp_dot`), from `along_m.0` to `along_m.1` (`dir.dot`).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Face {
    pub dir: DVec2,
    /// True if `dir` is a wall's direction (or square to one).
    pub on_wall: bool,
    across_m: f64,
    along_m: (f64, f64),
}

impl Face {
    /// The returns of `pts` on the face.
    pub fn select(&self, pts: &[(DVec2, f64)]) -> Vec<(DVec2, f64)> {
        pts.iter()
            .filter(|(q, _)| {
                let s = q.dot(self.dir);
                (self.dir.perp_dot(*q) - self.across_m).abs() <= HALF_WIDTH_M
                    && s >= self.along_m.0
                    && s <= self.along_m.1
            })
            .copied()
            .collect()
    }

    /// How many of the face's candidate directions (itself, then its reverse) are a wall's.
    pub fn walls_cands(&self) -> usize {
        if self.on_wall {
            2
        } else {
            0
        }
    }
}

/// The straight faces of a part's returns `pts` along the candidate directions `cands` (the
/// first `walls_cands` of them the walls'), each direction tried once up to its sign: the lines
/// across which the returns peak, at least twice as dense as either side of them, each split
/// where its returns leave a gap; those long and dense enough to hold `min_steps` steps.
pub(super) fn side_faces(
    pts: &[(DVec2, f64)],
    cands: &[DVec2],
    walls_cands: usize,
    c: &StairsConfig,
) -> Vec<Face> {
    let min_points = 2 * c.min_steps as usize * c.min_step_points;
    let min_length = f64::from(c.min_steps) * c.run_m[0];
    if pts.len() < min_points {
        return Vec::new();
    }
    let mut faces = Vec::new();
    let mut tried: Vec<DVec2> = Vec::new();
    for (k, &dir) in cands.iter().enumerate() {
        let parallel =
            |e: &DVec2| e.angle_to(dir).sin().abs() < c.snap_direction_deg.to_radians().sin();
        if tried.iter().any(parallel) {
            continue;
        }
        tried.push(dir);
        for across_m in dense_lines(pts, dir, min_points) {
            let mut along: Vec<f64> = pts
                .iter()
                .filter(|(q, _)| (dir.perp_dot(*q) - across_m).abs() <= HALF_WIDTH_M)
                .map(|(q, _)| q.dot(dir))
                .collect();
            along.sort_by(f64::total_cmp);
            for run in along.chunk_by(|a, b| b - a <= GAP_M) {
                let (first, last) = (run[0], run[run.len() - 1]);
                if run.len() >= min_points
                    && last - first >= min_length
                    && (run.len() as f64) < WHOLE_PART * pts.len() as f64
                {
                    faces.push(Face {
                        dir,
                        on_wall: k < walls_cands,
                        across_m,
                        along_m: (first, last),
                    });
                }
            }
        }
    }
    faces
}

/// The lines along `dir` (their `dir.perp_dot` coordinates) on which at least `min_points` of
/// `pts` lie within [`HALF_WIDTH_M`], [`DENSER`] times as many as within it of the lines
/// [`BESIDE_M`] either side; the densest first, each at least [`BESIDE_M`] from a denser one.
fn dense_lines(pts: &[(DVec2, f64)], dir: DVec2, min_points: usize) -> Vec<f64> {
    let t: Vec<f64> = pts.iter().map(|(q, _)| dir.perp_dot(*q)).collect();
    let lo = t.iter().copied().fold(f64::INFINITY, f64::min) - BESIDE_M - HALF_WIDTH_M;
    let hi = t.iter().copied().fold(f64::NEG_INFINITY, f64::max) + BESIDE_M + HALF_WIDTH_M;
    // (the histogram is as long as the part is wide, which the height map's size bounds; a
    // part wider than `MAX_BINS` of them holds no staircase's side face worth the search)
    let span = (hi - lo) / BIN_M;
    if !span.is_finite() || span >= MAX_BINS as f64 {
        return Vec::new();
    }
    let bins = span.ceil() as usize + 1;
    // (the counts within HALF_WIDTH_M of each bin)
    let half = (HALF_WIDTH_M / BIN_M).round() as usize;
    let counts = window_counts(&t, lo, BIN_M, bins + 1, half);
    let window = |i: usize| counts[i];
    let beside = (BESIDE_M / BIN_M).round() as usize;
    let mut peaks: Vec<(usize, usize)> = (beside..=bins.saturating_sub(beside))
        .map(|i| (i, window(i)))
        .filter(|&(i, n)| {
            n >= min_points && n >= DENSER * window(i - beside).max(window(i + beside))
        })
        .collect();
    peaks.sort_by_key(|&(i, n)| (std::cmp::Reverse(n), i));
    let mut kept: Vec<usize> = Vec::new();
    for (i, _) in peaks {
        if kept.iter().all(|&j| i.abs_diff(j) >= beside) {
            kept.push(i);
        }
    }
    // (each line at the median of the returns in its window: a plateau of equally full windows
    // spans a face's width)
    kept.into_iter()
        .filter_map(|i| {
            let a = lo + i.saturating_sub(half) as f64 * BIN_M;
            let b = lo + (i + half + 1) as f64 * BIN_M;
            let mut within: Vec<f64> = t.iter().copied().filter(|&v| v >= a && v < b).collect();
            crate::points::quantile(&mut within, 0.5)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A vertical face along x at y = `y`, from x0 to x1, stepping up `rise` every `run`.
    fn stepped_face(y: f64, x0: f64, steps: u32, run: f64, rise: f64) -> Vec<(DVec2, f64)> {
        let mut v = Vec::new();
        let n = (f64::from(steps) * run / 0.02) as usize;
        for i in 0..n {
            let x = x0 + i as f64 * 0.02;
            let top = rise * ((i as f64 * 0.02 / run).floor() + 1.0);
            let mut z = 0.05;
            while z <= top {
                v.push((DVec2::new(x, y + 0.01 * ((i % 3) as f64 - 1.0)), z));
                z += 0.03;
            }
        }
        v
    }

    /// A flat top (a desk) from `lo` to `hi` at height `z`, sampled every 5 cm.
    fn desk(lo: DVec2, hi: DVec2, z: f64) -> Vec<(DVec2, f64)> {
        let mut v = Vec::new();
        let mut x = lo.x;
        while x <= hi.x {
            let mut y = lo.y;
            while y <= hi.y {
                v.push((DVec2::new(x, y), z));
                y += 0.05;
            }
            x += 0.05;
        }
        v
    }

    #[test]
    fn a_side_face_beside_a_desk_is_a_face_of_its_own() {
        let face = stepped_face(5.15, 11.0, 6, 0.3, 0.17);
        let mut pts = face.clone();
        pts.extend(desk(DVec2::new(12.0, 3.2), DVec2::new(14.0, 5.0), 0.75));
        let faces = side_faces(&pts, &[DVec2::X, DVec2::Y], 2, &StairsConfig::default());
        let along_x: Vec<&Face> = faces.iter().filter(|f| f.dir == DVec2::X).collect();
        assert_eq!(along_x.len(), 1, "{faces:?}");
        assert!(along_x[0].on_wall);
        let selected = along_x[0].select(&pts);
        assert_eq!(
            selected.len(),
            face.len(),
            "the desk's returns are left out"
        );
        let last = face.iter().map(|(q, _)| q.x).fold(f64::MIN, f64::max);
        assert_eq!(along_x[0].along_m, (11.0, last));
    }

    #[test]
    fn an_even_spread_of_returns_has_no_face() {
        let pts = desk(DVec2::new(0.0, 0.0), DVec2::new(3.0, 2.0), 0.75);
        assert!(side_faces(&pts, &[DVec2::X, DVec2::Y], 2, &StairsConfig::default()).is_empty());
    }

    #[test]
    fn a_part_that_is_one_face_is_not_tried_again() {
        let pts = stepped_face(0.0, 0.0, 5, 0.28, 0.16);
        assert!(side_faces(&pts, &[DVec2::X], 1, &StairsConfig::default()).is_empty());
    }
}
