//! The point-to-plane step (Chen & Medioni 1991; Low 2004's linearisation): minimise
//! `Σ w (n_i · (R d_i + t - m_i))^2` over a small rotation vector `ω` and translation `t`.
//! With `R ≈ I + [ω]×` the residual is linear, `r_i = n_i·(d_i - m_i) + (d_i × n_i)·ω + n_i·t`,
//! so each pair adds `J^T J` with `J = [d_i × n_i, n_i]` to the 6x6 normal equations, solved
//! per iteration; the increment (exact rotation of `ω`, then `t`) is composed onto the
//! current transform.

use super::correspondences::Correspondences;
use super::Weighting;
use crate::linalg::System6;
use glam::{Affine3A, DVec3, Vec3, Vec3A};

/// Accumulates the normal equations over the accepted pairs whose target has a normal,
/// linearised about `reference`: the Jacobian is `J = [(d - reference) × n, n]`, so the solved
/// increment rotates about `reference` (as the GPU kernels do; a reference near the points also
/// keeps the system well conditioned).
pub(crate) fn accumulate(
    corr: &Correspondences,
    source: &[Vec3],
    target: &[Vec3],
    normals: &[Vec3],
    target_from_source: &Affine3A,
    weighting: Weighting<'_>,
    reference: DVec3,
) -> System6 {
    corr.fold(
        System6::default(),
        |acc, i, j, d2| {
            let n = normals[j as usize];
            if n == Vec3::ZERO {
                return;
            }
            let d = Vec3::from(target_from_source.transform_point3a(Vec3A::from(source[i])));
            let (d, m, n) = (d.as_dvec3(), target[j as usize].as_dvec3(), n.as_dvec3());
            let r = n.dot(d - m);
            let w = weighting.of(i, r);
            let c = (d - reference).cross(n);
            acc.add_row(&[c.x, c.y, c.z, n.x, n.y, n.z], r, w);
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
    use crate::icp::correspondences::NONE;
    use crate::linalg::increment;
    use glam::{DAffine3, DQuat};

    #[test]
    fn steps_converge_on_three_planes() {
        // Three orthogonal planes (a room corner), the source moved by a small known motion.
        let mut target = Vec::new();
        let mut normals = Vec::new();
        for i in 0..20 {
            for j in 0..20 {
                let (a, b) = (i as f32 * 0.1, j as f32 * 0.1);
                for (p, n) in [
                    (Vec3::new(a, b, 0.0), Vec3::Z),
                    (Vec3::new(a, 0.0, b), Vec3::Y),
                    (Vec3::new(0.0, a, b), Vec3::X),
                ] {
                    target.push(p);
                    normals.push(n);
                }
            }
        }
        let truth = DAffine3::from_rotation_translation(
            DQuat::from_euler(glam::EulerRot::ZYX, 0.02, 0.01, -0.015),
            DVec3::new(0.03, -0.02, 0.01),
        );
        // source = truth^-1 * target, same indexing: pairs are known.
        let inv = truth.inverse();
        let source: Vec<Vec3> = target
            .iter()
            .map(|p| inv.transform_point3(p.as_dvec3()).as_vec3())
            .collect();
        let mut corr = Correspondences::new(source.len());
        for (k, p) in corr.pairs.iter_mut().enumerate() {
            *p = (k as u32, 0.0);
        }
        corr.matched = source.len();
        let mut t = DAffine3::IDENTITY;
        for _ in 0..5 {
            let a = Affine3A::from_mat4(glam::DMat4::from(t).as_mat4());
            let sys = accumulate(
                &corr,
                &source,
                &target,
                &normals,
                &a,
                RobustKernel::None.into(),
                DVec3::ZERO,
            );
            assert_eq!(sys.pairs, source.len());
            t = increment(&sys.solve().expect("solvable")) * t;
        }
        assert!(t.abs_diff_eq(truth, 1e-5), "{t:?}");
        corr.pairs[0].0 = NONE;
        let a = Affine3A::IDENTITY;
        assert_eq!(
            accumulate(
                &corr,
                &source,
                &target,
                &normals,
                &a,
                RobustKernel::None.into(),
                DVec3::ZERO
            )
            .pairs,
            source.len() - 1
        );
    }
}
