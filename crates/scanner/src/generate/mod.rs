//! Procedural buildings in several styles. The same seed and configuration always give the
//! same building, and every building is validated before it is returned.
//!
//! - `clean` (default, the original generator): a corridor with rooms, doors in every state,
//!   a staircase, clutter boxes ([`clean`]).
//! - `office`: a corridor with rooms holding desks and chairs on legs, cabinets and shelves,
//!   a glass partition and a glass door, a partial-height partition, clutter in a doorway,
//!   one or two staircases ([`office`]).
//! - `garage`: a wide low hall with rows of pillars, parked cars, downstand beams, a duct and
//!   a pipe under the ceiling, a ramp and a staircase ([`garage`]).
//! - `hall`: a wide open hall with walls not at right angles, a side room, a few pillars,
//!   furniture and a staircase ([`hall`]).
//! - `mixed`: one of the above, picked by the seed.

mod clean;
mod furniture;
mod garage;
mod hall;
mod layout;
mod office;
mod stairs;

use crate::building::Building;
use crate::error::Result;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// What kind of building the generator makes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Style {
    /// The original generator: corridor, rooms, doors, a staircase, clutter boxes.
    #[default]
    Clean,
    /// Offices: furniture on legs, cabinets, glass, partial partitions, two staircases.
    Office,
    /// An underground car park: pillars, cars, beams, ducts, a ramp, a staircase.
    Garage,
    /// A wide open hall with walls not at right angles.
    Hall,
    /// One of the others, picked by the seed.
    Mixed,
}

impl Style {
    /// Every style, in the order of the CLI's help.
    pub const ALL: [Style; 5] = [
        Style::Clean,
        Style::Office,
        Style::Garage,
        Style::Hall,
        Style::Mixed,
    ];

    /// The style's name as written in files and on the command line.
    pub fn name(&self) -> &'static str {
        match self {
            Style::Clean => "clean",
            Style::Office => "office",
            Style::Garage => "garage",
            Style::Hall => "hall",
            Style::Mixed => "mixed",
        }
    }

    /// The style of that name, if any.
    pub fn from_name(name: &str) -> Option<Style> {
        Style::ALL.into_iter().find(|s| s.name() == name)
    }
}

impl std::fmt::Display for Style {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Ranges the generator draws from. The ranges are those of the `clean` style; the other
/// styles draw from their own human-scale ranges (documented in their files).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct GeneratorConfig {
    /// Which kind of building.
    pub style: Style,
    /// Corridor length range.
    pub corridor_length_m: [f64; 2],
    /// Corridor clear width range.
    pub corridor_width_m: [f64; 2],
    /// Room depth range (across the corridor).
    pub room_depth_m: [f64; 2],
    /// Room width range (along the corridor).
    pub room_width_m: [f64; 2],
    /// Ceiling height range.
    pub ceiling_height_m: [f64; 2],
    /// Most clutter boxes per room.
    pub max_boxes_per_room: u32,
}

impl Default for GeneratorConfig {
    fn default() -> Self {
        GeneratorConfig {
            style: Style::Clean,
            corridor_length_m: [14.0, 28.0],
            corridor_width_m: [1.8, 3.0],
            room_depth_m: [3.5, 6.0],
            room_width_m: [3.5, 6.5],
            ceiling_height_m: [2.5, 3.2],
            max_boxes_per_room: 3,
        }
    }
}

/// Generates a building of `config.style` from `seed`, validated.
pub fn generate_building(seed: u64, config: &GeneratorConfig) -> Result<Building> {
    let b = match resolve_style(config.style, seed) {
        Style::Office => office::generate(seed),
        Style::Garage => garage::generate(seed),
        Style::Hall => hall::generate(seed),
        Style::Clean | Style::Mixed => clean::generate(seed, config),
    };
    b.validate(Path::new(&format!(
        "<generated {} building, seed {seed}>",
        config.style
    )))?;
    Ok(b)
}

/// The concrete style `style` stands for with `seed`: `mixed` picks one of the four others
/// from the seed (a stream of its own, so the building itself is that style's for the seed).
pub fn resolve_style(style: Style, seed: u64) -> Style {
    if style != Style::Mixed {
        return style;
    }
    let mut r = cloud::Rng::stream(seed, 0x0057_171e);
    [Style::Clean, Style::Office, Style::Garage, Style::Hall][r.int(0, 3) as usize]
}
