//! Which scans saw something within a distance of a point: every scan's points sorted into
//! voxels of that edge, so that the points within the distance lie in the 27 voxels round the
//! point's, and a distance test on those settles it.
//!
//! A voxel test alone (another scan's point anywhere in the 27 voxels) reaches up to twice
//! the edge along each axis: a person standing 10-30 cm from a pillar that every scan saw
//! shares voxels with it and stays, a thin tall obstacle or, beside a second pillar, a wall.

use cloud::PointCloud;
use glam::Vec3;
use rayon::prelude::*;
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};
use std::sync::atomic::{AtomicU8, Ordering};

/// Every scan's points by voxel, with which scans left them.
pub(crate) struct Voxels {
    edge_m: f32,
    cells: HashMap<[i32; 3], Cell, BuildHasherDefault<KeyHasher>>,
    /// (scan, point), sorted by voxel and within a voxel by scan.
    points: Vec<(u32, Vec3)>,
    /// Per point, whether its scan's returns round it are sparse (`UNKNOWN` until asked).
    sparse: Vec<AtomicU8>,
}

/// One voxel's points: `points[start..end]`, and the scan that left them all, or `MANY`.
struct Cell {
    start: u32,
    end: u32,
    owner: u32,
}

const MANY: u32 = u32::MAX;

/// Which other scans saw a point ([`Voxels::vouchers`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Vouch {
    /// No other scan.
    None,
    /// Exactly one other scan: this one.
    One(u32),
    /// Two or more, or any where the point's own returns are sparse.
    Many,
}

impl Voxels {
    /// Sorts the finite points of `scans` into voxels of `edge_m`, the distance within which
    /// another scan's return sees the same thing.
    pub(crate) fn build(scans: &[PointCloud], edge_m: f32) -> Voxels {
        let mut points: Vec<(u32, Vec3)> = scans
            .iter()
            .enumerate()
            .flat_map(|(k, s)| {
                s.points
                    .iter()
                    .filter(|p| p.is_finite())
                    .map(move |&p| (k as u32, p))
            })
            .collect();
        points.par_sort_unstable_by_key(|&(k, p)| (key(p, edge_m), k));
        let mut cells: HashMap<[i32; 3], Cell, BuildHasherDefault<KeyHasher>> = HashMap::default();
        let mut start = 0;
        while start < points.len() {
            let here = key(points[start].1, edge_m);
            let end = start
                + points[start..]
                    .iter()
                    .take_while(|&&(_, p)| key(p, edge_m) == here)
                    .count();
            let first = points[start].0;
            let owner = if points[end - 1].0 == first {
                first
            } else {
                MANY
            };
            // The sort keeps the points' count within u32 for any cloud this crate reads.
            cells.insert(
                here,
                Cell {
                    start: start as u32,
                    end: end as u32,
                    owner,
                },
            );
            start = end;
        }
        let sparse = (0..points.len()).map(|_| AtomicU8::new(UNKNOWN)).collect();
        Voxels {
            edge_m,
            cells,
            points,
            sparse,
        }
    }

    /// Which scans other than `k` left a point within the edge of `p`, or within twice
    /// that where the returns are sparse (fewer than [`MIN_OWN_NEIGHBOURS`] of their own
    /// scan's within the edge): scan `k`'s round `p`, or the other scan's round its point.
    /// None, one (which), or more. A point of scan `k`'s sparse returns seen by any other is
    /// [`Vouch::Many`]: glass, whose few returns per scan lie apart, is vouched for by every
    /// scan that looks at it, seldom within the distance.
    pub(crate) fn vouchers(&self, p: Vec3, k: usize) -> Vouch {
        let (k, r) = (k as u32, self.edge_m);
        let mut one = None;
        let mut note = |j: usize| {
            let s = self.points[j].0;
            match one {
                None => one = Some(s),
                Some(o) if o != s => return true,
                Some(_) => {}
            }
            false
        };
        // (any_other stops at the first accepted point: a second scan's stops it)
        if self.any_other(p, k, r, &mut note) {
            return Vouch::Many;
        }
        let sparse_here = self.own_count(p, k) < MIN_OWN_NEIGHBOURS;
        if sparse_here {
            let seen = one.is_some() || self.any_other(p, k, 2.0 * r, |_| true);
            return if seen { Vouch::Many } else { Vouch::None };
        }
        if self.any_other(p, k, 2.0 * r, |j| self.is_sparse(j) && note(j)) {
            return Vouch::Many;
        }
        one.map_or(Vouch::None, Vouch::One)
    }

