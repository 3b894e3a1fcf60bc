//! The correspondence step: for every (transformed) source point the nearest target point
//! within the current gate, in parallel over source points; then the optional rejection of the
//! worst fraction by distance.
//!
//! Buffers live in [`Correspondences`] and are reused across iterations, so the hot loop does
//! not allocate.

use crate::nearest::NearestNeighbors;
use glam::{Affine3A, Vec3, Vec3A};
use rayon::prelude::*;

/// Source points per parallel task.
pub(crate) const CHUNK: usize = 2048;
/// Marks a source point without a correspondence.
pub(crate) const NONE: u32 = u32::MAX;

/// The pairs of one iteration: for source point `i`, `pairs[i] = (target index, squared
/// distance)`, target index [`NONE`] when unmatched or rejected.
pub(crate) struct Correspondences {
    pub pairs: Vec<(u32, f32)>,
    /// Source points with a target point within the gate (before rejection).
    pub matched: usize,
    scratch: Vec<f32>,
}

impl Correspondences {
    pub(crate) fn new(n: usize) -> Self {
        Correspondences {
            pairs: vec![(NONE, 0.0); n],
            matched: 0,
            scratch: Vec::new(),
        }
    }

    /// Finds the nearest target point of each source point moved by `target_from_source`,
    /// within `gate_m`. Each search is hinted with the better of the point's previous
    /// correspondence and the previous source point's match (neighbours in scan order), which
    /// lets the bucket grid prune almost everything.
    ///
    /// With `facing = Some((oriented target normals, sensor position in the target frame))` a
    /// nearest target point whose normal points away from the sensor is no pair (its surface
    /// is seen from behind).
    pub(crate) fn find<N: NearestNeighbors>(
        &mut self,
        index: &N,
        target: &[Vec3],
        source: &[Vec3],
        target_from_source: &Affine3A,
        gate_m: f32,
        facing: Option<(&[Vec3], Vec3)>,
    ) {
        debug_assert_eq!(source.len(), self.pairs.len());
        self.matched = self
            .pairs
            .par_chunks_mut(CHUNK)
            .zip(source.par_chunks(CHUNK))
            .map(|(out, src)| {
                let mut n = 0;
                let mut last = NONE;
                for (o, p) in out.iter_mut().zip(src) {
                    let q = Vec3::from(target_from_source.transform_point3a(Vec3A::from(*p)));
                    let mut hint: Option<(u32, f32)> = None;
                    for j in [o.0, last] {
                        if let Some(t) = target.get(j as usize) {
                            let d2 = (*t - q).length_squared();
                            if hint.is_none_or(|h| d2 < h.1) {
                                hint = Some((j, d2));
                            }
                        }
                    }
                    let hit = index.nearest_with_hint(q, gate_m, hint);
                    let seen = |j: u32| {
                        facing.is_none_or(|(normals, sensor)| {
                            let j = j as usize;
                            normals[j].dot(sensor - target[j]) >= 0.0
                        })
                    };
                    *o = match hit {
                        Some(hit) if seen(hit.0) => {
                            n += 1;
                            last = hit.0;
                            hit
                        }
                        _ => (NONE, 0.0),
                    };
                }
                n
            })
            .sum();
    }

    /// Drops the `fraction` of matched pairs with the largest distances; returns how many
    /// pairs remain.
    pub(crate) fn reject_worst(&mut self, fraction: f64) -> usize {
        let keep = ((1.0 - fraction) * self.matched as f64).ceil() as usize;
        if fraction <= 0.0 || keep >= self.matched || keep == 0 {
            return self.matched;
        }
        self.scratch.clear();
        self.scratch
            .extend(self.pairs.iter().filter(|p| p.0 != NONE).map(|p| p.1));
        let (_, threshold, _) = self
            .scratch
            .select_nth_unstable_by(keep - 1, f32::total_cmp);
        let threshold = *threshold;
        let mut kept = 0;
        for p in &mut self.pairs {
            if p.0 != NONE {
                if p.1 > threshold || kept == keep {
                    *p = (NONE, 0.0);
                } else {
                    kept += 1;
                }
            }
        }
        kept
    }

    /// Parallel fold over the accepted pairs: `add(acc, source index, target index, d2)`.
    pub(crate) fn fold<S, A, M>(&self, identity: S, add: A, merge: M) -> S
    where
        S: Send + Clone + Sync,
        A: Fn(&mut S, usize, u32, f32) + Sync,
        M: Fn(S, S) -> S + Sync,
    {
        self.pairs
            .par_chunks(CHUNK)
            .enumerate()
            .map(|(c, chunk)| {
                let mut acc = identity.clone();
                for (k, &(j, d2)) in chunk.iter().enumerate() {
                    if j != NONE {
                        add(&mut acc, c * CHUNK + k, j, d2);
                    }
                }
                acc
            })
            .reduce(|| identity.clone(), &merge)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nearest::kdtree::KdTree;

    #[test]
    fn finds_gates_and_rejects_the_worst() {
        let target: Vec<Vec3> = (0..10).map(|i| Vec3::new(i as f32, 0.0, 0.0)).collect();
        let tree = KdTree::new(&target);
        // Source points 0.0, 0.1, ..., 0.9 off the target points, plus one far away.
        let mut source: Vec<Vec3> = (0..10)
            .map(|i| Vec3::new(i as f32, 0.1 * i as f32 / 2.0, 0.0))
            .collect();
        source.push(Vec3::new(50.0, 0.0, 0.0));
        let mut c = Correspondences::new(source.len());
        c.find(&tree, &target, &source, &Affine3A::IDENTITY, 0.42, None);
        assert_eq!(c.matched, 9);
        assert_eq!(c.pairs[3].0, 3);
        assert_eq!(c.pairs[10].0, NONE);
        assert_eq!(c.reject_worst(0.34), 6);
        assert!(c.pairs[..6].iter().all(|p| p.0 != NONE));
        assert!(c.pairs[6..].iter().all(|p| p.0 == NONE));
        let sum = c.fold(
            0usize,
            |a, i, j, _| *a += (i == j as usize) as usize,
            |a, b| a + b,
        );
        assert_eq!(sum, 6);
        // Moving the source moves the matches.
        let shift = Affine3A::from_translation(Vec3::new(1.0, 0.0, 0.0));
        c.find(&tree, &target, &source, &shift, 0.42, None);
        assert_eq!(c.pairs[0].0, 1);
        assert_eq!(c.pairs[9].0, NONE);
    }
}
