//! The point-to-point step of the 2009 paper: the closed-form rigid transform that best maps
//! the (already moved) source points `d_i` onto their corresponding target ("model") points
//! `m_i` in the least-squares sense (Arun, Huang & Blostein 1987; Horn 1987; Umeyama 1991).
//!
//! 1. Centroids `c_d = Σ w d_i / W`, `c_m = Σ w m_i / W`.
//! 2. The 3x3 correlation matrix `H = Σ w (d_i - c_d)(m_i - c_m)^T`, accumulated in f64 as
//!    `Σ w d m^T - W c_d c_m^T` by a parallel reduction.
//! 3. Its SVD `H = U S V^T`; the rotation is `R = V U^T`. If `det(R) < 0` the best orthogonal
//!    matrix is a reflection (planar or very noisy pairs): flip the singular vector of the
//!    smallest singular value, `R = V diag(1, 1, -1) U^T` (Umeyama's correction).
//! 4. The translation `t = c_m - R c_d`.

use super::correspondences::Correspondences;
use super::Weighting;
use crate::linalg::svd3;
use glam::{Affine3A, DAffine3, DMat3, DVec3, Vec3, Vec3A};

/// Weighted sums for the closed-form step.
#[derive(Clone, Copy, Debug)]
pub(crate) struct CorrelationSums {
    pub weight: f64,
    pub sum_d: DVec3,
    pub sum_m: DVec3,
    /// `Σ w d m^T`.
    pub sum_dm: DMat3,
    /// Sum of squared (unweighted) distances.
    pub sq_dist: f64,
    pub pairs: usize,
}

impl Default for CorrelationSums {
    fn default() -> Self {
        // Not derived: `DMat3::default()` is the identity.
        CorrelationSums {
            weight: 0.0,
            sum_d: DVec3::ZERO,
            sum_m: DVec3::ZERO,
            sum_dm: DMat3::ZERO,
            sq_dist: 0.0,
            pairs: 0,
        }
    }
}

impl CorrelationSums {
    /// Adds the pair (source point `d`, model point `m`) with weight `w`.
    #[inline]
    pub(crate) fn add(&mut self, d: DVec3, m: DVec3, w: f64) {
        self.weight += w;
        self.sum_d += w * d;
        self.sum_m += w * m;
        let wm = w * m;
        self.sum_dm += DMat3::from_cols(d * wm.x, d * wm.y, d * wm.z);
        self.sq_dist += d.distance_squared(m);
        self.pairs += 1;
    }

    /// Sums two partial sums.
    pub(crate) fn merge(mut self, o: CorrelationSums) -> CorrelationSums {
        self.weight += o.weight;
        self.sum_d += o.sum_d;
        self.sum_m += o.sum_m;
        self.sum_dm += o.sum_dm;
        self.sq_dist += o.sq_dist;
        self.pairs += o.pairs;
        self
    }

    /// The rigid transform (`model_from_data`) minimising the weighted squared distances,
    /// `None` for fewer than three pairs or a non-finite result.
    pub(crate) fn solve(&self) -> Option<DAffine3> {
        if self.pairs < 3 || self.weight <= 0.0 {
            return None;
        }
        // Step 1: centroids.
        let c_d = self.sum_d / self.weight;
        let c_m = self.sum_m / self.weight;
        // Step 2: correlation matrix H = Σ w (d - c_d)(m - c_m)^T.
        let centred = DMat3::from_cols(c_d * c_m.x, c_d * c_m.y, c_d * c_m.z) * self.weight;
        let h = self.sum_dm - centred;
        // Step 3: SVD H = U S V^T, R = V U^T with the reflection guard.
        let (u, _s, mut v) = svd3(h);
        if (v * u.transpose()).determinant() < 0.0 {
            // Singular values are in decreasing order: flip the last right singular vector.
            v.z_axis = -v.z_axis;
        }
        let r = v * u.transpose();
        // Step 4: t = c_m - R c_d.
        let t = c_m - r * c_d;
        let out = DAffine3::from_mat3_translation(r, t);
        out.is_finite().then_some(out)
    }
}

