//! The realistic sensor's parameters: one section per effect, `Realism::off()` (the ideal
//! laser, the default) and `Realism::real()` (the documented preset: a SICK LMS 200 on a
//! rotating unit, the paper's sensor). In a configuration file `[laser] realism = "real"`
//! (or `"ideal"`) names a preset, and a `[laser.realism]` table gives every value (missing
//! ones are the ideal laser's); every run writes the table it used.

use super::mixed::MixedPixels;
use super::mount::Mount;
use super::noise::RangeNoise;
use super::people::People;
use super::returns::Returns;
use cloud::check_range;
use serde::de::{self, MapAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// How far the virtual laser is from an ideal sensor.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(remote = "Self", default, deny_unknown_fields)]
pub struct Realism {
    /// Full angle of the beam's divergence, milliradians: the footprint on a surface at range
    /// `r` is `r * divergence` wide (the incidence noise and mixed pixels use it).
    pub beam_divergence_mrad: f64,
    /// The range the sensor writes for a beam that brings back no echo, as many real sensors
    /// do (3DTK's SICK scans: 32.767 m, the largest 16-bit millimetre count); absent: a
    /// missing return is NaN (PCL's convention). Must lie beyond `max_range_m`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub no_echo_range_m: Option<f64>,
    /// Range noise growing with range and incidence.
    pub noise: RangeNoise,
    /// Lost returns: received power, grazing incidence, glass.
    pub returns: Returns,
    /// Mixed pixels at depth edges.
    pub mixed: MixedPixels,
    /// People walking by during the scan.
    pub people: People,
    /// A slightly tilted mount.
    pub mount: Mount,
}

impl Default for Realism {
    fn default() -> Self {
        Realism::off()
    }
}

/// The names of the presets, as `--laser` and `[laser] realism = "..."` take them.
pub const PRESETS: [&str; 2] = ["ideal", "real"];

impl Realism {
    /// The ideal sensor: every effect off (scans are exactly the geometry plus the laser's
    /// constant gaussian range noise).
    pub fn off() -> Realism {
        Realism {
            beam_divergence_mrad: 0.0,
            no_echo_range_m: None,
            noise: RangeNoise::off(),
            returns: Returns::off(),
            mixed: MixedPixels::off(),
            people: People::off(),
            mount: Mount::off(),
        }
    }

    /// The preset of a real sensor (see each section's `real()`): beam divergence 4.4 mrad
    /// (0.25 degrees, the order of the LMS-2xx's spot: about 4 cm wide at 10 m) and the no-echo
    /// value 32.767 m of 3DTK's scans.
    pub fn real() -> Realism {
        Realism {
            beam_divergence_mrad: 4.4,
            no_echo_range_m: Some(32.767),
            noise: RangeNoise::real(),
            returns: Returns::real(),
            mixed: MixedPixels::real(),
            people: People::real(),
            mount: Mount::real(),
        }
    }

    /// The preset called `name` (one of [`PRESETS`]).
    pub fn preset(name: &str) -> Option<Realism> {
        match name {
            "ideal" | "off" => Some(Realism::off()),
            "real" => Some(Realism::real()),
            _ => None,
        }
    }

    /// Whether every effect is off (the ideal laser's exact code path).
    pub fn is_off(&self) -> bool {
        *self == Realism::off()
    }

    /// Checks every parameter, for a laser whose returns end at `max_range_m`.
    pub fn validate(&self, max_range_m: f64) -> Result<(), cloud::InvalidParameter> {
        check_range(
            "realism.beam_divergence_mrad",
            self.beam_divergence_mrad,
            0.0,
            100.0,
            "within 0..100 mrad",
        )?;
        if let Some(r) = self.no_echo_range_m {
            check_range(
                "realism.no_echo_range_m",
                r,
                max_range_m + 1e-3,
                10_000.0,
                "beyond max_range_m (a no-echo value must not read as a return) and at most 10000 m",
            )?;
        }
        self.noise.validate()?;
        self.returns.validate()?;
        self.mixed.validate()?;
        self.people.validate()?;
        self.mount.validate()?;
        Ok(())
    }
}

impl Serialize for Realism {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        Realism::serialize(self, s)
    }
}

impl<'de> Deserialize<'de> for Realism {
    /// A preset's name, or a table of values.
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Realism, D::Error> {
        struct PresetOrTable;
        impl<'de> Visitor<'de> for PresetOrTable {
            type Value = Realism;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                write!(
                    f,
                    "a preset ({}) or a table of realism values",
                    PRESETS.join(", ")
                )
            }
            fn visit_str<E: de::Error>(self, name: &str) -> Result<Realism, E> {
                Realism::preset(name).ok_or_else(|| {
                    E::custom(format!(
                        "unknown laser preset '{name}': expected one of {}",
                        PRESETS.join(", ")
                    ))
                })
            }
            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Realism, A::Error> {
                Realism::deserialize(de::value::MapAccessDeserializer::new(map))
            }
        }
        d.deserialize_any(PresetOrTable)
    }
}
