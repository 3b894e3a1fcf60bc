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

use crate::cells::{pack, CellTable, MAX_CELLS};
use crate::error::{RegistrationError, Result};
use crate::nearest::NearestNeighbors;
use glam::{Vec3, Vec3A, Vec4};

/// Target number of points per sub-cell (for points on a surface).
pub(crate) const LEAF_POINTS: usize = 16;
/// Largest sub-division of a bucket per axis (finer cuts measured slower: with hints the
/// search is bound by memory traffic, not by distance computations).
const MAX_SUB: usize = 3;

/// Offsets of the 26 neighbours: 6 faces, 12 edges, 8 corners (nearest boxes first).
const NEIGHBOURS: [[i8; 3]; 26] = {
    let mut out = [[0i8; 3]; 26];
    let mut n = 0;
    let mut order = 1;
    while order <= 3 {
        let mut z = -1i8;
        while z <= 1 {
            let mut y = -1i8;
            while y <= 1 {
                let mut x = -1i8;
                while x <= 1 {
                    let nonzero = (x != 0) as i32 + (y != 0) as i32 + (z != 0) as i32;
                    if nonzero == order {
                        out[n] = [x, y, z];
                        n += 1;
                    }
                    x += 1;
                }
                y += 1;
            }
            z += 1;
        }
        order += 1;
    }
    out
};

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
    bucket_size_m: f32,
    inv_bucket: f32,
    /// Minimum corner of the finite points' bounding box.
    origin: Vec3A,
    /// Buckets per axis.
    dims: [i64; 3],
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
    /// Fails with [`RegistrationError::InvalidParameter`] for a bucket edge that is not a
    /// positive finite length, or so small for the cloud's extent that the grid would span more
    /// than 2^40 buckets.
    pub fn new(points: &[Vec3], bucket_size_m: f64) -> Result<BucketGrid> {
        if !(bucket_size_m.is_finite() && bucket_size_m > 1e-6) {
            return Err(RegistrationError::invalid(
                "bucket_size_m",
                bucket_size_m,
                "must be a finite length above 1 micrometre",
            ));
        }
        if points.len() >= (u32::MAX / 4) as usize {
            return Err(RegistrationError::invalid(
                "points",
                points.len() as f64,
                "at most 2^30 points",
            ));
        }
        let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        for p in points.iter().filter(|p| p.is_finite()) {
            lo = lo.min(*p);
            hi = hi.max(*p);
        }
        if lo.x > hi.x {
            lo = Vec3::ZERO;
            hi = Vec3::ZERO;
        }
        let extent = (hi - lo).as_dvec3() / bucket_size_m;
        let dims_f = (extent.floor() + 1.0).to_array();
        let cells = dims_f[0] * dims_f[1] * dims_f[2];
        if cells > MAX_CELLS || cells.is_nan() {
            return Err(RegistrationError::invalid(
                "bucket_size_m",
                bucket_size_m,
                format!(
                    "too small for the cloud's extent {:.1} x {:.1} x {:.1} m: the grid would \
                     span {cells:.3e} buckets (at most 2^40)",
                    hi.x - lo.x,
                    hi.y - lo.y,
                    hi.z - lo.z
                ),
            ));
        }
        let dims = dims_f.map(|d| d as i64);
        let inv_bucket = (1.0 / bucket_size_m) as f32;
        let origin = Vec3A::from(lo);
        let coords = |p: Vec3A| -> [i64; 3] {
            let c = ((p - origin) * inv_bucket).floor();
            let c = [c.x as i64, c.y as i64, c.z as i64];
            [0, 1, 2].map(|a| c[a].clamp(0, dims[a] - 1))
        };

        // Counting sort, pass 1: bucket id of each point, and the count of each bucket.
        let mut table = CellTable::with_capacity(points.len() / 8 + 16);
        let mut counts: Vec<u32> = Vec::new();
        let mut cell_of: Vec<u32> = Vec::with_capacity(points.len());
        for p in points {
            if !p.is_finite() {
                cell_of.push(u32::MAX);
                continue;
            }
            let id = table.get_or_insert(pack(coords(Vec3A::from(*p)), dims), counts.len() as u32);
            if id as usize == counts.len() {
                counts.push(0);
            }
            counts[id as usize] += 1;
            cell_of.push(id);
        }
        // Pass 2: prefix sums give each bucket's start, then scatter.
        let mut start = Vec::with_capacity(counts.len() + 1);
        let mut acc = 0u32;
        start.push(0);
        for &c in &counts {
            acc += c;
            start.push(acc);
        }
        let mut fill: Vec<u32> = start[..counts.len()].to_vec();
        let mut order = vec![0u32; acc as usize];
        for (i, &id) in cell_of.iter().enumerate() {
            if id != u32::MAX {
                order[fill[id as usize] as usize] = i as u32;
                fill[id as usize] += 1;
            }
        }
        // Pass 3: per bucket, counting sort by sub-cell into leaves.
        let mut grid = BucketGrid {
            bucket_size_m: bucket_size_m as f32,
            inv_bucket,
            origin,
            dims,
            table,
            buckets: Vec::with_capacity(counts.len()),
            sub_start: Vec::with_capacity(counts.len() * 2),
            sub_box: Vec::with_capacity(counts.len() * 2),
            chunks: Vec::with_capacity(acc as usize / 2),
            indices: Vec::with_capacity(acc as usize * 2),
            len: acc as usize,
        };
        let mut sub_count: Vec<u32> = Vec::new();
        let mut sub_of: Vec<u32> = Vec::new();
        let mut sorted: Vec<u32> = Vec::new();
        for b in 0..counts.len() {
            let members = &order[start[b] as usize..start[b + 1] as usize];
            let n = members.len();
            let s = (((n as f64 / LEAF_POINTS as f64).sqrt().ceil()) as usize).clamp(1, MAX_SUB);
            let corner = grid.bucket_min(coords(Vec3A::from(points[members[0] as usize])));
            let inv_g = inv_bucket * s as f32;
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

    /// Minimum corner of bucket `c`.
    fn bucket_min(&self, c: [i64; 3]) -> Vec3A {
        self.origin + Vec3A::new(c[0] as f32, c[1] as f32, c[2] as f32) * self.bucket_size_m
    }

    /// The bucket edge in metres.
    pub fn bucket_size_m(&self) -> f64 {
        self.bucket_size_m as f64
    }

    /// Number of occupied buckets.
    pub fn occupied_buckets(&self) -> usize {
        self.buckets.len()
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
        let g = self.bucket_size_m / s as f32;
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
        let rel = (q - self.origin) * self.inv_bucket;
        let cf = rel.floor();
        if !cf.is_finite() {
            return None;
        }
        let c = [cf.x as i64, cf.y as i64, cf.z as i64];
        let d = self.dims;
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
        let frac = (rel - cf) * self.bucket_size_m;
        let lo = (frac * frac).to_array();
        let up = Vec3A::splat(self.bucket_size_m) - frac;
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
    use crate::kdtree::KdTree;

    /// A small deterministic generator (SplitMix64) for test points.
    fn points(seed: u64, n: usize, scale: f32) -> Vec<Vec3> {
        let mut s = seed;
        let mut next = move || {
            s = s.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = s;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
        };
        (0..n)
            .map(|_| Vec3::new(next(), next(), next()) * scale)
            .collect()
    }

    fn brute(points: &[Vec3], q: Vec3) -> f32 {
        points
            .iter()
            .map(|p| (*p - q).length_squared())
            .fold(f32::INFINITY, f32::min)
    }

    #[test]
    fn neighbour_table_is_faces_edges_corners() {
        let order: Vec<usize> = NEIGHBOURS
            .iter()
            .map(|o| o.iter().filter(|v| **v != 0).count())
            .collect();
        assert_eq!(order.iter().filter(|&&o| o == 1).count(), 6);
        assert!(order.windows(2).all(|w| w[0] <= w[1]));
        assert_eq!(order[25], 3);
    }

    #[test]
    fn grid_matches_brute_force_and_kdtree_within_a_bucket() {
        // Sparse buckets, dense (sub-divided) buckets, and a dense plane.
        let plane: Vec<Vec3> = points(3, 20_000, 1.0)
            .into_iter()
            .map(|p| Vec3::new(p.x, p.y, 0.3 + 0.01 * p.z))
            .collect();
        for (pts, bucket) in [
            (points(7, 3000, 2.0), 0.2f32),
            (points(8, 20_000, 0.5), 0.25),
            (plane, 0.3),
        ] {
            let grid = BucketGrid::new(&pts, bucket as f64).expect("grid");
            let tree = KdTree::new(&pts);
            assert_eq!(grid.len(), pts.len());
            let (lo, hi) = pts
                .iter()
                .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(l, h), p| {
                    (l.min(*p), h.max(*p))
                });
            let mut checked = 0;
            for q in points(99, 2000, 1.0) {
                let q = lo - Vec3::splat(0.1) + q * (hi - lo + Vec3::splat(0.2));
                let truth = brute(&pts, q);
                let g = grid.nearest(q, bucket);
                // A hint (any point, with its true distance) never changes the answer.
                let h = q.x.to_bits() % pts.len() as u32;
                let hinted = grid.nearest_with_hint(
                    q,
                    bucket,
                    Some((h, (pts[h as usize] - q).length_squared())),
                );
                assert_eq!(hinted.map(|r| r.1), g.map(|r| r.1));
                let t = tree.nearest(q, bucket);
                if truth < bucket * bucket * 0.999 {
                    let (gi, gd) = g.expect("grid finds a neighbour within a bucket");
                    let (ti, td) = t.expect("tree finds it too");
                    assert!((gd - truth).abs() < 1e-6 && (td - truth).abs() < 1e-6);
                    assert!(((pts[gi as usize] - q).length_squared() - gd).abs() < 1e-6);
                    assert!(((pts[ti as usize] - q).length_squared() - td).abs() < 1e-6);
                    checked += 1;
                } else if truth > bucket * bucket * 1.001 {
                    assert!(g.is_none() && t.is_none());
                }
            }
            assert!(checked > 1000, "{checked}");
            assert!(
                grid.buckets.iter().any(|b| b.sub > 1) || bucket < 0.25,
                "dense buckets are cut"
            );
        }
    }

    #[test]
    fn grid_skips_non_finite_points_and_far_queries() {
        let pts = vec![Vec3::ZERO, Vec3::NAN, Vec3::new(1.0, 0.0, 0.0)];
        let grid = BucketGrid::new(&pts, 0.5).expect("grid");
        assert_eq!(grid.len(), 2);
        assert_eq!(
            grid.nearest(Vec3::new(0.9, 0.1, 0.0), 0.5).map(|r| r.0),
            Some(2)
        );
        assert_eq!(grid.nearest(Vec3::new(100.0, 0.0, 0.0), 0.5), None);
        assert_eq!(grid.nearest(Vec3::NAN, 0.5), None);
        let empty = BucketGrid::new(&[], 0.5).expect("empty grid");
        assert!(empty.is_empty());
        assert_eq!(empty.nearest(Vec3::ZERO, 1.0), None);
    }

    #[test]
    fn wide_cloud_is_sparse_but_tiny_buckets_are_refused() {
        // 10 km x 10 km x 20 m in 0.25 m buckets: 1.3e11 buckets in the key space, 2 occupied.
        let pts = vec![Vec3::ZERO, Vec3::new(10_000.0, 10_000.0, 20.0)];
        let grid = BucketGrid::new(&pts, 0.25).expect("10 km wide cloud");
        assert_eq!(grid.occupied_buckets(), 2);
        assert!(matches!(
            BucketGrid::new(&pts, 0.001),
            Err(RegistrationError::InvalidParameter {
                name: "bucket_size_m",
                ..
            })
        ));
        assert!(BucketGrid::new(&pts, 0.0).is_err());
    }
}
