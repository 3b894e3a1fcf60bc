//! The 2009 paper's regular grid of buckets for nearest-neighbour search, made sparse.
//!
//! Space is cut into cubic buckets of edge `bucket_size_m`. Building is a counting sort: every
//! point gets its bucket key, a hash table (open addressing) maps occupied keys to dense bucket
//! ids and counts their points, a prefix sum gives each bucket's start offset, and the points
//! are scattered into bucket order. Only occupied buckets cost memory, so a 10 km wide cloud
//! with 0.25 m buckets is fine.
//!
//! Near the scanner a bucket of floor holds thousands of points, so each bucket is cut once more
//! into `s x s x s` sub-cells (`s` from the bucket's point count, so that a sub-cell of a surface
//! holds about [`LEAF_POINTS`] points; a second counting sort orders the bucket's points by
//! sub-cell, and a table of `s^3 + 1` offsets gives each sub-cell's points). Points are stored
//! "structure of arrays" in chunks of four (x, y and z of four points in one SIMD register each,
//! each sub-cell padded with points at infinity), so a scan computes four squared distances at
//! once.
//!
//! A query scans its own bucket, then those of the 26 neighbours whose box is nearer than the
//! best point found so far (faces first, then edges, then corners); in a bucket it scans only
//! the sub-cells that overlap the ball of the best distance so far and whose points' tight
//! bounding box is nearer than it. A *hint* (a candidate point
//! already known, e.g. the previous query's neighbour or the previous iteration's
//! correspondence) starts the search with a tight bound, so it touches a few sub-cells only.
//!
//! The 27 buckets cover every point within one bucket edge of the query, so **the result is
//! exact when the true nearest neighbour is within `bucket_size_m`**; farther neighbours may be
//! missed (the query then returns a farther point among the 27 buckets, or nothing). With a
//! correspondence gate no wider than the bucket edge the grid is exact.
//!
//! Measured (release, one thread, 162,841 queries of a virtual-laser scan against another,
//! `cargo test --release -p registration --test measure -- --ignored --nocapture`): see the
//! crate documentation.

use super::NearestNeighbors;
use crate::cells::{pack, sort_into_cells, CellTable, Lattice};
use crate::error::Result;
use glam::{Vec3, Vec3A, Vec4};

/// Target number of points per sub-cell (for points on a surface).
pub(crate) const LEAF_POINTS: usize = 16;
/// Largest sub-division of a bucket per axis (finer cuts measured slower: with hints the
/// search is bound by memory traffic, not by distance computations).
const MAX_SUB: usize = 3;

/// Offsets of the 26 neighbours: 6 faces, 12 edges, 8 corners (nearest boxes first).
#[rustfmt::skip]
const NEIGHBOURS: [[i8; 3]; 26] = [
    [-1, 0, 0], [1, 0, 0], [0, -1, 0], [0, 1, 0], [0, 0, -1], [0, 0, 1],
    [-1, -1, 0], [1, -1, 0], [-1, 1, 0], [1, 1, 0], [-1, 0, -1], [1, 0, -1],
    [0, -1, -1], [0, 1, -1], [-1, 0, 1], [1, 0, 1], [0, -1, 1], [0, 1, 1],
    [-1, -1, -1], [1, -1, -1], [-1, 1, -1], [1, 1, -1],
    [-1, -1, 1], [1, -1, 1], [-1, 1, 1], [1, 1, 1],
];

/// Four points, structure of arrays.
#[derive(Clone, Copy, Debug)]
struct Chunk {
    x: Vec4,
    y: Vec4,
    z: Vec4,
}

/// A padding slot: never nearer than anything.
const PAD: Chunk = Chunk {
    x: Vec4::INFINITY,
    y: Vec4::INFINITY,
    z: Vec4::INFINITY,
};

/// One occupied bucket: its sub-division and where its sub-cell offsets start.
#[derive(Clone, Copy, Debug)]
struct Bucket {
    /// Minimum corner.
    corner: Vec3A,
    /// Sub-cells per axis.
    sub: u32,
    /// Sub-cell `k` holds chunks `sub_start[table + k]..sub_start[table + k + 1]`.
    table: u32,
}

