//! Small dense linear algebra for the steps, in f64: the 3x3 SVD of the point-to-point step
//! (one-sided Jacobi, accurate to machine precision also for rank-deficient matrices), the 6x6
//! normal equations of the linearised methods with their Cholesky solution, and the increment
//! they describe.

// Dense matrix code reads best with index loops.
#![allow(clippy::needless_range_loop)]

use glam::{DAffine3, DMat3, DQuat, DVec3};

/// Accumulated Gauss-Newton normal equations `H x = -b` over 6 parameters
/// (rotation vector first, then translation), with the pairs' summed squared distances.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct System6 {
    /// `H`, upper triangle only (row <= column) until solved.
    pub h: [[f64; 6]; 6],
    pub b: [f64; 6],
    /// Sum of squared point distances of the pairs (for the RMSE).
    pub sq_dist: f64,
    /// Pairs summed.
    pub pairs: usize,
}

impl System6 {
    /// Adds `w j j^T` to `H` and `w r j` to `b`.
    #[inline]
    pub(crate) fn add_row(&mut self, j: &[f64; 6], r: f64, w: f64) {
        for a in 0..6 {
            let wa = w * j[a];
            for b in a..6 {
                self.h[a][b] += wa * j[b];
            }
            self.b[a] += wa * r;
        }
    }

    /// Adds the 6x6 block matrix `[[hww, hwv], [hwv^T, hvv]]` (upper triangle) and `(bw, bv)`.
    #[inline]
    pub(crate) fn add_blocks(
        &mut self,
        hww: &DMat3,
        hwv: &DMat3,
        hvv: &DMat3,
        bw: DVec3,
        bv: DVec3,
    ) {
        for r in 0..3 {
            for c in 0..3 {
                if c >= r {
                    self.h[r][c] += hww.col(c)[r];
                    self.h[r + 3][c + 3] += hvv.col(c)[r];
                }
                self.h[r][c + 3] += hwv.col(c)[r];
            }
            self.b[r] += bw[r];
            self.b[r + 3] += bv[r];
        }
    }

    /// Sums two partial systems.
    pub(crate) fn merge(mut self, o: System6) -> System6 {
        for a in 0..6 {
            for b in 0..6 {
                self.h[a][b] += o.h[a][b];
            }
            self.b[a] += o.b[a];
        }
        self.sq_dist += o.sq_dist;
        self.pairs += o.pairs;
        self
    }

    /// Solves `H x = -b` by Cholesky, adding a small damping (Levenberg) if `H` is not
    /// positive definite; `None` if even that fails.
    pub(crate) fn solve(&self) -> Option<[f64; 6]> {
        let mut full = self.h;
        for a in 0..6 {
            for b in 0..a {
                full[a][b] = full[b][a];
            }
        }
        let rhs = self.b.map(|v| -v);
        if let Some(x) = cholesky_solve(full, rhs) {
            return Some(x);
        }
        let scale = (0..6).map(|i| full[i][i].abs()).fold(0.0, f64::max);
        if !(scale > 0.0 && scale.is_finite()) {
            return None;
        }
        for (i, row) in full.iter_mut().enumerate() {
            row[i] += scale * 1e-9;
        }
        cholesky_solve(full, rhs)
    }
}

