//! An exact k-d tree (kiddo 6's immutable tree) for nearest-neighbour and k-nearest queries.

use super::NearestNeighbors;
use glam::Vec3;
use kiddo::{ImmutableKdTree, SquaredEuclidean};
use std::num::NonZeroUsize;

/// An exact k-d tree over a point set. Non-finite points are not indexed; results index the
/// slice given to [`KdTree::new`].
pub struct KdTree {
    tree: Option<ImmutableKdTree<f32, 3>>,
    /// Input index of each indexed point (None when every point was finite).
    remap: Option<Vec<u32>>,
    len: usize,
}

impl KdTree {
    /// Builds the tree over the finite points of `points`.
    pub fn new(points: &[Vec3]) -> KdTree {
        let all_finite = points.iter().all(|p| p.is_finite());
        let (coords, remap): (Vec<[f32; 3]>, Option<Vec<u32>>) = if all_finite {
            (points.iter().map(|p| p.to_array()).collect(), None)
        } else {
            let (c, r) = points
                .iter()
                .enumerate()
                .filter(|(_, p)| p.is_finite())
                .map(|(i, p)| (p.to_array(), i as u32))
                .unzip();
            (c, Some(r))
        };
        let len = coords.len();
        let tree = if coords.is_empty() {
            None
        } else {
            ImmutableKdTree::new_from_slice(&coords).ok()
        };
        KdTree { tree, remap, len }
    }

    #[inline]
    fn input_index(&self, item: u32) -> u32 {
        match &self.remap {
            Some(r) => r[item as usize],
            None => item,
        }
    }

    /// Appends to `out` the indices of (at most) the `k` nearest points to `query` within
    /// `radius_m`, unsorted. `out` is cleared first.
    pub fn k_nearest(&self, query: Vec3, k: usize, radius_m: f32, out: &mut Vec<u32>) {
        out.clear();
        let (Some(tree), Some(k)) = (&self.tree, NonZeroUsize::new(k)) else {
            return;
        };
        let found = tree
            .query(&query.to_array())
            .nearest_n::<SquaredEuclidean<f32>>(k)
            .within(radius_m * radius_m)
            .unsorted()
            .execute();
        out.extend(found.iter().map(|r| self.input_index(r.item)));
    }
}

impl std::fmt::Debug for KdTree {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("KdTree").field("points", &self.len).finish()
    }
}

impl NearestNeighbors for KdTree {
    #[inline]
    fn nearest(&self, query: Vec3, max_distance_m: f32) -> Option<(u32, f32)> {
        let tree = self.tree.as_ref()?;
        let r = tree
            .query(&query.to_array())
            .nearest_one::<SquaredEuclidean<f32>>()
            .execute();
        (r.distance < max_distance_m * max_distance_m)
            .then(|| (self.input_index(r.item), r.distance))
    }

    fn len(&self) -> usize {
        self.len
    }
}
