//! The sparse cell index shared by the bucket grid and voxel downsampling: a lattice of cubic
//! cells over the cloud's bounding box whose integer coordinates pack into one key, an
//! open-addressing hash table from keys to dense cell ids (so only occupied cells cost memory),
//! and the counting sort of points into cells.

use crate::error::{RegistrationError, Result};
use glam::{Vec3, Vec3A};

/// The most cells a key space may span (2^40).
pub(crate) const MAX_CELLS: f64 = (1u64 << 40) as f64;

/// A lattice of cubic cells of edge `edge` over the bounding box of a point set.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Lattice {
    /// Minimum corner of the finite points' bounding box.
    pub origin: Vec3A,
    pub edge: f32,
    pub inv_edge: f32,
    /// Cells per axis.
    pub dims: [i64; 3],
}

impl Lattice {
    /// The lattice of edge `edge_m` over the finite points of `points`. Fails with
    /// [`RegistrationError::InvalidParameter`] (blaming `name`) for an edge that is not a
    /// positive finite length, or so small for the extent that it would span more than 2^40
    /// cells.
    pub(crate) fn new(points: &[Vec3], edge_m: f64, name: &'static str) -> Result<Lattice> {
        if !(edge_m.is_finite() && edge_m > 1e-6) {
            return Err(RegistrationError::invalid(
                name,
                edge_m,
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
        let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
        for p in points.iter().filter(|p| p.is_finite()) {
            lo = lo.min(*p);
            hi = hi.max(*p);
        }
        if lo.x > hi.x {
            (lo, hi) = (Vec3::ZERO, Vec3::ZERO);
        }
        let dims_f = (((hi - lo).as_dvec3() / edge_m).floor() + 1.0).to_array();
        let cells = dims_f[0] * dims_f[1] * dims_f[2];
        if cells > MAX_CELLS || cells.is_nan() {
            let e = hi - lo;
            return Err(RegistrationError::invalid(
                name,
                edge_m,
                format!(
                    "too small for the cloud's extent {:.1} x {:.1} x {:.1} m: {cells:.3e} cells \
                     (at most 2^40)",
                    e.x, e.y, e.z
                ),
            ));
        }
        Ok(Lattice {
            origin: Vec3A::from(lo),
            edge: edge_m as f32,
            inv_edge: (1.0 / edge_m) as f32,
            dims: dims_f.map(|d| d as i64),
        })
    }

    /// Cell coordinates of a point (clamped into the lattice).
    #[inline]
    pub(crate) fn coords(&self, p: Vec3A) -> [i64; 3] {
        let c = ((p - self.origin) * self.inv_edge).floor();
        let c = [c.x as i64, c.y as i64, c.z as i64];
        [0, 1, 2].map(|a| c[a].clamp(0, self.dims[a] - 1))
    }

    /// Minimum corner of cell `c`.
    #[inline]
    pub(crate) fn cell_min(&self, c: [i64; 3]) -> Vec3A {
        self.origin + Vec3A::new(c[0] as f32, c[1] as f32, c[2] as f32) * self.edge
    }
}

/// Counting sort of the finite points of `points` into the cells of `lattice`: the table from
/// keys to cell ids (in order of each cell's first point), each cell's start in the order
/// (one more entry than cells), and the input indices in cell order.
pub(crate) fn sort_into_cells(
    points: &[Vec3],
    lattice: &Lattice,
) -> (CellTable, Vec<u32>, Vec<u32>) {
    // Pass 1: cell id of each point, and the count of each cell.
    let mut table = CellTable::with_capacity(points.len() / 8 + 16);
    let mut counts: Vec<u32> = Vec::new();
    let mut cell_of: Vec<u32> = Vec::with_capacity(points.len());
    for p in points {
        if !p.is_finite() {
            cell_of.push(u32::MAX);
            continue;
        }
        let key = pack(lattice.coords(Vec3A::from(*p)), lattice.dims);
        let id = table.get_or_insert(key, counts.len() as u32);
        if id as usize == counts.len() {
            counts.push(0);
        }
        counts[id as usize] += 1;
        cell_of.push(id);
    }
    // Pass 2: prefix sums give each cell's start; scatter the indices.
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
    (table, start, order)
}

/// The bucket key of in-range bucket coordinates.
#[inline(always)]
pub(crate) fn pack(c: [i64; 3], dims: [i64; 3]) -> u64 {
    (c[0] + dims[0] * (c[1] + dims[1] * c[2])) as u64
}

/// An open-addressing hash table (linear probing) from bucket keys to dense bucket ids.
pub(crate) struct CellTable {
    keys: Vec<u64>,
    vals: Vec<u32>,
    shift: u32,
    len: usize,
}

const EMPTY: u64 = u64::MAX;

impl CellTable {
    pub(crate) fn with_capacity(n: usize) -> CellTable {
        let slots = (2 * n.max(8)).next_power_of_two();
        CellTable {
            keys: vec![EMPTY; slots],
            vals: vec![0; slots],
            shift: 64 - slots.trailing_zeros(),
            len: 0,
        }
    }

    #[inline(always)]
    fn slot(&self, key: u64) -> usize {
        (key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> self.shift) as usize
    }

    #[inline(always)]
    pub(crate) fn get(&self, key: u64) -> Option<u32> {
        let mask = self.keys.len() - 1;
        let mut s = self.slot(key);
        loop {
            let k = self.keys[s];
            if k == key {
                return Some(self.vals[s]);
            }
            if k == EMPTY {
                return None;
            }
            s = (s + 1) & mask;
        }
    }

    /// The id of `key`, inserting it with `new_id` if absent.
    pub(crate) fn get_or_insert(&mut self, key: u64, new_id: u32) -> u32 {
        if 2 * (self.len + 1) > self.keys.len() {
            self.grow();
        }
        let mask = self.keys.len() - 1;
        let mut s = self.slot(key);
        loop {
            let k = self.keys[s];
            if k == key {
                return self.vals[s];
            }
            if k == EMPTY {
                self.keys[s] = key;
                self.vals[s] = new_id;
                self.len += 1;
                return new_id;
            }
            s = (s + 1) & mask;
        }
    }

    fn grow(&mut self) {
        let old_keys = std::mem::take(&mut self.keys);
        let old_vals = std::mem::take(&mut self.vals);
        *self = CellTable::with_capacity(old_keys.len());
        for (k, v) in old_keys.into_iter().zip(old_vals) {
            if k != EMPTY {
                self.get_or_insert(k, v);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_grows_and_keeps_every_key() {
        let mut t = CellTable::with_capacity(1);
        for k in 0..10_000u64 {
            assert_eq!(t.get_or_insert(k * 7919, k as u32), k as u32);
        }
        for k in 0..10_000u64 {
            assert_eq!(t.get(k * 7919), Some(k as u32));
            assert_eq!(t.get_or_insert(k * 7919, 0), k as u32);
        }
        assert_eq!(t.get(3), None);
    }

    #[test]
    fn points_sort_into_their_cells_in_first_seen_order() {
        let pts = [
            Vec3::new(0.05, 0.0, 0.0),
            Vec3::new(1.05, 0.0, 0.0),
            Vec3::NAN,
            Vec3::new(0.02, 0.09, 0.0),
            Vec3::new(1.0, 1.0, 1.0),
        ];
        let lattice = Lattice::new(&pts, 0.1, "edge").expect("lattice");
        let (table, start, order) = sort_into_cells(&pts, &lattice);
        assert_eq!(start, vec![0, 2, 3, 4]);
        assert_eq!(order, vec![0, 3, 1, 4]);
        let key = pack(lattice.coords(Vec3A::new(1.05, 0.0, 0.0)), lattice.dims);
        assert_eq!(table.get(key), Some(1));
        assert!(Lattice::new(&pts, f64::NAN, "edge").is_err());
    }
}
