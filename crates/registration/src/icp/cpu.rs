//! The CPU's per-iteration work: correspondences by hinted nearest-neighbour searches (rayon
//! over source points) and the method's reduction to step sums.

use super::correspondences::Correspondences;
use super::{
    gicp, point_to_plane, point_to_point, run_loop, PairSums, PreparedSource, StepSums, Weighting,
};
use crate::config::{IcpConfig, Method};
use crate::covariance::estimate_surface;
use crate::error::Result;
use crate::result::IcpResult;
use crate::target::Target;
use glam::{Affine3A, DAffine3, DMat4, DVec3, Mat3, Vec3};

/// The CPU registration of prepared source points.
pub(crate) fn register_points_cpu(
    target: &Target,
    sensor: Vec3,
    prepared: &PreparedSource,
    guess: DAffine3,
    config: &IcpConfig,
) -> Result<IcpResult> {
    let points = &prepared.points;
    let source_cov = if config.method == Method::Gicp {
        estimate_surface(points, config.source_voxel_m, config, true)?.covariances
    } else {
        Vec::new()
    };
    let mut pairs = CpuPairs {
        config,
        target,
        sensor,
        source: points,
        weights: &prepared.weights,
        source_cov: &source_cov,
        corr: Correspondences::new(points.len()),
    };
    run_loop(config, points, guess, &mut pairs)
}

/// The CPU's correspondences (rayon, hinted grid or k-d tree searches) and reductions.
struct CpuPairs<'a> {
    config: &'a IcpConfig,
    target: &'a Target,
    /// The source's sensor position in the source frame.
    sensor: Vec3,
    source: &'a [Vec3],
    /// Each source point's prior weight (empty: all 1).
    weights: &'a [f32],
    source_cov: &'a [Mat3],
    corr: Correspondences,
}

impl PairSums for CpuPairs<'_> {
    fn pair_sums(
        &mut self,
        t: &DAffine3,
        gate: f64,
        reference: DVec3,
    ) -> Result<(usize, StepSums)> {
        let (c, target) = (self.config, self.target);
        let t32 = Affine3A::from_mat4(DMat4::from(*t).as_mat4());
        self.corr.find(
            target.index(),
            target.points(),
            self.source,
            &t32,
            gate as f32,
            target
                .oriented_normals()
                .filter(|_| c.reject_back_faces)
                .map(|n| (n, t32.transform_point3(self.sensor))),
        );
        let matched = self.corr.matched;
        self.corr.reject_worst(c.reject_worst_fraction);
        let weighting = Weighting {
            kernel: c.kernel,
            prior: self.weights,
        };
        let sums = match c.method {
            Method::PointToPoint => StepSums::Svd(
                point_to_point::accumulate(
                    &self.corr,
                    self.source,
                    target.points(),
                    &t32,
                    weighting,
                    reference,
                ),
                reference,
            ),
            Method::PointToPlane => StepSums::Normal(
                point_to_plane::accumulate(
                    &self.corr,
                    self.source,
                    target.points(),
                    target.normals(),
                    &t32,
                    weighting,
                    reference,
                ),
                reference,
            ),
            // GICP linearises about the origin (its Jacobian uses the absolute moved point).
            Method::Gicp => StepSums::Normal(
                gicp::accumulate(
                    &self.corr,
                    self.source,
                    self.source_cov,
                    target.points(),
                    target.covariances(),
                    t,
                    weighting,
                ),
                DVec3::ZERO,
            ),
        };
        Ok((matched, sums))
    }
}
