//! Robust kernels as iteratively re-weighted least squares (IRLS) weights.

use crate::config::RobustKernel;
use glam::Vec3;

/// Each point's prior weight `1 / (1 + (r / knee_m)^2)`, `r` its distance from `sensor`
/// (see [`crate::IcpConfig::range_knee_m`]).
pub(crate) fn range_weights(points: &[Vec3], sensor: Vec3, knee_m: f64) -> Vec<f32> {
    let inv_knee2 = 1.0 / (knee_m * knee_m);
    points
        .iter()
        .map(|p| (1.0 / (1.0 + p.distance_squared(sensor) as f64 * inv_knee2)) as f32)
        .collect()
}

impl RobustKernel {
    /// The IRLS weight of a pair with residual `r_m` (metres, sign ignored).
    ///
    /// Huber: `1` for `|r| <= k`, `k / |r|` beyond. Cauchy: `1 / (1 + (r / k)^2)`.
    #[inline]
    pub fn weight(&self, r_m: f64) -> f64 {
        match *self {
            RobustKernel::None => 1.0,
            RobustKernel::Huber { k_m } => {
                let a = r_m.abs();
                if a <= k_m {
                    1.0
                } else {
                    k_m / a
                }
            }
            RobustKernel::Cauchy { k_m } => {
                let u = r_m / k_m;
                1.0 / (1.0 + u * u)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::icp::point_to_point::CorrelationSums;
    use glam::{DAffine3, DVec3};

    #[test]
    fn range_weights_halve_at_the_knee_and_fall_with_the_square_of_range() {
        let sensor = Vec3::new(1.0, 0.0, 0.0);
        let pts = [
            sensor,
            sensor + Vec3::new(0.0, 2.0, 0.0),
            sensor + Vec3::new(0.0, 0.0, 20.0),
        ];
        let w = range_weights(&pts, sensor, 2.0);
        assert_eq!(w[0], 1.0);
        assert!((w[1] - 0.5).abs() < 1e-6, "{w:?}");
        assert!((w[2] - 1.0 / 101.0).abs() < 1e-6, "{w:?}");
    }

    #[test]
    fn weights_follow_the_kernels() {
        assert_eq!(RobustKernel::None.weight(10.0), 1.0);
        let h = RobustKernel::Huber { k_m: 0.1 };
        assert_eq!(h.weight(0.05), 1.0);
        assert_eq!(h.weight(-0.1), 1.0);
        assert!((h.weight(0.4) - 0.25).abs() < 1e-12);
        let c = RobustKernel::Cauchy { k_m: 0.1 };
        assert!((c.weight(0.0) - 1.0).abs() < 1e-12);
        assert!((c.weight(0.1) - 0.5).abs() < 1e-12);
        assert!(c.weight(1.0) < 0.01);
    }

    #[test]
    fn kernel_weights_shrug_off_gross_outliers_in_a_step() {
        // 200 exact pairs shifted by 2 cm, plus 20 pairs 0.4 m off in y.
        let truth = DAffine3::from_translation(DVec3::new(0.02, 0.0, 0.0));
        let pairs: Vec<(DVec3, DVec3)> = (0..220)
            .map(|i| {
                let f = i as f64;
                let d = DVec3::new((f * 0.7).sin() * 3.0, (f * 0.3).cos() * 2.0, f * 0.01);
                let m = truth.transform_point3(d);
                (
                    d,
                    if i < 200 {
                        m
                    } else {
                        m + DVec3::new(0.0, 0.4, 0.0)
                    },
                )
            })
            .collect();
        let solve = |kernel: RobustKernel| {
            let mut s = CorrelationSums::default();
            for (d, m) in &pairs {
                s.add(*d, *m, kernel.weight(d.distance(*m)));
            }
            let t = s.solve().expect("solvable");
            (t.translation - truth.translation).length()
        };
        let plain = solve(RobustKernel::None);
        let cauchy = solve(RobustKernel::Cauchy { k_m: 0.03 });
        assert!(plain > 0.01, "{plain}");
        assert!(cauchy < plain / 10.0, "{cauchy} vs {plain}");
    }
}