    /// Whether a point of a scan other than `k` lies within `r` of `p`, not lower than `p` by
    /// more than [`BELOW_FRACTION`] of the edge, and passes `accept` (given its index in
    /// `points`).
    fn any_other(&self, p: Vec3, k: u32, r: f32, mut accept: impl FnMut(usize) -> bool) -> bool {
        let (r2, lowest) = (r * r, p.z - BELOW_FRACTION * self.edge_m);
        self.cells_near(p, r).any(|cell| {
            let (lo, hi) = cell.run_of(k, &self.points);
            (cell.start..lo).chain(hi..cell.end).any(|j| {
                let q = self.points[j].1;
                q.distance_squared(p) <= r2 && q.z >= lowest && accept(j)
            })
        })
    }

    /// How many of scan `k`'s points lie within the edge of `p` (`p` itself included),
    /// counted up to [`MIN_OWN_NEIGHBOURS`].
    fn own_count(&self, p: Vec3, k: u32) -> usize {
        let r2 = self.edge_m * self.edge_m;
        let mut n = 0;
        for cell in self.cells_near(p, self.edge_m) {
            let (lo, hi) = cell.run_of(k, &self.points);
            n += self.points[lo..hi]
                .iter()
                .filter(|e| e.1.distance_squared(p) <= r2)
                .take(MIN_OWN_NEIGHBOURS - n)
                .count();
            if n >= MIN_OWN_NEIGHBOURS {
                break;
            }
        }
        n
    }

    /// Whether `points[j]` is a sparse return of its scan, worked out once.
    fn is_sparse(&self, j: usize) -> bool {
        match self.sparse[j].load(Ordering::Relaxed) {
            DENSE => false,
            SPARSE => true,
            _ => {
                let (s, q) = self.points[j];
                let sparse = self.own_count(q, s) < MIN_OWN_NEIGHBOURS;
                self.sparse[j].store(if sparse { SPARSE } else { DENSE }, Ordering::Relaxed);
                sparse
            }
        }
    }

    /// The voxels within `r` of `p`, its own first (most questions are settled there).
    fn cells_near(&self, p: Vec3, r: f32) -> impl Iterator<Item = Span> + '_ {
        let reach = (r / self.edge_m).ceil() as i32;
        let [x, y, z] = key(p, self.edge_m);
        let around = (-reach..=reach)
            .flat_map(move |dx| {
                (-reach..=reach).flat_map(move |dy| (-reach..=reach).map(move |dz| [dx, dy, dz]))
            })
            .filter(|&o| o != [0, 0, 0]);
        std::iter::once([0, 0, 0])
            .chain(around)
            .filter_map(move |[dx, dy, dz]| self.cells.get(&[x + dx, y + dy, z + dz]))
            .map(|c| Span {
                start: c.start as usize,
                end: c.end as usize,
                owner: c.owner,
            })
    }
}

/// One voxel's range of `points`, and the scan that left them all, or `MANY`.
struct Span {
    start: usize,
    end: usize,
    owner: u32,
}

impl Span {
    /// Scan `k`'s points in the voxel: one run (sorted by scan), as a range of `points`.
    fn run_of(&self, k: u32, points: &[(u32, Vec3)]) -> (usize, usize) {
        if self.owner == k {
            return (self.start, self.end);
        }
        let here = &points[self.start..self.end];
        (
            self.start + here.partition_point(|&(s, _)| s < k),
            self.start + here.partition_point(|&(s, _)| s <= k),
        )
    }
}

const UNKNOWN: u8 = 0;
const DENSE: u8 = 1;
const SPARSE: u8 = 2;

/// Another scan's point lower than a point by more than this fraction of the edge is not of
/// the same thing: it is what the thing stands on. A person's feet have the floor within the
/// edge (twice it where the person's returns are sparse, a streak), which every scan saw: as
/// "seen by another", the lowest 0.15-0.3 m of a person who walked past one scan stayed in the
/// map, a kerb-high obstacle in a garage's lane (garage-64, seeds 61-65: 18 of them). The
/// frame's z is up, as everywhere in the chain (the floor is levelled later, a tilt of a few
/// degrees moves a neighbour 0.15 m away by under a centimetre).
const BELOW_FRACTION: f32 = 0.5;

/// A scan's returns round a point (itself included) fewer than this within `persist_m` are
/// sparse: glass returns a few of the beams that meet it (8 % in the realistic laser), dark
/// and far surfaces lose or spread theirs, so another scan's returns on the same surface lie
/// farther apart too and are looked for within twice `persist_m`. A surface sampled densely
/// (a person a few metres from the sensor: dozens of returns within 15 cm) is not.
pub(crate) const MIN_OWN_NEIGHBOURS: usize = 8;