/// A sparse regular grid of buckets over a point set (the paper's bucket grid).
pub struct BucketGrid {
    lattice: Lattice,
    table: CellTable,
    buckets: Vec<Bucket>,
    /// Chunk offsets of the sub-cells of all buckets.
    sub_start: Vec<u32>,
    /// Tight bounding box (min, max) of each sub-cell's points, aligned with `sub_start`
    /// (empty sub-cells have an inverted box, infinitely far).
    sub_box: Vec<(Vec3A, Vec3A)>,
    /// Positions in bucket and leaf order, four per chunk.
    chunks: Vec<Chunk>,
    /// Input index of each slot of `chunks` (`u32::MAX` for padding).
    indices: Vec<u32>,
    len: usize,
}

impl BucketGrid {
    /// Builds the grid over the finite points of `points` (non-finite ones are not indexed;
    /// results index the given slice).
    ///
    /// Fails with [`crate::RegistrationError::InvalidParameter`] for a bucket edge that is not a
    /// positive finite length, or so small for the cloud's extent that the grid would span more
    /// than 2^40 buckets.
    pub fn new(points: &[Vec3], bucket_size_m: f64) -> Result<BucketGrid> {
        let lattice = Lattice::new(points, bucket_size_m, "bucket_size_m")?;
        let (table, start, order) = sort_into_cells(points, &lattice);
        let (counts, acc) = (start.len() - 1, order.len());
        // Pass 3: per bucket, counting sort by sub-cell into leaves.
        let mut grid = BucketGrid {
            lattice,
            table,
            buckets: Vec::with_capacity(counts),
            sub_start: Vec::with_capacity(counts * 2),
            sub_box: Vec::with_capacity(counts * 2),
            chunks: Vec::with_capacity(acc / 2),
            indices: Vec::with_capacity(acc * 2),
            len: acc,
        };
        let mut sub_count: Vec<u32> = Vec::new();
        let mut sub_of: Vec<u32> = Vec::new();
        let mut sorted: Vec<u32> = Vec::new();
        for b in 0..counts {
            let members = &order[start[b] as usize..start[b + 1] as usize];
            let n = members.len();
            let s = (((n as f64 / LEAF_POINTS as f64).sqrt().ceil()) as usize).clamp(1, MAX_SUB);
            let corner = lattice.cell_min(lattice.coords(Vec3A::from(points[members[0] as usize])));
            let inv_g = lattice.inv_edge * s as f32;
            sub_of.clear();
            sub_of.extend(members.iter().map(|&i| {
                let l = ((Vec3A::from(points[i as usize]) - corner) * inv_g).floor();
                let l = [l.x, l.y, l.z].map(|v| (v.max(0.0) as usize).min(s - 1));
                (l[0] + s * (l[1] + s * l[2])) as u32
            }));
            let cells = s * s * s;
            sub_count.clear();
            sub_count.resize(cells + 1, 0);
            for &k in &sub_of {
                sub_count[k as usize + 1] += 1;
            }
            for k in 0..cells {
                sub_count[k + 1] += sub_count[k];
            }
            sorted.clear();
            sorted.resize(n, 0);
            let mut fill = sub_count.clone();
            for (m, &k) in members.iter().zip(&sub_of) {
                sorted[fill[k as usize] as usize] = *m;
                fill[k as usize] += 1;
            }
            grid.buckets.push(Bucket {
                corner,
                sub: s as u32,
                table: grid.sub_start.len() as u32,
            });
            for k in 0..cells {
                grid.sub_start.push(grid.chunks.len() as u32);
                let bbox = grid.push_points(
                    points,
                    &sorted[sub_count[k] as usize..sub_count[k + 1] as usize],
                );
                grid.sub_box.push(bbox);
            }
            grid.sub_start.push(grid.chunks.len() as u32);
            grid.sub_box.push((Vec3A::INFINITY, Vec3A::NEG_INFINITY));
        }
        Ok(grid)
    }

