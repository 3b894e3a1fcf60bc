//! Local surface estimation: normals (point-to-plane) and plane-regularised covariances (GICP)
//! from the k nearest neighbours of each point.
//!
//! On a raw organised scan the k nearest neighbours of a point line up along one scan line
//! and span a few millimetres, less than the range noise: their normals are degenerate or
//! noise. So neighbourhoods are taken on a *support* copy of the cloud downsampled to
//! `normal_voxel_m` (voxel centroids average the noise and are spread in two directions),
//! within a radius of [`SUPPORT_RADIUS_VOXELS`] voxels, and each input point takes the surface
//! of its nearest support point. A neighbourhood with fewer than [`MIN_NEIGHBOURS`] points or
//! whose middle eigenvalue is below [`MIN_SPREAD_RATIO`] times the largest (a line, not a
//! surface) is degenerate: its point gets a zero normal and covariance and is not used as a
//! point-to-plane or GICP correspondence.
//!
//! GICP covariances are regularised as in Segal et al. 2009 and small_gicp: the eigenvalues of
//! the neighbourhood covariance are replaced by (1e-3, 1, 1) (normal direction first), so every
//! point is a small plane patch.

use crate::config::IcpConfig;
use crate::downsample::voxel_downsample;
use crate::error::Result;
use crate::nearest::grid::BucketGrid;
use crate::nearest::kdtree::KdTree;
use crate::nearest::NearestNeighbors;
use glam::{DMat3, DVec3, Mat3, Vec3};
use rayon::prelude::*;

/// Fewest neighbours (the point itself included) that make a surface estimate.
pub(crate) const MIN_NEIGHBOURS: usize = 5;
/// A neighbourhood whose middle eigenvalue is below this fraction of the largest is a line.
pub(crate) const MIN_SPREAD_RATIO: f64 = 0.01;
/// Neighbourhood radius, in support voxels.
pub(crate) const SUPPORT_RADIUS_VOXELS: f64 = 20.0;
/// The regularised eigenvalue along the normal (the others are 1).
pub(crate) const GICP_EPSILON: f64 = 1e-3;

/// Per-point surface estimates.
pub(crate) struct Surface {
    /// Unit normal per point; zero where the neighbourhood is degenerate.
    pub normals: Vec<Vec3>,
    /// Plane-regularised covariance per point (empty unless asked for); zero where degenerate.
    pub covariances: Vec<Mat3>,
}

impl Surface {
    /// Number of points with a usable surface estimate.
    #[cfg(test)]
    pub(crate) fn valid_count(&self) -> usize {
        self.normals.iter().filter(|n| **n != Vec3::ZERO).count()
    }
}

/// Estimates the surface at every point of `points`. `points_voxel_m` is the voxel edge the
/// points were already downsampled to, if any: when it is at least `normal_voxel_m` the
/// points are their own support.
pub(crate) fn estimate_surface(
    points: &[Vec3],
    points_voxel_m: Option<f64>,
    config: &IcpConfig,
    covariances: bool,
) -> Result<Surface> {
    let voxel = config.normal_voxel_m;
    let own_support = points_voxel_m.is_some_and(|v| v >= voxel * 0.999);
    let downsampled;
    let support: &[Vec3] = if own_support {
        points
    } else {
        downsampled = voxel_downsample(points, voxel, "normal_voxel_m")?;
        &downsampled
    };
    let radius = (voxel.max(points_voxel_m.unwrap_or(0.0)) * SUPPORT_RADIUS_VOXELS) as f32;
    let tree = KdTree::new(support);
    let k = config.neighbours_k;
    let estimates: Vec<(Vec3, Mat3)> = support
        .par_iter()
        .with_min_len(512)
        .map_init(
            || Vec::with_capacity(k),
            |buf, p| {
                tree.k_nearest(*p, k, radius, buf);
                local_surface(support, buf, *p, k.min(MIN_NEIGHBOURS), covariances)
            },
        )
        .collect();
    if own_support {
        let (normals, covs) = estimates.into_iter().unzip();
        return Ok(finish(normals, covs, covariances));
    }
    // Each input point takes the surface of its nearest support point.
    let reach = (2.0 * voxel) as f32;
    let grid = BucketGrid::new(support, 2.0 * voxel)?;
    let (normals, covs): (Vec<Vec3>, Vec<Mat3>) = points
        .par_iter()
        .with_min_len(1024)
        .map(|p| match grid.nearest(*p, reach) {
            Some((j, _)) => estimates[j as usize],
            None => (Vec3::ZERO, Mat3::ZERO),
        })
        .unzip();
    Ok(finish(normals, covs, covariances))
}

fn finish(normals: Vec<Vec3>, covs: Vec<Mat3>, covariances: bool) -> Surface {
    Surface {
        normals,
        covariances: if covariances { covs } else { Vec::new() },
    }
}

