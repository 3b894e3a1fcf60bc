//! Voxel-grid downsampling: one point per occupied voxel, at the centroid of the points in it.

use crate::cloud::{Label, PointCloud};
use crate::error::Result;
use glam::{DVec3, Vec3};
use std::collections::HashMap;

/// The smallest voxel edge: below it f32 coordinates would not separate voxels.
const MIN_VOXEL_M: f64 = 1e-6;

/// Downsamples `cloud` to one point per cubic voxel of edge `voxel_size_m`.
///
/// The output point is the centroid of the voxel's finite points; intensity is averaged;
/// the label is that of the voxel's most frequent label (ties: the first seen).
/// Output order follows each voxel's first point in the input, so the result is deterministic.
/// Missing returns are dropped and the output is unorganised.
pub fn voxel_downsample(cloud: &PointCloud, voxel_size_m: f64) -> Result<PointCloud> {
    crate::check_range(
        "voxel_size_m",
        voxel_size_m,
        MIN_VOXEL_M,
        f64::MAX,
        "must be a finite length of at least 1 micrometre",
    )?;
    let inv = 1.0 / voxel_size_m;
    let mut slot_of: HashMap<(i64, i64, i64), usize> = HashMap::new();
    let mut acc: Vec<Accumulator> = Vec::new();
    for (i, p) in cloud.points.iter().enumerate() {
        if !p.is_finite() {
            continue;
        }
        let key = (
            (p.x as f64 * inv).floor() as i64,
            (p.y as f64 * inv).floor() as i64,
            (p.z as f64 * inv).floor() as i64,
        );
        let slot = *slot_of.entry(key).or_insert_with(|| {
            acc.push(Accumulator::default());
            acc.len() - 1
        });
        let a = &mut acc[slot];
        a.sum += p.as_dvec3();
        a.count += 1;
        if let Some(v) = &cloud.intensity {
            a.intensity += v[i] as f64;
        }
        if let Some(v) = &cloud.labels {
            a.vote(v[i]);
        }
    }
    let mut out = PointCloud::from_points(
        acc.iter()
            .map(|a| (a.sum / a.count as f64).as_vec3())
            .collect::<Vec<Vec3>>(),
    );
    if cloud.intensity.is_some() {
        out.intensity = Some(
            acc.iter()
                .map(|a| (a.intensity / a.count as f64) as f32)
                .collect(),
        );
    }
    if cloud.labels.is_some() {
        out.labels = Some(acc.iter().map(Accumulator::majority).collect());
    }
    out.sensor_origin = cloud.sensor_origin;
    out.sensor_orientation = cloud.sensor_orientation;
    Ok(out)
}

#[derive(Default)]
struct Accumulator {
    sum: DVec3,
    count: usize,
    intensity: f64,
    votes: Vec<(Label, u32)>,
}

impl Accumulator {
    fn vote(&mut self, label: Label) {
        match self.votes.iter_mut().find(|(l, _)| *l == label) {
            Some((_, n)) => *n += 1,
            None => self.votes.push((label, 1)),
        }
    }

    fn majority(&self) -> Label {
        let mut best: Option<(Label, u32)> = None;
        for &(l, n) in &self.votes {
            if best.is_none_or(|(_, b)| n > b) {
                best = Some((l, n));
            }
        }
        best.map(|(l, _)| l).unwrap_or_default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::class::EntityClass;

    #[test]
    fn merges_points_per_voxel_at_their_centroid() {
        let mut c = PointCloud::from_points(vec![
            Vec3::new(0.01, 0.01, 0.01),
            Vec3::new(0.03, 0.03, 0.03),
            Vec3::new(0.51, 0.0, 0.0),
            Vec3::NAN,
        ]);
        let wall = Label {
            entity: 3,
            class: EntityClass::Wall,
        };
        c.labels = Some(vec![wall, wall, Label::default(), Label::default()]);
        c.organized = Some(crate::Organized { rows: 2, cols: 2 });
        let d = voxel_downsample(&c, 0.1).expect("valid voxel size");
        assert_eq!(d.len(), 2);
        assert!((d.points[0] - Vec3::splat(0.02)).length() < 1e-6);
        assert_eq!(d.labels.as_ref().map(|l| l[0]), Some(wall));
        assert!(d.organized.is_none());
    }

    #[test]
    fn rejects_absurd_voxel_sizes() {
        let c = PointCloud::from_points(vec![Vec3::ZERO]);
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(voxel_downsample(&c, bad).is_err(), "{bad} accepted");
        }
    }
}