    /// Appends the given input points as chunks of four (the last padded); returns their
    /// bounding box.
    fn push_points(&mut self, points: &[Vec3], members: &[u32]) -> (Vec3A, Vec3A) {
        let (mut min, mut max) = (Vec3A::INFINITY, Vec3A::NEG_INFINITY);
        for group in members.chunks(4) {
            let mut ch = PAD;
            for (lane, &i) in group.iter().enumerate() {
                let p = points[i as usize];
                min = min.min(Vec3A::from(p));
                max = max.max(Vec3A::from(p));
                ch.x[lane] = p.x;
                ch.y[lane] = p.y;
                ch.z[lane] = p.z;
                self.indices.push(i);
            }
            for _ in group.len()..4 {
                self.indices.push(u32::MAX);
            }
            self.chunks.push(ch);
        }
        (min, max)
    }

    /// The bucket edge in metres.
    pub fn bucket_size_m(&self) -> f64 {
        self.lattice.edge as f64
    }

    /// Number of occupied buckets.
    pub fn occupied_buckets(&self) -> usize {
        self.buckets.len()
    }

    /// Number of occupied buckets cut into sub-cells (those with more than a few dozen points).
    pub fn subdivided_buckets(&self) -> usize {
        self.buckets.iter().filter(|b| b.sub > 1).count()
    }

    /// Scans the sub-cells of bucket `key` (if occupied) that overlap the ball of `best.1`
    /// (squared) for a nearer point; `best.0` is an input index.
    #[inline(always)]
    fn scan(&self, key: u64, q: Vec3A, qc: &Chunk, best: &mut (u32, f32)) {
        let Some(id) = self.table.get(key) else {
            return;
        };
        let b = self.buckets[id as usize];
        let offsets = &self.sub_start[b.table as usize..];
        let boxes = &self.sub_box[b.table as usize..];
        if b.sub == 1 {
            let (min, max) = boxes[0];
            if (min - q).max(q - max).max(Vec3A::ZERO).length_squared() < best.1 {
                self.scan_chunks(offsets[0] as usize, offsets[1] as usize, qc, best);
            }
            return;
        }
        let s = b.sub as i32;
        let g = self.lattice.edge / s as f32;
        let local = (q - b.corner) / g;
        let r = best.1.sqrt() / g;
        let top = Vec3A::splat((s - 1) as f32);
        let lo = (local - r).floor().max(Vec3A::ZERO).min(top);
        let hi = (local + r).floor().max(Vec3A::ZERO).min(top);
        let (lo, hi) = (lo.as_ivec3(), hi.as_ivec3());
        for z in lo.z..=hi.z {
            let dz = axis_gap(local.z, z);
            for y in lo.y..=hi.y {
                let dy = axis_gap(local.y, y);
                let row = (s * (y + s * z)) as usize;
                for x in lo.x..=hi.x {
                    let dx = axis_gap(local.x, x);
                    if (dx * dx + dy * dy + dz * dz) * g * g >= best.1 {
                        continue;
                    }
                    let k = row + x as usize;
                    let (min, max) = boxes[k];
                    let gap = (min - q).max(q - max).max(Vec3A::ZERO);
                    if gap.length_squared() >= best.1 {
                        continue;
                    }
                    self.scan_chunks(offsets[k] as usize, offsets[k + 1] as usize, qc, best);
                }
            }
        }
    }

    /// Scans chunks `s..e` for a point nearer than `best.1`.
    #[inline(always)]
    fn scan_chunks(&self, s: usize, e: usize, qc: &Chunk, best: &mut (u32, f32)) {
        let mut bound = Vec4::splat(best.1);
        for (k, ch) in self.chunks[s..e].iter().enumerate() {
            let dx = ch.x - qc.x;
            let dy = ch.y - qc.y;
            let dz = ch.z - qc.z;
            let d2 = dx * dx + dy * dy + dz * dz;
            if d2.cmplt(bound).any() {
                for lane in 0..4 {
                    if d2[lane] < best.1 {
                        *best = (self.indices[(s + k) * 4 + lane], d2[lane]);
                    }
                }
                bound = Vec4::splat(best.1);
            }
        }
    }

