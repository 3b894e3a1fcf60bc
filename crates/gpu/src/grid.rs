//! The model (target) cloud's bucket grid for the GPU, built on the CPU and uploaded once:
//! a counting sort of the points into cubic buckets, and an open-addressing hash table from
//! occupied bucket keys to their ranges, so only occupied buckets cost memory (the paper used a
//! dense 256^3 grid over a 40 m cube; the hash keeps a 10 km wide cloud cheap).

use crate::error::{GpuError, Result};
use glam::Vec3;
use std::collections::HashMap;

/// Marks an empty hash slot and "no correspondence".
pub(crate) const NONE: u32 = u32::MAX;

/// A bucket grid ready for upload.
pub(crate) struct HostGrid {
    /// Grid origin (minimum corner, one bucket of margin).
    pub origin: Vec3,
    /// Bucket edge.
    pub bucket_size_m: f32,
    /// Buckets per axis.
    pub dims: [u32; 3],
    /// Points in bucket order, xyz + 1.
    pub sorted: Vec<[f32; 4]>,
    /// Input index of each sorted point.
    pub original: Vec<u32>,
    /// Normals in bucket order (xyz + 0), if given.
    pub normals: Option<Vec<[f32; 4]>>,
    /// Hash table keys (`NONE` = empty).
    pub keys: Vec<u32>,
    /// Hash table values: bucket id.
    pub vals: Vec<u32>,
    /// Sub-cells per bucket axis: each bucket is cut into `sub^3` sub-cells.
    pub sub: u32,
    /// Sub-cell `k` of bucket `b` holds sorted points `start[b * sub^3 + k]..start[b * sub^3 + k + 1]`.
    pub start: Vec<u32>,
}

/// Target edge of a sub-cell (metres).
const LEAF_M: f32 = 0.05;

/// The hash of a bucket key (Knuth's multiplicative hash), as in the shader.
pub(crate) fn slot_of(key: u32, mask: u32) -> u32 {
    key.wrapping_mul(2_654_435_761) & mask
}

impl HostGrid {
    pub(crate) fn build(
        points: &[Vec3],
        normals: Option<&[Vec3]>,
        bucket_size_m: f32,
    ) -> Result<HostGrid> {
        if points.is_empty() {
            return Err(GpuError::Invalid("the target cloud is empty".into()));
        }
        if !(bucket_size_m.is_finite() && bucket_size_m > 1e-4) {
            return Err(GpuError::Invalid(format!(
                "bucket_size_m = {bucket_size_m} must be a positive length"
            )));
        }
        if let Some(i) = points.iter().position(|p| !p.is_finite()) {
            return Err(GpuError::Invalid(format!("target point {i} is not finite")));
        }
        let (lo, hi) = points
            .iter()
            .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(a, b), p| {
                (a.min(*p), b.max(*p))
            });
        let origin = lo - Vec3::splat(bucket_size_m);
        let span = ((hi - origin) / bucket_size_m).floor() + Vec3::splat(2.0);
        let cells = span.x as f64 * span.y as f64 * span.z as f64;
        if cells >= u32::MAX as f64 {
            return Err(GpuError::TooLarge(format!(
                "{:.0} buckets of {bucket_size_m} m over the cloud's extent exceed the 2^32 key space; use larger buckets",
                cells
            )));
        }
        let dims = [span.x as u32, span.y as u32, span.z as u32];
        let sub = (bucket_size_m / LEAF_M).round().clamp(1.0, 8.0) as u32;
        let sub3 = sub * sub * sub;
        let cell_of = |p: Vec3| {
            let g = (p - origin) / bucket_size_m;
            let c = g.floor();
            let f = ((g - c) * sub as f32)
                .floor()
                .clamp(Vec3::ZERO, Vec3::splat(sub as f32 - 1.0));
            let key = c.x as u32 + dims[0] * (c.y as u32 + dims[1] * c.z as u32);
            (key, f.x as u32 + sub * (f.y as u32 + sub * f.z as u32))
        };
        let mut id_of: HashMap<u32, u32> = HashMap::new();
        let slots_of: Vec<(u32, u32)> = points
            .iter()
            .map(|p| {
                let (key, subcell) = cell_of(*p);
                let next = id_of.len() as u32;
                (*id_of.entry(key).or_insert(next), subcell)
            })
            .collect();
        let total = id_of.len() as u64 * sub3 as u64;
        if total > 50_000_000 {
            return Err(GpuError::TooLarge(format!(
                "{total} sub-cells; use larger buckets"
            )));
        }
        let mut counts = vec![0u32; total as usize];
        for (id, subcell) in &slots_of {
            counts[(id * sub3 + subcell) as usize] += 1;
        }
        let mut start = Vec::with_capacity(counts.len() + 1);
        let mut acc = 0u32;
        start.push(0);
        for c in &counts {
            acc += c;
            start.push(acc);
        }
        let mut fill = start.clone();
        let mut sorted = vec![[0.0f32; 4]; points.len()];
        let mut original = vec![0u32; points.len()];
        let mut sorted_normals = normals.map(|_| vec![[0.0f32; 4]; points.len()]);
        for (i, (p, (id, subcell))) in points.iter().zip(&slots_of).enumerate() {
            let cell = (id * sub3 + subcell) as usize;
            let slot = fill[cell] as usize;
            fill[cell] += 1;
            sorted[slot] = [p.x, p.y, p.z, 1.0];
            original[slot] = i as u32;
            if let (Some(out), Some(n)) = (sorted_normals.as_mut(), normals) {
                let n = n.get(i).copied().unwrap_or(Vec3::ZERO);
                out[slot] = [n.x, n.y, n.z, 0.0];
            }
        }
        let slots = (2 * id_of.len()).next_power_of_two().max(64);
        let mask = slots as u32 - 1;
        let mut keys = vec![NONE; slots];
        let mut vals = vec![0u32; slots];
        let mut entries: Vec<(u32, u32)> = id_of.into_iter().collect();
        entries.sort_unstable();
        for (key, id) in entries {
            let mut s = slot_of(key, mask);
            while keys[s as usize] != NONE {
                s = (s + 1) & mask;
            }
            keys[s as usize] = key;
            vals[s as usize] = id;
        }
        Ok(HostGrid {
            origin,
            bucket_size_m,
            dims,
            sorted,
            original,
            normals: sorted_normals,
            keys,
            vals,
            sub,
            start,
        })
    }
}