fn key(p: Vec3, edge_m: f32) -> [i32; 3] {
    // Saturating casts: a coordinate beyond i32's range lands in the edge voxel.
    [
        (p.x / edge_m).floor() as i32,
        (p.y / edge_m).floor() as i32,
        (p.z / edge_m).floor() as i32,
    ]
}

/// A cheap hash of voxel keys (the standard one costs more than the lookups it serves).
#[derive(Default)]
struct KeyHasher(u64);

impl Hasher for KeyHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for b in bytes {
            self.0 = (self.0.rotate_left(8) ^ u64::from(*b)).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        }
    }

    fn write_i32(&mut self, v: i32) {
        self.0 = (self.0.rotate_left(21) ^ v as u32 as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whether a scan other than `k` saw `p`.
    fn seen(v: &Voxels, p: Vec3, k: usize) -> bool {
        v.vouchers(p, k) != Vouch::None
    }

    /// Scan 0 dense round the origin: a 5 x 5 grid, 1 cm apart.
    fn dense() -> PointCloud {
        PointCloud::from_points(
            (0..25)
                .map(|i| Vec3::new(0.01 * (i % 5) as f32, 0.01 * (i / 5) as f32, 0.0))
                .collect(),
        )
    }

    #[test]
    fn another_scans_point_counts_within_the_distance() {
        // Scan 1 dense too, 0.12 m away diagonally and 0.2 m away along x.
        let shifted = |o: Vec3| {
            let mut c = dense();
            c.points.iter_mut().for_each(|p| *p += o);
            c
        };
        let pair = [dense(), shifted(Vec3::new(0.2, 0.0, 0.0))];
        // Scan 0's nearest to scan 1's (0.2, 0, 0) is (0.04, 0, 0): 0.16 m.
        assert!(!seen(
            &Voxels::build(&pair, 0.15),
            Vec3::new(0.2, 0.0, 0.0),
            1
        ));
        assert!(seen(
            &Voxels::build(&pair, 0.17),
            Vec3::new(0.2, 0.0, 0.0),
            1
        ));
        // The nearest of scan 1's, shifted by (-0.07, 0.07, 0.07), is 0.103 m away.
        let pair = [dense(), shifted(Vec3::new(-0.07, 0.07, 0.07))];
        assert!(seen(&Voxels::build(&pair, 0.15), Vec3::ZERO, 0));
        assert!(!seen(&Voxels::build(&pair, 0.1), Vec3::ZERO, 0));
        // Scan 0's own points never count.
        let v = Voxels::build(&[dense(), PointCloud::from_points(vec![])], 0.15);
        assert!(!seen(&v, Vec3::ZERO, 0));
    }

    #[test]
    fn the_floor_under_a_point_is_not_the_same_thing() {
        // Scan 0's floor, dense, and a lone return of scan 1 0.12 m above it (a person's
        // shin): the floor is within the edge, yet no other scan saw the shin.
        let floor = dense();
        let shin = PointCloud::from_points(vec![Vec3::new(0.02, 0.02, 0.12)]);
        let v = Voxels::build(&[floor, shin], 0.15);
        assert!(!seen(&v, Vec3::new(0.02, 0.02, 0.12), 1));
        // The floor point itself is seen by the other scan's return above it (a thing's foot
        // on the floor hides nothing of it), and a return 5 cm up still counts as the floor's.
        assert!(seen(&v, Vec3::new(0.02, 0.02, 0.0), 0));
        let low = PointCloud::from_points(vec![Vec3::new(0.02, 0.02, 0.05)]);
        let v = Voxels::build(&[dense(), low], 0.15);
        assert!(seen(&v, Vec3::new(0.02, 0.02, 0.05), 1));
    }

    #[test]
    fn sparse_returns_count_within_twice_the_distance() {
        // A lone return of scan 1 (glass returns a few beams) 0.2 m from scan 0's dense
        // surface: it matches from either side; 0.35 m away it does not.
        let lone = |x: f32| PointCloud::from_points(vec![Vec3::new(x, 0.0, 0.0)]);
        let v = Voxels::build(&[dense(), lone(0.24)], 0.15);
        assert!(seen(&v, Vec3::ZERO, 0));
        assert!(seen(&v, Vec3::new(0.24, 0.0, 0.0), 1));
        let v = Voxels::build(&[dense(), lone(0.39)], 0.15);
        assert!(!seen(&v, Vec3::ZERO, 0));
        assert!(!seen(&v, Vec3::new(0.39, 0.0, 0.0), 1));
        assert!(!seen(&v, Vec3::new(3.0, 0.0, 0.0), 0));
    }
}