    /// The nearest point within the 27 buckets, starting from a known candidate
    /// `hint = (input index, squared distance to the query)` when that is within the gate.
    fn search(
        &self,
        query: Vec3,
        max_distance_m: f32,
        hint: Option<(u32, f32)>,
    ) -> Option<(u32, f32)> {
        let q = Vec3A::from(query);
        let l = &self.lattice;
        let rel = (q - l.origin) * l.inv_edge;
        let cf = rel.floor();
        if !cf.is_finite() {
            return None;
        }
        let c = [cf.x as i64, cf.y as i64, cf.z as i64];
        let d = l.dims;
        if (0..3).any(|a| c[a] < -1 || c[a] > d[a]) {
            return None;
        }
        let mut best = (u32::MAX, max_distance_m * max_distance_m);
        if let Some(h) = hint.filter(|h| h.1 < best.1) {
            best = h;
        }
        let qc = Chunk {
            x: Vec4::splat(q.x),
            y: Vec4::splat(q.y),
            z: Vec4::splat(q.z),
        };
        let inside = |c: [i64; 3]| (0..3).all(|a| c[a] >= 0 && c[a] < d[a]);
        if inside(c) {
            self.scan(pack(c, d), q, &qc, &mut best);
        }
        // Squared distances to the lower and upper faces of the query's bucket; neighbours
        // only where a face is nearer than the best so far (most queries near a surface need
        // none), in the order faces, edges, corners.
        let frac = (rel - cf) * l.edge;
        let lo = (frac * frac).to_array();
        let up = Vec3A::splat(l.edge) - frac;
        let hi = (up * up).to_array();
        if (0..3).any(|a| lo[a].min(hi[a]) < best.1) {
            for off in &NEIGHBOURS {
                let mut box_d2 = 0.0;
                for a in 0..3 {
                    box_d2 += match off[a] {
                        -1 => lo[a],
                        1 => hi[a],
                        _ => 0.0,
                    };
                }
                if box_d2 >= best.1 {
                    continue;
                }
                let n = [0, 1, 2].map(|a| c[a] + off[a] as i64);
                if inside(n) {
                    self.scan(pack(n, d), q, &qc, &mut best);
                }
            }
        }
        (best.0 != u32::MAX).then_some(best)
    }
}

/// Distance (in sub-cells) from coordinate `v` to the interval `[i, i + 1)`.
#[inline(always)]
fn axis_gap(v: f32, i: i32) -> f32 {
    let i = i as f32;
    (i - v).max(v - (i + 1.0)).max(0.0)
}

impl std::fmt::Debug for BucketGrid {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("BucketGrid")
            .field("bucket_size_m", &self.lattice.edge)
            .field("points", &self.len)
            .field("buckets", &self.buckets.len())
            .finish()
    }
}

impl NearestNeighbors for BucketGrid {
    #[inline]
    fn nearest(&self, query: Vec3, max_distance_m: f32) -> Option<(u32, f32)> {
        self.search(query, max_distance_m, None)
    }

    #[inline]
    fn nearest_with_hint(
        &self,
        query: Vec3,
        max_distance_m: f32,
        hint: Option<(u32, f32)>,
    ) -> Option<(u32, f32)> {
        self.search(query, max_distance_m, hint)
    }

    fn len(&self) -> usize {
        self.len
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn neighbour_table_is_faces_edges_corners() {
        let order: Vec<usize> = NEIGHBOURS
            .iter()
            .map(|o| o.iter().filter(|v| **v != 0).count())
            .collect();
        assert_eq!(order.iter().filter(|&&o| o == 1).count(), 6);
        assert!(order.windows(2).all(|w| w[0] <= w[1]));
        assert_eq!(order[25], 3);
        let mut sorted = NEIGHBOURS.to_vec();
        sorted.sort();
        sorted.dedup();
        assert_eq!(sorted.len(), 26);
    }
}
