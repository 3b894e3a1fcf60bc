//! Whether a beam that meets a surface comes back: the received power of a diffuse
//! (Lambertian) surface, `reflectivity * cos(incidence) / range^2`, against the sensor's
//! detection threshold (a soft edge: detection is likelier the more power there is), dropouts
//! at grazing incidence, and glass, which passes most beams, returns a few and reflects the
//! rest away.
//!
//! Sources: SICK's operating instructions for its LMS5xx scanners (chapter "Impact of object
//! surfaces on the measurement": remission of white plaster about 100 %, of black foam rubber
//! about 2.4 %; energy is reflected best head-on), and the LMS-2xx technical description's
//! ranges at 10 % remission (LMS 200: about 10 m; LMS 291: about 30 m; both 80 m at best).
//! Soda-lime window glass transmits about 90 % in the near infrared (the LMS-2xx works at
//! 905 nm) and reflects about 4 % per face, specularly: only near-normal beams come back.

use crate::building::Material;
use cloud::check_range;
use serde::{Deserialize, Serialize};

/// Which returns a real sensor loses.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Returns {
    /// The range to which a 10 % reflective target, head-on, is still detected (half the
    /// time); absent: every hit is detected (no power limit).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub range_at_10pct_m: Option<f64>,
    /// Width of the detection edge in natural-log units of received power (0: a hard
    /// threshold; 0.3: twice the threshold power is detected 91 % of the time).
    pub detection_softness: f64,
    /// Diffuse reflectivity of `matte` surfaces (plaster, paint, wood) and of people.
    pub reflectivity_matte: f64,
    /// Diffuse reflectivity of `dark` surfaces (black paint, rubber, dark fabric).
    pub reflectivity_dark: f64,
    /// Incidence angle (from the surface normal) above which returns start to drop out; the
    /// dropout chance rises linearly to 1 at 90 degrees (90: no grazing dropouts).
    pub grazing_dropout_start_deg: f64,
    /// Chance that a beam meeting glass passes through it (and goes on to what is behind).
    pub glass_pass_probability: f64,
    /// Chance that a beam meeting glass returns from the glass itself. The rest of the beams
    /// are reflected away: no echo.
    pub glass_return_probability: f64,
}

impl Default for Returns {
    fn default() -> Self {
        Returns::off()
    }
}

/// What happens to a beam at a surface.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Fate {
    /// It comes back from this surface.
    Return,
    /// It goes on through the surface (glass).
    PassThrough,
    /// Nothing comes back.
    Lost,
}

impl Returns {
    /// Every hit returns, glass is opaque (the ideal sensor).
    pub fn off() -> Returns {
        Returns {
            range_at_10pct_m: None,
            detection_softness: 0.0,
            reflectivity_matte: 0.7,
            reflectivity_dark: 0.024,
            grazing_dropout_start_deg: 90.0,
            glass_pass_probability: 0.0,
            glass_return_probability: 1.0,
        }
    }

    /// The preset: an LMS 200 (10 m at 10 % remission), matte surfaces at 70 % (painted
    /// plaster), dark ones at 2.4 % (SICK's black foam rubber), dropouts from 75 degrees
    /// incidence, glass passing 85 % of the beams (90 % transmission, less what the faces
    /// reflect) and returning 8 % (two faces at 4 %).
    pub fn real() -> Returns {
        Returns {
            range_at_10pct_m: Some(10.0),
            detection_softness: 0.3,
            reflectivity_matte: 0.7,
            reflectivity_dark: 0.024,
            grazing_dropout_start_deg: 75.0,
            glass_pass_probability: 0.85,
            glass_return_probability: 0.08,
        }
    }

    /// Checks the parameters.
    pub fn validate(&self) -> Result<(), cloud::InvalidParameter> {
        if let Some(r) = self.range_at_10pct_m {
            check_range(
                "realism.returns.range_at_10pct_m",
                r,
                0.1,
                10_000.0,
                "within 0.1..10000 m",
            )?;
        }
        check_range(
            "realism.returns.detection_softness",
            self.detection_softness,
            0.0,
            5.0,
            "within 0..5 (log power)",
        )?;
        for (name, v) in [
            (
                "realism.returns.reflectivity_matte",
                self.reflectivity_matte,
            ),
            ("realism.returns.reflectivity_dark", self.reflectivity_dark),
        ] {
            check_range(
                name,
                v,
                1e-4,
                10.0,
                "within 0.0001..10 (1 = white Lambertian)",
            )?;
        }
        check_range(
            "realism.returns.grazing_dropout_start_deg",
            self.grazing_dropout_start_deg,
            0.0,
            90.0,
            "within 0..90 degrees",
        )?;
        for (name, v) in [
            (
                "realism.returns.glass_pass_probability",
                self.glass_pass_probability,
            ),
            (
                "realism.returns.glass_return_probability",
                self.glass_return_probability,
            ),
        ] {
            check_range(name, v, 0.0, 1.0, "a probability within 0..1")?;
        }
        check_range(
            "realism.returns.glass_pass_probability + glass_return_probability",
            self.glass_pass_probability + self.glass_return_probability,
            0.0,
            1.0,
            "at most 1 together",
        )?;
        Ok(())
    }

