//! The Generalized-ICP step (Segal, Haehnel & Thrun 2009, "plane-to-plane"), as small_gicp
//! implements it: each pair's residual `e = m_i - T d_i` is weighted by the inverse of the
//! combined covariance `C_m + R C_d R^T` (the plane-regularised covariances of
//! [`crate::covariance`]), and the Mahalanobis cost `Σ e^T (C_m + R C_d R^T)^-1 e` is minimised
//! by Gauss-Newton on SE(3): with the increment `exp(ξ)` applied on the left, `ξ = (ω, v)`, the
//! Jacobian of `e` at the moved point `p = T d_i` is `J = [[p]×, -I]`, and each pair adds
//! `J^T M J` and `J^T M e` to the 6x6 normal equations.

use super::correspondences::Correspondences;
use super::Weighting;
use crate::linalg::{skew, System6};
use glam::{DAffine3, Mat3, Vec3};

/// Accumulates the Gauss-Newton system over the accepted pairs whose target has a covariance.
/// `source_cov` may hold zero matrices (a source point without a usable neighbourhood is then
/// treated as an exact point).
pub(crate) fn accumulate(
    corr: &Correspondences,
    source: &[Vec3],
    source_cov: &[Mat3],
    target: &[Vec3],
    target_cov: &[Mat3],
    target_from_source: &DAffine3,
    weighting: Weighting<'_>,
) -> System6 {
    let r = target_from_source.matrix3;
    corr.fold(
        System6::default(),
        |acc, i, j, d2| {
            let ct = target_cov[j as usize];
            if ct == Mat3::ZERO {
                return;
            }
            let p = target_from_source.transform_point3(source[i].as_dvec3());
            let e = target[j as usize].as_dvec3() - p;
            let c = ct.as_dmat3() + r * source_cov[i].as_dmat3() * r.transpose();
            let det = c.determinant();
            if det.abs() <= 1e-18 || det.is_nan() {
                return;
            }
            let w = weighting.of(i, (d2 as f64).sqrt());
            let m = c.inverse() * w;
            // J = [P, -I] with P = [p]x (and P^T = -P): J^T M J = [[-P M P, P M], [-M P, M]],
            // J^T M e = (-p x (M e), -M e).
            let pm = skew(p);
            let me = m * e;
            acc.add_blocks(&(-(pm * m * pm)), &(pm * m), &m, -p.cross(me), -me);
            acc.sq_dist += d2 as f64;
            acc.pairs += 1;
        },
        System6::merge,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::RobustKernel;
    use crate::linalg::increment;
    use glam::{DQuat, DVec3};

    #[test]
    fn gauss_newton_converges_on_a_room_corner() {
        let mut target = Vec::new();
        let mut covs = Vec::new();
        let plane_cov =
            |n: Vec3| Mat3::IDENTITY - (1.0 - 1e-3) * Mat3::from_cols(n * n.x, n * n.y, n * n.z);
        for i in 0..15 {
            for j in 0..15 {
                let (a, b) = (i as f32 * 0.1, j as f32 * 0.1);
                for (p, n) in [
                    (Vec3::new(a, b, 0.0), Vec3::Z),
                    (Vec3::new(a, 0.0, b), Vec3::Y),
                    (Vec3::new(0.0, a, b), Vec3::X),
                ] {
                    target.push(p);
                    covs.push(plane_cov(n));
                }
            }
        }
        let truth = DAffine3::from_rotation_translation(
            DQuat::from_euler(glam::EulerRot::ZYX, -0.03, 0.02, 0.01),
            DVec3::new(-0.02, 0.04, 0.015),
        );
        let inv = truth.inverse();
        let source: Vec<Vec3> = target
            .iter()
            .map(|p| inv.transform_point3(p.as_dvec3()).as_vec3())
            .collect();
        let src_cov: Vec<Mat3> = covs
            .iter()
            .map(|c| (inv.matrix3 * c.as_dmat3() * inv.matrix3.transpose()).as_mat3())
            .collect();
        let mut corr = Correspondences::new(source.len());
        for (k, p) in corr.pairs.iter_mut().enumerate() {
            *p = (k as u32, 0.0);
        }
        corr.matched = source.len();
        let mut t = DAffine3::IDENTITY;
        for _ in 0..6 {
            let sys = accumulate(
                &corr,
                &source,
                &src_cov,
                &target,
                &covs,
                &t,
                RobustKernel::Huber { k_m: 0.5 }.into(),
            );
            t = increment(&sys.solve().expect("solvable")) * t;
        }
        assert!(t.abs_diff_eq(truth, 1e-5), "{t:?}");
    }
}
