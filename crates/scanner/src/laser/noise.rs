//! Range noise that grows with range and with the angle of incidence.
//!
//! `sigma(r, theta)^2 = sigma0^2 + (per_m * r)^2 + (incidence_weight * r * beta * tan(theta))^2`
//! with `sigma0` the laser's `range_noise_sigma_m`, `beta` the beam divergence (full angle) and
//! `theta` the angle between the beam and the surface normal. The last term is the depth
//! spread across the beam's footprint on an inclined surface: a footprint of diameter
//! `r * beta` on a surface inclined by `theta` spans `r * beta * tan(theta)` in depth, and a
//! uniformly lit footprint's depths have a standard deviation of `1/sqrt(12)` of that span
//! (`incidence_weight = 0.29`). Ye and Borenstein ("Characterization of a 2-D laser scanner
//! for mobile robot obstacle negotiation", ICRA 2002, SICK LMS 200) and Pomerleau et al.
//! ("Noise characterization of depth sensors for surface inspections", CARPI 2012) measured
//! range noise growing with range and with incidence on real time-of-flight scanners.

use cloud::check_range;
use serde::{Deserialize, Serialize};

/// How the range noise grows (on top of the laser's `range_noise_sigma_m`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RangeNoise {
    /// Growth of the sigma with range: adds `(sigma_per_m * range)^2` to the variance.
    pub sigma_per_m: f64,
    /// Share of the footprint's depth spread on an inclined surface that adds to the sigma
    /// (0: none; 0.29 = 1/sqrt(12): a uniformly lit footprint).
    pub incidence_weight: f64,
}

impl Default for RangeNoise {
    fn default() -> Self {
        RangeNoise::off()
    }
}

/// The steepest incidence whose tangent enters the sigma (the tangent is infinite at 90
/// degrees; such beams drop out as grazing returns anyway).
const MAX_INCIDENCE_DEG: f64 = 89.0;

impl RangeNoise {
    /// Constant noise (the laser's `range_noise_sigma_m` alone).
    pub fn off() -> RangeNoise {
        RangeNoise {
            sigma_per_m: 0.0,
            incidence_weight: 0.0,
        }
    }

    /// The preset: 1 mm more sigma per metre of range (with the laser's 1 cm that is 1.02 cm
    /// at 2 m, 1.41 cm at 10 m, 3.2 cm at 30 m: the LMS-2xx data sheets give about 1 cm at
    /// short range and worse towards the range limit), and the footprint spread of a
    /// uniformly lit spot.
    pub fn real() -> RangeNoise {
        RangeNoise {
            sigma_per_m: 0.001,
            incidence_weight: 1.0 / 12f64.sqrt(),
        }
    }

    /// Checks the parameters.
    pub fn validate(&self) -> Result<(), cloud::InvalidParameter> {
        check_range(
            "realism.noise.sigma_per_m",
            self.sigma_per_m,
            0.0,
            0.1,
            "within 0..0.1 m per m",
        )?;
        check_range(
            "realism.noise.incidence_weight",
            self.incidence_weight,
            0.0,
            1.0,
            "within 0..1",
        )?;
        Ok(())
    }

    /// The range sigma (metres) of a return at `range_m` whose beam meets the surface at
    /// `cos_incidence` (1 head-on), for a laser of base sigma `sigma0_m` and beam divergence
    /// `divergence_rad`.
    pub fn sigma_m(
        &self,
        sigma0_m: f64,
        range_m: f64,
        cos_incidence: f64,
        divergence_rad: f64,
    ) -> f64 {
        let growth = self.sigma_per_m * range_m;
        let cos = cos_incidence
            .abs()
            .clamp(MAX_INCIDENCE_DEG.to_radians().cos(), 1.0);
        let tan = (1.0 - cos * cos).sqrt() / cos;
        let spread = self.incidence_weight * range_m * divergence_rad * tan;
        (sigma0_m * sigma0_m + growth * growth + spread * spread).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sigma_grows_with_range_and_incidence_and_is_constant_when_off() {
        let off = RangeNoise::off();
        assert_eq!(off.sigma_m(0.01, 25.0, 0.1, 0.0044), 0.01);
        let real = RangeNoise::real();
        let (near, far) = (
            real.sigma_m(0.01, 2.0, 1.0, 0.0044),
            real.sigma_m(0.01, 10.0, 1.0, 0.0044),
        );
        assert!(
            (near - 0.0102).abs() < 1e-4 && (far - 0.01414).abs() < 1e-4,
            "{near} {far}"
        );
        let oblique = real.sigma_m(0.01, 10.0, 70f64.to_radians().cos(), 0.0044);
        assert!(oblique > far * 1.1, "{oblique} vs head-on {far}");
        assert!(real.sigma_m(0.01, 10.0, 0.0, 0.0044).is_finite());
    }
}
