//! What one GPU iteration gives back: the point-to-point sums or the point-to-plane normal
//! equations, the robust kernel they were weighted with, and the time each stage took.

/// Robust kernel for point-to-plane (IRLS weight computed on the GPU).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GpuKernel {
    /// Plain least squares.
    None,
    /// Huber with width `k` metres.
    Huber(f32),
    /// Cauchy with width `k` metres.
    Cauchy(f32),
}

/// Wall-clock split of one GPU iteration, in milliseconds. Without stage timing (see
/// [`GpuIcp::set_stage_timing`](super::GpuIcp::set_stage_timing)) everything after the upload counts as `search_ms`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StageTimes {
    /// Writing the parameters (and, on the first iteration, the data points).
    pub upload_ms: f64,
    /// The nearest-neighbour search with the per-workgroup reduction.
    pub search_ms: f64,
    /// The final reduction of the workgroup partials.
    pub reduce_ms: f64,
    /// Copying the sums back and mapping them.
    pub download_ms: f64,
}

/// Point-to-point sums over the accepted pairs (transformed data point p, model point q),
/// both centred on the `reference` point given, each pair weighted by the robust kernel `w` of
/// its distance (1 without a kernel): count, sum w p, sum w q, sum w p q^T, sum |p - q|^2, sum w.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct P2pSums {
    /// Pairs.
    pub count: f64,
    /// Sum of w (p - reference).
    pub sum_p: [f64; 3],
    /// Sum of w (q - reference).
    pub sum_q: [f64; 3],
    /// Sum of w (p - reference)(q - reference)^T, row-major.
    pub sum_pq: [f64; 9],
    /// Sum of squared distances (unweighted).
    pub sum_d2: f64,
    /// Sum of the weights (equals `count` without a kernel).
    pub weight: f64,
}

/// Point-to-plane normal equations over the accepted pairs, linearised about `reference`:
/// upper triangle of J^T W J (21, row-major), J^T W r (6), sum of w r^2, pair count, sum of
/// squared point distances.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneSystem {
    /// Pairs.
    pub count: f64,
    /// Upper triangle of J^T W J, row by row.
    pub jtj_upper: [f64; 21],
    /// J^T W r.
    pub jtr: [f64; 6],
    /// Sum of w r^2.
    pub sum_wr2: f64,
    /// Sum of the squared point (not plane) distances of the pairs.
    pub sum_d2: f64,
}
