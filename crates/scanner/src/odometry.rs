//! Simulated wheel odometry: the ground-truth poses with drift and noise accumulated
//! step by step, as a robot's dead reckoning would report them.

use crate::error::Result;
use crate::pose::ScanPose;
use cloud::check_range;
use cloud::Rng;
use serde::{Deserialize, Serialize};

/// How wrong the odometry is.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct OdometryConfig {
    /// Systematic scale error of travelled distance (0.02 = 2% too long).
    pub distance_scale_error: f64,
    /// Systematic heading drift per metre travelled.
    pub yaw_drift_deg_per_m: f64,
    /// Gaussian noise on each step's translation (per axis).
    pub translation_noise_sigma_m: f64,
    /// Gaussian noise on each step's heading change.
    pub yaw_noise_sigma_deg: f64,
    /// Seed of the noise.
    pub seed: u64,
}

impl Default for OdometryConfig {
    fn default() -> Self {
        OdometryConfig {
            distance_scale_error: 0.02,
            yaw_drift_deg_per_m: 0.3,
            translation_noise_sigma_m: 0.05,
            yaw_noise_sigma_deg: 1.0,
            seed: 1,
        }
    }
}

impl OdometryConfig {
    /// Checks every parameter's range.
    pub fn validate(&self) -> Result<()> {
        let config = self;
        check_range(
            "distance_scale_error",
            config.distance_scale_error,
            -0.5,
            0.5,
            "within -0.5..0.5",
        )?;
        check_range(
            "yaw_drift_deg_per_m",
            config.yaw_drift_deg_per_m,
            -90.0,
            90.0,
            "within -90..90",
        )?;
        check_range(
            "translation_noise_sigma_m",
            config.translation_noise_sigma_m,
            0.0,
            10.0,
            "within 0..10 m",
        )?;
        check_range(
            "yaw_noise_sigma_deg",
            config.yaw_noise_sigma_deg,
            0.0,
            90.0,
            "within 0..90",
        )?;
        Ok(())
    }
}

/// Odometry poses for a sequence of true poses: the first is exact, each later one adds the
/// true relative motion from the previous pose, distorted by drift and noise.
pub fn odometry_from_truth(truth: &[ScanPose], config: &OdometryConfig) -> Result<Vec<ScanPose>> {
    config.validate()?;
    let mut rng = Rng::new(config.seed);
    let mut out: Vec<ScanPose> = Vec::with_capacity(truth.len());
    for (k, t) in truth.iter().enumerate() {
        let Some(prev_odom) = out.last().copied() else {
            out.push(*t);
            continue;
        };
        let prev = truth[k - 1];
        // True motion in the previous pose's frame.
        let (s, c) = prev.yaw_deg.to_radians().sin_cos();
        let (dx, dy) = (t.x_m - prev.x_m, t.y_m - prev.y_m);
        let local = (c * dx + s * dy, -s * dx + c * dy);
        let dist = local.0.hypot(local.1);
        let scale = 1.0 + config.distance_scale_error;
        let lx = local.0 * scale + config.translation_noise_sigma_m * rng.gaussian();
        let ly = local.1 * scale + config.translation_noise_sigma_m * rng.gaussian();
        let dyaw = (t.yaw_deg - prev.yaw_deg)
            + config.yaw_drift_deg_per_m * dist
            + config.yaw_noise_sigma_deg * rng.gaussian();
        let (s, c) = prev_odom.yaw_deg.to_radians().sin_cos();
        out.push(ScanPose {
            x_m: prev_odom.x_m + c * lx - s * ly,
            y_m: prev_odom.y_m + s * lx + c * ly,
            yaw_deg: prev_odom.yaw_deg + dyaw,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(n: usize) -> Vec<ScanPose> {
        (0..n)
            .map(|i| ScanPose {
                x_m: i as f64,
                y_m: 0.0,
                yaw_deg: 10.0 * i as f64,
            })
            .collect()
    }

    #[test]
    fn noiseless_odometry_equals_truth() {
        let cfg = OdometryConfig {
            distance_scale_error: 0.0,
            yaw_drift_deg_per_m: 0.0,
            translation_noise_sigma_m: 0.0,
            yaw_noise_sigma_deg: 0.0,
            seed: 3,
        };
        let truth = line(5);
        for (o, t) in odometry_from_truth(&truth, &cfg)
            .expect("valid")
            .iter()
            .zip(&truth)
        {
            assert!(
                (o.x_m - t.x_m).abs() < 1e-9
                    && (o.y_m - t.y_m).abs() < 1e-9
                    && (o.yaw_deg - t.yaw_deg).abs() < 1e-9
            );
        }
    }

    #[test]
    fn drift_grows_with_distance() {
        let truth = line(10);
        let odo = odometry_from_truth(&truth, &OdometryConfig::default()).expect("valid");
        let err = |k: usize| (odo[k].x_m - truth[k].x_m).hypot(odo[k].y_m - truth[k].y_m);
        assert_eq!(err(0), 0.0);
        assert!(err(9) > 0.05, "final error {}", err(9));
        assert!(odometry_from_truth(
            &truth,
            &OdometryConfig {
                yaw_noise_sigma_deg: -1.0,
                ..Default::default()
            }
        )
        .is_err());
    }
}