    /// The diffuse reflectivity of an opaque material (glass passes or returns beams by its
    /// probabilities instead).
    pub fn reflectivity(&self, material: Material) -> f64 {
        match material {
            Material::Dark => self.reflectivity_dark,
            Material::Matte | Material::Glass => self.reflectivity_matte,
        }
    }

    /// The chance that a beam at incidence `cos_incidence` drops out for grazing the surface.
    pub fn grazing_dropout(&self, cos_incidence: f64) -> f64 {
        let start = self.grazing_dropout_start_deg;
        if start >= 90.0 {
            return 0.0;
        }
        let theta = cos_incidence.abs().min(1.0).acos().to_degrees();
        ((theta - start) / (90.0 - start)).clamp(0.0, 1.0)
    }

    /// The chance that the sensor detects the echo of a diffuse surface of `reflectivity` at
    /// `range_m` and `cos_incidence`, its power also scaled by `transmission` (glass on the
    /// way, both ways).
    pub fn detection(
        &self,
        reflectivity: f64,
        range_m: f64,
        cos_incidence: f64,
        transmission: f64,
    ) -> f64 {
        let Some(r10) = self.range_at_10pct_m else {
            return 1.0;
        };
        // Received power relative to the threshold: a 10 % target head-on at r10.
        let power = reflectivity * cos_incidence.abs() * transmission / range_m.max(1e-3).powi(2);
        let threshold = 0.1 / (r10 * r10);
        let log_ratio = (power / threshold).max(f64::MIN_POSITIVE).ln();
        if self.detection_softness <= 0.0 {
            return if log_ratio >= 0.0 { 1.0 } else { 0.0 };
        }
        1.0 / (1.0 + (-log_ratio / self.detection_softness).exp())
    }

    /// The fate of a beam at a surface of `material`, from one uniform draw `u` in [0, 1) and
    /// the chance `p_return` that an opaque surface's echo is detected.
    pub(crate) fn fate(&self, material: Material, p_return: f64, u: f64) -> Fate {
        match material {
            Material::Glass if u < self.glass_return_probability => Fate::Return,
            Material::Glass if u < self.glass_return_probability + self.glass_pass_probability => {
                Fate::PassThrough
            }
            Material::Glass => Fate::Lost,
            Material::Matte | Material::Dark if u < p_return => Fate::Return,
            Material::Matte | Material::Dark => Fate::Lost,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn detection_follows_received_power_and_off_detects_everything() {
        let off = Returns::off();
        assert_eq!(off.detection(0.001, 29.0, 0.01, 1.0), 1.0);
        assert_eq!(off.grazing_dropout(0.0), 0.0);
        assert_eq!(off.fate(Material::Glass, 1.0, 0.99), Fate::Return);
        let real = Returns::real();
        // A 10 % target head-on at 10 m: the threshold, half the time.
        assert!((real.detection(0.1, 10.0, 1.0, 1.0) - 0.5).abs() < 1e-9);
        // Matte at 5 m head-on: certain; dark at 8 m: rarely; dark at 2 m: mostly.
        assert!(real.detection(0.7, 5.0, 1.0, 1.0) > 0.999);
        assert!(real.detection(0.024, 8.0, 1.0, 1.0) < 0.1);
        assert!(real.detection(0.024, 2.0, 1.0, 1.0) > 0.9);
        // Grazing: none head-on or below the start, half way at 82.5, all at 90 degrees.
        assert_eq!(real.grazing_dropout(1.0), 0.0);
        assert_eq!(real.grazing_dropout(70f64.to_radians().cos()), 0.0);
        assert!((real.grazing_dropout(82.5f64.to_radians().cos()) - 0.5).abs() < 1e-9);
        assert_eq!(real.grazing_dropout(0.0), 1.0);
        assert_eq!(real.fate(Material::Glass, 1.0, 0.05), Fate::Return);
        assert_eq!(real.fate(Material::Glass, 1.0, 0.5), Fate::PassThrough);
        assert_eq!(real.fate(Material::Glass, 1.0, 0.95), Fate::Lost);
        assert!(real.validate().is_ok() && off.validate().is_ok());
        let too_much = Returns {
            glass_pass_probability: 0.9,
            glass_return_probability: 0.2,
            ..Returns::real()
        };
        assert!(too_much.validate().is_err());
    }
}