/// Solves `a x = rhs` for symmetric positive definite `a`.
fn cholesky_solve(a: [[f64; 6]; 6], rhs: [f64; 6]) -> Option<[f64; 6]> {
    let mut l = [[0.0f64; 6]; 6];
    for i in 0..6 {
        for j in 0..=i {
            let mut s = a[i][j];
            for k in 0..j {
                s -= l[i][k] * l[j][k];
            }
            if i == j {
                if s <= 0.0 || s.is_nan() {
                    return None;
                }
                l[i][i] = s.sqrt();
            } else {
                l[i][j] = s / l[j][j];
            }
        }
    }
    let mut y = [0.0f64; 6];
    for i in 0..6 {
        let s: f64 = (0..i).map(|k| l[i][k] * y[k]).sum();
        y[i] = (rhs[i] - s) / l[i][i];
    }
    let mut x = [0.0f64; 6];
    for i in (0..6).rev() {
        let s: f64 = (i + 1..6).map(|k| l[k][i] * x[k]).sum();
        x[i] = (y[i] - s) / l[i][i];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// The rigid increment of a 6-vector `(rotation vector, translation)`: rotate by the exact
/// rotation of the rotation vector about the origin, then translate.
pub(crate) fn increment(x: &[f64; 6]) -> DAffine3 {
    let omega = DVec3::new(x[0], x[1], x[2]);
    let v = DVec3::new(x[3], x[4], x[5]);
    DAffine3::from_rotation_translation(DQuat::from_scaled_axis(omega), v)
}

/// Translation length and rotation angle (degrees) of a rigid transform.
pub(crate) fn motion_size(t: &DAffine3) -> (f64, f64) {
    let q = DQuat::from_mat3(&t.matrix3);
    let angle = 2.0 * q.w.abs().min(1.0).acos();
    (t.translation.length(), angle.to_degrees())
}

/// The skew-symmetric matrix `[p]×` with `[p]× v = p × v`.
#[inline]
pub(crate) fn skew(p: DVec3) -> DMat3 {
    DMat3::from_cols(
        DVec3::new(0.0, p.z, -p.y),
        DVec3::new(-p.z, 0.0, p.x),
        DVec3::new(p.y, -p.x, 0.0),
    )
}

/// The singular value decomposition `m = U diag(s) V^T` of a 3x3 matrix by one-sided Jacobi
/// (Hestenes) rotations: singular values in decreasing order, `U` and `V` orthogonal. For a
/// rank-deficient `m` the missing left singular vectors complete `U` to a rotation.
pub(crate) fn svd3(m: DMat3) -> (DMat3, DVec3, DMat3) {
    let mut a = [m.x_axis, m.y_axis, m.z_axis];
    let mut v = [DVec3::X, DVec3::Y, DVec3::Z];
    for _sweep in 0..64 {
        let mut rotated = false;
        for (i, j) in [(0usize, 1usize), (0, 2), (1, 2)] {
            let alpha = a[i].length_squared();
            let beta = a[j].length_squared();
            let gamma = a[i].dot(a[j]);
            if gamma == 0.0 || gamma.abs() <= 1e-15 * (alpha * beta).sqrt() {
                continue;
            }
            rotated = true;
            let zeta = (beta - alpha) / (2.0 * gamma);
            let t = zeta.signum() / (zeta.abs() + (1.0 + zeta * zeta).sqrt());
            let c = 1.0 / (1.0 + t * t).sqrt();
            let s = c * t;
            let (ai, aj) = (a[i], a[j]);
            a[i] = c * ai - s * aj;
            a[j] = s * ai + c * aj;
            let (vi, vj) = (v[i], v[j]);
            v[i] = c * vi - s * vj;
            v[j] = s * vi + c * vj;
        }
        if !rotated {
            break;
        }
    }
    let mut order = [0usize, 1, 2];
    let norms = a.map(|c| c.length());
    order.sort_by(|&i, &j| norms[j].total_cmp(&norms[i]));
    let s = DVec3::new(norms[order[0]], norms[order[1]], norms[order[2]]);
    let vv = DMat3::from_cols(v[order[0]], v[order[1]], v[order[2]]);
    let tiny = 1e-13 * s.x.max(f64::MIN_POSITIVE);
    let unit = |k: usize| a[order[k]] / s[k];
    let u0 = if s.x > tiny { unit(0) } else { DVec3::X };
    let u1 = if s.y > tiny {
        unit(1)
    } else {
        u0.any_orthonormal_vector()
    };
    let u2 = if s.z > tiny { unit(2) } else { u0.cross(u1) };
    (DMat3::from_cols(u0, u1, u2), s, vv)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solve_recovers_a_known_vector_and_survives_rank_deficiency() {
        let mut s = System6::default();
        let x = [0.1, -0.2, 0.3, 1.0, -2.0, 0.5];
        for k in 0..12 {
            let j: [f64; 6] = std::array::from_fn(|i| {
                (((i * 7 + k * 3) % 5) as f64 - 2.0) + (i == k % 6) as u8 as f64 * 3.0
            });
            let r = -(0..6).map(|i| j[i] * x[i]).sum::<f64>();
            s.add_row(&j, r, 1.0);
        }
        let got = s.solve().expect("solvable");
        assert!((0..6).all(|i| (got[i] - x[i]).abs() < 1e-9), "{got:?}");
        let merged = s.merge(s);
        let got = merged.solve().expect("solvable");
        assert!((0..6).all(|i| (got[i] - x[i]).abs() < 1e-9));
        // A rank-1 system still gives a finite answer.
        let mut r1 = System6::default();
        r1.add_row(&[1.0, 0.0, 0.0, 0.0, 1.0, 0.0], 1.0, 1.0);
        assert!(r1.solve().is_some_and(|x| x.iter().all(|v| v.is_finite())));
        assert!(System6::default().solve().is_none());
    }

    #[test]
    fn increment_and_motion_size() {
        let t = increment(&[0.0, 0.0, 5f64.to_radians(), 0.3, 0.0, 0.0]);
        let (dt, deg) = motion_size(&t);
        assert!((dt - 0.3).abs() < 1e-12 && (deg - 5.0).abs() < 1e-9);
        assert_eq!(
            skew(DVec3::new(1.0, 2.0, 3.0)) * DVec3::Y,
            DVec3::new(1.0, 2.0, 3.0).cross(DVec3::Y)
        );
    }

    #[test]
    fn svd_reconstructs_full_and_rank_deficient_matrices() {
        let r1 = DMat3::from_euler(glam::EulerRot::ZYX, 0.3, -0.7, 1.1);
        let r2 = DMat3::from_euler(glam::EulerRot::XYZ, -1.2, 0.4, 2.0);
        for diag in [
            DVec3::new(5.0, 2.0, 0.5),
            DVec3::new(3.0, 3.0, 1.0),
            DVec3::new(4.0, 1.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
        ] {
            let m = r1 * DMat3::from_diagonal(diag) * r2.transpose();
            let (u, s, v) = svd3(m);
            assert!(s.abs_diff_eq(diag, 1e-12), "{s} vs {diag}");
            assert!((u * DMat3::from_diagonal(s) * v.transpose()).abs_diff_eq(m, 1e-12));
            assert!((u.transpose() * u).abs_diff_eq(DMat3::IDENTITY, 1e-12));
            assert!((v.transpose() * v).abs_diff_eq(DMat3::IDENTITY, 1e-12));
        }
    }
}
