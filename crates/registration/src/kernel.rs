//! Robust kernels as iteratively re-weighted least squares (IRLS) weights.

use crate::config::RobustKernel;

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
}
