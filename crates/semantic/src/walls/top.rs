//! Whether a wall prerequisite's face reaches up to the ceiling, stretch by stretch. A wall's
//! face is seen as densely near the ceiling as lower down (at most a few times sparser: the
//! beams meet it more steeply there); a door leaf standing open, a cupboard or a partition
//! stops short of it, and the few returns a real laser leaves above such a top edge (mixed
//! pixels between the edge and the ceiling behind it, along rays that graze the face) are a
//! small fraction of what its face holds lower down. A duct or a pipe in front of a wall's top
//! hides it from the laser as sparsely, so the test is asked only of faces with no free space
//! seen in front of them (see `fit`).

/// Height of the bands whose face points are counted (m).
const BAND_M: f64 = 0.25;
/// The most bands counted per stretch (a 16 m high hall).
const MAX_BANDS: usize = 64;
/// A stretch reaches the top if its top band holds at least this fraction of the points of its
/// typical band (the median of the bands below that hold any).
const TOP_SHARE: f64 = 0.25;

/// Face points per stretch of a prerequisite and per height band, from `z_lo` up to the top
/// band (from `top_from` up).
pub(super) struct TopReach {
    z_lo: f64,
    top_from: f64,
    bands: usize,
    counts: Vec<u32>,
    top: Vec<u32>,
}

impl TopReach {
    /// Counts for `stretches` stretches; the bands below the top one run from `z_lo` to
    /// `top_from`.
    pub fn new(stretches: usize, z_lo: f64, top_from: f64) -> TopReach {
        let bands = (((top_from - z_lo) / BAND_M).ceil().max(1.0) as usize).min(MAX_BANDS);
        TopReach {
            z_lo,
            top_from,
            bands,
            counts: vec![0; stretches * bands],
            top: vec![0; stretches],
        }
    }

    /// A face point at height `z` in stretch `b`.
    pub fn add(&mut self, b: usize, z: f64) {
        if b >= self.top.len() {
            return;
        }
        if z >= self.top_from {
            self.top[b] += 1;
        } else if z >= self.z_lo {
            let k = (((z - self.z_lo) / BAND_M) as usize).min(self.bands - 1);
            self.counts[b * self.bands + k] += 1;
        }
    }

    /// The fraction of the stretches whose top band holds any face point.
    pub fn any_fraction(&self) -> f64 {
        let reached = self.top.iter().filter(|&&n| n > 0).count();
        reached as f64 / self.top.len().max(1) as f64
    }

    /// The fraction of the stretches whose top band holds face points, at least
    /// [`TOP_SHARE`] of their typical band below.
    pub fn dense_fraction(&self) -> f64 {
        let reached = (0..self.top.len())
            .filter(|&b| {
                let mut seen: Vec<u32> = self.counts[b * self.bands..(b + 1) * self.bands]
                    .iter()
                    .copied()
                    .filter(|&n| n > 0)
                    .collect();
                seen.sort_unstable();
                let typical = seen.get(seen.len() / 2).copied().unwrap_or(0);
                self.top[b] > 0 && self.top[b] as f64 >= TOP_SHARE * typical as f64
            })
            .count();
        reached as f64 / self.top.len().max(1) as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `n` face points per 5 cm of height from `z0` to `z1` in stretch `b`.
    fn face(t: &mut TopReach, b: usize, z0: f64, z1: f64, n: usize) {
        let mut z = z0;
        while z < z1 {
            for _ in 0..n {
                t.add(b, z);
            }
            z += 0.05;
        }
    }

    #[test]
    fn a_face_up_to_the_ceiling_reaches_it_a_door_leaf_with_mixed_pixels_over_it_does_not() {
        // Floor at 0, ceiling at 2.6: the top band from 2.3 m.
        let mut t = TopReach::new(4, 0.05, 2.3);
        // A wall's face, seen twice as sparsely near the ceiling.
        face(&mut t, 0, 0.05, 2.3, 4);
        face(&mut t, 0, 2.3, 2.55, 2);
        // A glass wall: one return per 5 cm.
        face(&mut t, 1, 0.05, 2.55, 1);
        // A door leaf 2.07 m high with 3 mixed pixels over its top edge.
        face(&mut t, 2, 0.05, 2.07, 4);
        face(&mut t, 2, 2.35, 2.5, 1);
        // A wall behind a cabinet: nothing seen below 1.9 m.
        face(&mut t, 3, 1.9, 2.55, 4);
        assert_eq!(t.dense_fraction(), 0.75);
        let mut leaf = TopReach::new(1, 0.05, 2.3);
        face(&mut leaf, 0, 0.05, 2.07, 4);
        face(&mut leaf, 0, 2.35, 2.5, 1);
        assert_eq!(leaf.dense_fraction(), 0.0);
        assert_eq!(leaf.any_fraction(), 1.0);
    }
}
