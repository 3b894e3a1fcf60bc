//! The settings of door-opening identification (see `openings`).

use crate::error::Result;
use cloud::check_range;
use serde::{Deserialize, Serialize};

/// Configuration of door-opening identification.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct OpeningConfig {
    /// Bin width along a wall.
    pub bin_m: f64,
    /// Height range above the floor where an opening has no wall face.
    pub door_level_m: [f64; 2],
    /// Narrowest opening.
    pub min_width_m: f64,
    /// Widest opening.
    pub max_width_m: f64,
    /// Blocked slivers up to this width inside an opening are ignored.
    pub max_pier_m: f64,
    /// Fraction of an opening's bins with a lintel above.
    pub min_lintel_coverage: f64,
    /// Fraction of an opening's bins with points seen through it (one-sided walls, and
    /// two-sided walls seen from one side only about the opening).
    pub min_evidence: f64,
    /// How far behind a one-sided wall's face (or a two-sided wall's far face) points count as
    /// seen through an opening.
    pub behind_m: f64,
}

impl Default for OpeningConfig {
    fn default() -> Self {
        OpeningConfig {
            bin_m: 0.05,
            door_level_m: [0.3, 1.8],
            min_width_m: 0.5,
            max_width_m: 2.5,
            max_pier_m: 0.15,
            min_lintel_coverage: 0.5,
            min_evidence: 0.25,
            behind_m: 1.0,
        }
    }
}

impl OpeningConfig {
    pub(crate) fn validate(&self) -> Result<()> {
        check_range(
            "openings.bin_m",
            self.bin_m,
            0.005,
            1.0,
            "within 0.005..1 m",
        )?;
        check_range(
            "openings.door_level_m[0]",
            self.door_level_m[0],
            0.0,
            10.0,
            "within 0..10 m",
        )?;
        check_range(
            "openings.door_level_m[1]",
            self.door_level_m[1] - self.door_level_m[0],
            0.05,
            10.0,
            "at least 0.05 m above door_level_m[0]",
        )?;
        check_range(
            "openings.min_width_m",
            self.min_width_m,
            0.05,
            100.0,
            "within 0.05..100 m",
        )?;
        check_range(
            "openings.max_width_m",
            self.max_width_m,
            self.min_width_m,
            100.0,
            "at least min_width_m",
        )?;
        check_range(
            "openings.max_pier_m",
            self.max_pier_m,
            0.0,
            10.0,
            "within 0..10 m",
        )?;
        check_range(
            "openings.min_lintel_coverage",
            self.min_lintel_coverage,
            0.0,
            1.0,
            "within 0..1",
        )?;
        check_range(
            "openings.min_evidence",
            self.min_evidence,
            0.0,
            1.0,
            "within 0..1",
        )?;
        check_range(
            "openings.behind_m",
            self.behind_m,
            0.0,
            100.0,
            "within 0..100 m",
        )?;
        Ok(())
    }
}
