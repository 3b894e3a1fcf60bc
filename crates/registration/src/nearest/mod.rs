//! The nearest-neighbour interface shared by the bucket grid and the k-d tree, and the
//! backend chosen by the configuration.

pub(crate) mod grid;
pub(crate) mod kdtree;

use crate::config::NnBackend;
use crate::error::Result;
use glam::Vec3;
use grid::BucketGrid;
use kdtree::KdTree;

/// A nearest-neighbour structure over a fixed set of points (the target).
pub trait NearestNeighbors: Sync {
    /// The index of the point nearest to `query` and its **squared** distance, if one lies
    /// within `max_distance_m` (strictly).
    fn nearest(&self, query: Vec3, max_distance_m: f32) -> Option<(u32, f32)>;

    /// As [`NearestNeighbors::nearest`], given a candidate already known:
    /// `hint = (index, squared distance to the query)`. The answer is the same (up to ties);
    /// a structure may use the hint as an initial bound to prune its search (the bucket grid
    /// does, the k-d tree ignores it).
    fn nearest_with_hint(
        &self,
        query: Vec3,
        max_distance_m: f32,
        hint: Option<(u32, f32)>,
    ) -> Option<(u32, f32)> {
        let _ = hint;
        self.nearest(query, max_distance_m)
    }

    /// Number of points indexed.
    fn len(&self) -> usize;

    /// True if no point is indexed.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// The configured backend over a target's points.
pub(crate) enum NnIndex {
    Grid(BucketGrid),
    KdTree(KdTree),
}

impl NnIndex {
    /// Builds the backend over `points`.
    pub(crate) fn build(points: &[Vec3], backend: NnBackend, bucket_size_m: f64) -> Result<Self> {
        Ok(match backend {
            NnBackend::Grid => NnIndex::Grid(BucketGrid::new(points, bucket_size_m)?),
            NnBackend::KdTree => NnIndex::KdTree(KdTree::new(points)),
        })
    }
}

impl NearestNeighbors for NnIndex {
    #[inline]
    fn nearest(&self, query: Vec3, max_distance_m: f32) -> Option<(u32, f32)> {
        match self {
            NnIndex::Grid(g) => g.nearest(query, max_distance_m),
            NnIndex::KdTree(t) => t.nearest(query, max_distance_m),
        }
    }

    #[inline]
    fn nearest_with_hint(
        &self,
        query: Vec3,
        max_distance_m: f32,
        hint: Option<(u32, f32)>,
    ) -> Option<(u32, f32)> {
        match self {
            NnIndex::Grid(g) => g.nearest_with_hint(query, max_distance_m, hint),
            NnIndex::KdTree(t) => t.nearest(query, max_distance_m),
        }
    }

    fn len(&self) -> usize {
        match self {
            NnIndex::Grid(g) => g.len(),
            NnIndex::KdTree(t) => t.len(),
        }
    }
}