/// Normal and regularised covariance of the neighbourhood `idx` of `center` (zeros if
/// degenerate).
fn local_surface(
    support: &[Vec3],
    idx: &[u32],
    center: Vec3,
    min_neighbours: usize,
    covariance: bool,
) -> (Vec3, Mat3) {
    let none = (Vec3::ZERO, Mat3::ZERO);
    if idx.len() < min_neighbours.max(3) {
        return none;
    }
    // Mean and scatter relative to the centre point, in f64.
    let c = center.as_dvec3();
    let mut sum = DVec3::ZERO;
    let mut outer = [0.0f64; 6];
    for &j in idx {
        let d = support[j as usize].as_dvec3() - c;
        sum += d;
        outer[0] += d.x * d.x;
        outer[1] += d.x * d.y;
        outer[2] += d.x * d.z;
        outer[3] += d.y * d.y;
        outer[4] += d.y * d.z;
        outer[5] += d.z * d.z;
    }
    let n = idx.len() as f64;
    let m = sum / n;
    let cov = DMat3::from_cols_array(&[
        outer[0] / n - m.x * m.x,
        outer[1] / n - m.x * m.y,
        outer[2] / n - m.x * m.z,
        outer[1] / n - m.x * m.y,
        outer[3] / n - m.y * m.y,
        outer[4] / n - m.y * m.z,
        outer[2] / n - m.x * m.z,
        outer[4] / n - m.y * m.z,
        outer[5] / n - m.z * m.z,
    ]);
    let (values, vectors) = symmetric_eigen(cov);
    if !(values.z > 0.0 && values.y >= MIN_SPREAD_RATIO * values.z) {
        return none;
    }
    let normal = vectors.x_axis;
    let regularised = if covariance {
        let d = DMat3::from_diagonal(DVec3::new(GICP_EPSILON, 1.0, 1.0));
        (vectors * d * vectors.transpose()).as_mat3()
    } else {
        Mat3::ZERO
    };
    (normal.as_vec3(), regularised)
}

/// Eigen-decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations: eigenvalues in
/// ascending order and the matching unit eigenvectors as the columns of the matrix.
pub(crate) fn symmetric_eigen(m: DMat3) -> (DVec3, DMat3) {
    let mut a = [
        m.x_axis.to_array(),
        m.y_axis.to_array(),
        m.z_axis.to_array(),
    ];
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let scale = a[0][0].abs() + a[1][1].abs() + a[2][2].abs();
    for _sweep in 0..32 {
        let off = a[0][1].abs() + a[0][2].abs() + a[1][2].abs();
        if off <= 1e-15 * scale || off == 0.0 {
            break;
        }
        for (p, q) in [(0usize, 1usize), (0, 2), (1, 2)] {
            let apq = a[p][q];
            if apq == 0.0 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * apq);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            // A <- A J (columns p, q), then A <- J^T A (rows p, q), V <- V J.
            for row in &mut a {
                let (xp, xq) = (row[p], row[q]);
                row[p] = c * xp - s * xq;
                row[q] = s * xp + c * xq;
            }
            let (rp, rq) = (a[p], a[q]);
            for k in 0..3 {
                a[p][k] = c * rp[k] - s * rq[k];
                a[q][k] = s * rp[k] + c * rq[k];
            }
            for row in &mut v {
                let (xp, xq) = (row[p], row[q]);
                row[p] = c * xp - s * xq;
                row[q] = s * xp + c * xq;
            }
        }
    }
    let mut order = [0usize, 1, 2];
    order.sort_by(|&i, &j| a[i][i].total_cmp(&a[j][j]));
    let values = DVec3::new(
        a[order[0]][order[0]],
        a[order[1]][order[1]],
        a[order[2]][order[2]],
    );
    // `v` is indexed [row][col]: eigenvector i is column i.
    let col = |i: usize| DVec3::new(v[0][i], v[1][i], v[2][i]);
    (
        values,
        DMat3::from_cols(col(order[0]), col(order[1]), col(order[2])),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jacobi_reconstructs_symmetric_matrices() {
        let r = DMat3::from_euler(glam::EulerRot::ZYX, 0.3, -0.7, 1.1);
        for diag in [
            DVec3::new(3.0, 1.0, 0.01),
            DVec3::new(2.0, 2.0, 1e-6),
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(0.0, 0.0, 5.0),
        ] {
            let m = r * DMat3::from_diagonal(diag) * r.transpose();
            let (values, vectors) = symmetric_eigen(m);
            let mut sorted = diag.to_array();
            sorted.sort_by(f64::total_cmp);
            assert!(
                values.abs_diff_eq(DVec3::from_array(sorted), 1e-9),
                "{values}"
            );
            let back = vectors * DMat3::from_diagonal(values) * vectors.transpose();
            assert!(back.abs_diff_eq(m, 1e-9));
            assert!((vectors.transpose() * vectors).abs_diff_eq(DMat3::IDENTITY, 1e-9));
        }
    }

    #[test]
    fn plane_gets_its_normal_and_a_line_is_degenerate() {
        // A tilted plane z = 0.2 x sampled on a 2 cm grid, and a line along y far away.
        let mut pts = Vec::new();
        for i in 0..40 {
            for j in 0..40 {
                let (x, y) = (i as f32 * 0.02, j as f32 * 0.02);
                pts.push(Vec3::new(x, y, 0.2 * x));
            }
        }
        let plane = pts.len();
        for j in 0..200 {
            pts.push(Vec3::new(10.0, j as f32 * 0.01, 0.0));
        }
        let config = IcpConfig {
            normal_voxel_m: 0.05,
            neighbours_k: 10,
            ..IcpConfig::default()
        };
        let s = estimate_surface(&pts, None, &config, true).expect("surface");
        let truth = Vec3::new(-0.2, 0.0, 1.0).normalize();
        for n in &s.normals[..plane] {
            assert!(n.dot(truth).abs() > 0.999, "{n}");
        }
        assert!(s.normals[plane..].iter().all(|n| *n == Vec3::ZERO));
        assert_eq!(s.valid_count(), plane);
        // The regularised covariance is tight along the normal and loose in the plane.
        let c = s.covariances[0];
        assert!((truth.dot(c * truth) - 1e-3).abs() < 1e-4);
        assert!((c * Vec3::Y).dot(Vec3::Y) > 0.99);
    }
}
