//! Input preparation: the finite points of a cloud (with the error rules for missing returns)
//! and a fast positions-only voxel downsampling on the sparse cell index.

use crate::cells::{sort_into_cells, Lattice};
use crate::error::{RegistrationError, Result};
use cloud::PointCloud;
use glam::{DVec3, Vec3};

/// The finite points of `cloud`. Organised clouds may hold all-NaN missing returns, which are
/// skipped; any other non-finite coordinate is [`RegistrationError::NonFinite`]. A cloud
/// without a finite point is [`RegistrationError::EmptyCloud`].
pub(crate) fn finite_points(cloud: &PointCloud, which: &str) -> Result<Vec<Vec3>> {
    let organized = cloud.organized.is_some();
    let mut out = Vec::with_capacity(cloud.len());
    for (index, p) in cloud.points.iter().enumerate() {
        if p.is_finite() {
            out.push(*p);
        } else if !(organized && p.is_nan() && !p.to_array().iter().any(|v| v.is_infinite())) {
            return Err(RegistrationError::NonFinite {
                which: which.to_string(),
                index,
            });
        }
    }
    if out.is_empty() {
        return Err(RegistrationError::EmptyCloud {
            which: which.to_string(),
        });
    }
    Ok(out)
}

/// One point per occupied cubic voxel of edge `voxel_m`, at the centroid of the voxel's
/// points, in the order of each voxel's first point. `name` is the parameter blamed when the
/// voxel is absurd for the cloud's extent.
pub(crate) fn voxel_downsample(
    points: &[Vec3],
    voxel_m: f64,
    name: &'static str,
) -> Result<Vec<Vec3>> {
    Ok(voxel_centroids(points, voxel_m, name)?
        .into_iter()
        .map(|(p, _)| p)
        .collect())
}

/// As [`voxel_downsample`], carrying one attribute per point along: each voxel keeps the
/// attribute of its first point (e.g. the sensor position a map point was seen from).
pub(crate) fn voxel_downsample_with<A: Copy>(
    points: &[Vec3],
    attributes: &[A],
    voxel_m: f64,
    name: &'static str,
) -> Result<(Vec<Vec3>, Vec<A>)> {
    debug_assert_eq!(points.len(), attributes.len());
    Ok(voxel_centroids(points, voxel_m, name)?
        .into_iter()
        .map(|(p, first)| (p, attributes[first]))
        .unzip())
}

/// The centroid of every occupied voxel and the index of its first point.
fn voxel_centroids(
    points: &[Vec3],
    voxel_m: f64,
    name: &'static str,
) -> Result<Vec<(Vec3, usize)>> {
    let lattice = Lattice::new(points, voxel_m, name)?;
    let (_, start, order) = sort_into_cells(points, &lattice);
    let origin = Vec3::from(lattice.origin).as_dvec3();
    Ok(start
        .windows(2)
        .map(|w| {
            let members = &order[w[0] as usize..w[1] as usize];
            let sum: DVec3 = members
                .iter()
                .map(|&i| points[i as usize].as_dvec3() - origin)
                .sum();
            let first = members.iter().copied().min().unwrap_or(0) as usize;
            ((origin + sum / members.len() as f64).as_vec3(), first)
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use cloud::Organized;

    #[test]
    fn organised_missing_returns_are_skipped_but_unorganised_nan_is_an_error() {
        let mut c = PointCloud::from_points(vec![Vec3::ZERO, Vec3::NAN, Vec3::ONE, Vec3::X]);
        c.organized = Some(Organized { rows: 2, cols: 2 });
        assert_eq!(finite_points(&c, "source").expect("organised").len(), 3);
        c.organized = None;
        match finite_points(&c, "source") {
            Err(RegistrationError::NonFinite { which, index }) => {
                assert_eq!((which.as_str(), index), ("source", 1))
            }
            other => panic!("{other:?}"),
        }
        c.organized = Some(Organized { rows: 2, cols: 2 });
        c.points[1] = Vec3::new(f32::INFINITY, 0.0, 0.0);
        assert!(matches!(
            finite_points(&c, "target"),
            Err(RegistrationError::NonFinite { index: 1, .. })
        ));
        let all_nan = PointCloud {
            points: vec![Vec3::NAN; 4],
            organized: Some(Organized { rows: 2, cols: 2 }),
            ..PointCloud::default()
        };
        assert!(matches!(
            finite_points(&all_nan, "target"),
            Err(RegistrationError::EmptyCloud { .. })
        ));
    }

    #[test]
    fn voxels_average_their_points() {
        let pts = vec![
            Vec3::new(0.01, 0.01, 0.01),
            Vec3::new(0.03, 0.03, 0.03),
            Vec3::new(0.51, 0.0, 0.0),
        ];
        let d = voxel_downsample(&pts, 0.1, "v").expect("downsample");
        assert_eq!(d.len(), 2);
        assert!((d[0] - Vec3::splat(0.02)).length() < 1e-6);
        assert!((d[1] - Vec3::new(0.51, 0.0, 0.0)).length() < 1e-6);
        assert!(voxel_downsample(&pts, 0.0, "v").is_err());
        let wide = vec![Vec3::ZERO, Vec3::splat(10_000.0)];
        assert!(matches!(
            voxel_downsample(&wide, 1e-4, "source_voxel_m"),
            Err(RegistrationError::InvalidParameter(p)) if p.name == "source_voxel_m"
        ));
    }
}
