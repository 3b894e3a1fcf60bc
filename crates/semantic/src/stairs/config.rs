//! The configuration of staircase identification: the building codes' ranges a staircase
//! must fall in and the support each step needs (see the `stairs` module).

use crate::error::Result;
use cloud::check_range;
use serde::{Deserialize, Serialize};

/// Configuration of staircase identification.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct StairsConfig {
    /// Pixel edge of the height map.
    pub cell_m: f64,
    /// Fewest steps of a staircase.
    pub min_steps: u32,
    /// Plausible step heights: 0.10-0.23 m spans the building codes' risers (IBC 1011.5.2
    /// 102-178 mm, IRC R311.7.5.1 at most 196 mm, UK Approved Document K at most 220 mm,
    /// DIN 18065 140-200 mm) with a margin for measurement.
    pub rise_m: [f64; 2],
    /// Plausible tread depths: 0.20-0.45 m (IBC at least 279 mm, IRC 254 mm, UK 220 mm,
    /// DIN 18065 210-370 mm; longer treads are landings or garden steps).
    pub run_m: [f64; 2],
    /// Largest pace, twice the rise plus the run: the codes that bound it ask 0.55-0.70 m (UK
    /// Approved Document K) or 0.59-0.65 m (DIN 18065), which every stair people climb
    /// comfortably meets; 0.80 m leaves room for the measurement. A rise and a run each in
    /// range can still make no stair together (0.22 m risers on 0.42 m treads: a sparse side
    /// face's top edge read with too few, higher steps).
    pub max_pace_m: f64,
    /// Highest tread above the floor.
    pub max_height_m: f64,
    /// Fewest pixels of a level.
    pub min_level_pixels: usize,
    /// Narrowest staircase (codes ask 0.8-1.1 m, DIN 18065 0.5 m for secondary stairs): a
    /// narrower one was seen from its side only.
    pub min_width_m: f64,
    /// Fewest points on each step between its height and the one below (its tread, riser or
    /// side face): fewer are a glimpse of clutter, not a surface. Each of them is on a surface
    /// (see `min_surface_neighbours`), so 5 are a patch of a few spacings across; a registered
    /// map voxel-downsampled to 5 cm holds only 8-40 points on a whole step face (0.10-0.23 m
    /// by 0.20-0.45 m), and a face half hidden by clutter or seen at grazing angles fewer.
    pub min_step_points: usize,
    /// ... and at least this fraction of what the local density (the floor's around it)
    /// promises on a rise x run of surface (a step's riser or side face): the lowest step
    /// loses its bottom centimetres to the floor band and is seen at grazing angles from one
    /// side only, which leaves a fifth of the promise; less is no surface of that size.
    pub min_step_fill: f64,
    /// Width given to a staircase seen from its side only.
    pub default_width_m: f64,
    /// The direction of ascent snaps to a wall's (or its normal's) within this angle.
    pub snap_direction_deg: f64,
    /// A point of a candidate lies on a surface if it has this many neighbours within
    /// `surface_radius_spacings` times the candidate's point spacing (see `surface`): a surface
    /// sampled at spacing d puts about a dozen points within 2d of an inner point and 3-5 of
    /// a corner's; a mixed pixel floating in front of a depth edge has hardly any (0: keep all).
    pub min_surface_neighbours: usize,
    /// The neighbourhood's radius in point spacings (the median nearest-neighbour distance).
    pub surface_radius_spacings: f64,
}

impl Default for StairsConfig {
    fn default() -> Self {
        StairsConfig {
            cell_m: 0.05,
            min_steps: 3,
            rise_m: [0.10, 0.23],
            run_m: [0.20, 0.45],
            max_pace_m: 0.80,
            max_height_m: 2.6,
            min_level_pixels: 3,
            min_width_m: 0.6,
            min_step_points: 5,
            min_step_fill: 0.15,
            default_width_m: 1.0,
            snap_direction_deg: 10.0,
            min_surface_neighbours: 3,
            surface_radius_spacings: 3.0,
        }
    }
}

impl StairsConfig {
    pub(crate) fn validate(&self) -> Result<()> {
        check_range(
            "stairs.cell_m",
            self.cell_m,
            1e-3,
            10.0,
            "within 0.001..10 m",
        )?;
        check_range(
            "stairs.min_steps",
            self.min_steps as f64,
            2.0,
            1000.0,
            "within 2..1000",
        )?;
        check_range(
            "stairs.rise_m[0]",
            self.rise_m[0],
            0.01,
            1.0,
            "within 0.01..1 m",
        )?;
        check_range(
            "stairs.rise_m[1]",
            self.rise_m[1],
            self.rise_m[0],
            1.0,
            "within rise_m[0]..1 m",
        )?;
        check_range(
            "stairs.run_m[0]",
            self.run_m[0],
            0.01,
            2.0,
            "within 0.01..2 m",
        )?;
        check_range(
            "stairs.run_m[1]",
            self.run_m[1],
            self.run_m[0],
            2.0,
            "within run_m[0]..2 m",
        )?;
        check_range(
            "stairs.max_pace_m",
            self.max_pace_m,
            0.1,
            10.0,
            "within 0.1..10 m",
        )?;
        check_range(
            "stairs.max_height_m",
            self.max_height_m,
            0.1,
            100.0,
            "within 0.1..100 m",
        )?;
        check_range(
            "stairs.min_level_pixels",
            self.min_level_pixels as f64,
            1.0,
            1e6,
            "at least 1",
        )?;
        check_range(
            "stairs.min_width_m",
            self.min_width_m,
            0.0,
            100.0,
            "within 0..100 m",
        )?;
        check_range(
            "stairs.min_step_points",
            self.min_step_points as f64,
            0.0,
            1e6,
            "within 0..1e6",
        )?;
        check_range(
            "stairs.min_step_fill",
            self.min_step_fill,
            0.0,
            10.0,
            "within 0..10",
        )?;
        check_range(
            "stairs.default_width_m",
            self.default_width_m,
            0.01,
            100.0,
            "within 0.01..100 m",
        )?;
        check_range(
            "stairs.snap_direction_deg",
            self.snap_direction_deg,
            0.0,
            45.0,
            "within 0..45 deg",
        )?;
        check_range(
            "stairs.min_surface_neighbours",
            self.min_surface_neighbours as f64,
            0.0,
            100.0,
            "within 0..100",
        )?;
        check_range(
            "stairs.surface_radius_spacings",
            self.surface_radius_spacings,
            1.0,
            10.0,
            "within 1..10",
        )?;
        Ok(())
    }
}