/// Accumulates the sums over the accepted pairs of `corr`; the source points are moved by
/// `target_from_source` first, and both points of a pair are taken relative to `reference`
/// (so the step solved from the sums is in a frame centred there).
pub(crate) fn accumulate(
    corr: &Correspondences,
    source: &[Vec3],
    target: &[Vec3],
    target_from_source: &Affine3A,
    weighting: Weighting<'_>,
    reference: DVec3,
) -> CorrelationSums {
    corr.fold(
        CorrelationSums::default(),
        |acc, i, j, d2| {
            let d = target_from_source.transform_point3a(Vec3A::from(source[i]));
            let w = weighting.of(i, (d2 as f64).sqrt());
            acc.add(
                Vec3::from(d).as_dvec3() - reference,
                target[j as usize].as_dvec3() - reference,
                w,
            );
        },
        CorrelationSums::merge,
    )
}

/// The least-squares rigid transform `target_from_source` mapping `source[i]` onto
/// `target[i]` (equal weights), by the closed-form step above.
#[cfg(test)]
pub(crate) fn best_rigid_transform(source: &[DVec3], target: &[DVec3]) -> Option<DAffine3> {
    let mut s = CorrelationSums::default();
    for (d, m) in source.iter().zip(target) {
        s.add(*d, *m, 1.0);
    }
    s.solve()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DQuat;

    fn truth() -> DAffine3 {
        DAffine3::from_rotation_translation(
            DQuat::from_euler(glam::EulerRot::ZYX, 0.7, -0.2, 0.1),
            DVec3::new(1.5, -0.3, 2.0),
        )
    }

    #[test]
    fn recovers_a_known_transform_from_perfect_pairs() {
        let src: Vec<DVec3> = (0..50)
            .map(|i| {
                let f = i as f64;
                DVec3::new((f * 0.37).sin() * 5.0, (f * 0.11).cos() * 3.0, f * 0.05)
            })
            .collect();
        let t = truth();
        let dst: Vec<DVec3> = src.iter().map(|p| t.transform_point3(*p)).collect();
        let got = best_rigid_transform(&src, &dst).expect("solvable");
        assert!(got.abs_diff_eq(t, 1e-9), "{got:?}");
        assert!((got.matrix3.determinant() - 1.0).abs() < 1e-9);
    }

    #[test]
    fn coplanar_pairs_do_not_give_a_reflection() {
        // Points on the plane z = 0: H has rank 2 and a careless R = V U^T may be a reflection.
        let src: Vec<DVec3> = [(0.0, 0.0), (1.0, 0.0), (0.0, 2.0), (3.0, 1.0), (-1.0, 1.5)]
            .iter()
            .map(|&(x, y)| DVec3::new(x, y, 0.0))
            .collect();
        for t in [truth(), DAffine3::from_rotation_x(std::f64::consts::PI)] {
            let dst: Vec<DVec3> = src.iter().map(|p| t.transform_point3(*p)).collect();
            let got = best_rigid_transform(&src, &dst).expect("solvable");
            assert!((got.matrix3.determinant() - 1.0).abs() < 1e-9);
            assert!(got.abs_diff_eq(t, 1e-9), "{got:?} vs {t:?}");
        }
    }

    #[test]
    fn mirrored_pairs_give_the_best_rotation_not_the_mirror() {
        // The target is the source mirrored in x: the unconstrained optimum is a reflection.
        let src: Vec<DVec3> = [
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(2.0, 1.0, 0.0),
            DVec3::new(3.0, 0.0, 1.0),
            DVec3::new(1.5, 2.0, 2.0),
        ]
        .to_vec();
        let dst: Vec<DVec3> = src.iter().map(|p| DVec3::new(-p.x, p.y, p.z)).collect();
        let got = best_rigid_transform(&src, &dst).expect("solvable");
        assert!((got.matrix3.determinant() - 1.0).abs() < 1e-9, "{got:?}");
        let r = got.matrix3;
        assert!((r.transpose() * r).abs_diff_eq(DMat3::IDENTITY, 1e-9));
    }

    #[test]
    fn too_few_pairs_is_none() {
        assert!(best_rigid_transform(&[DVec3::ZERO, DVec3::X], &[DVec3::ZERO, DVec3::X]).is_none());
    }
}
