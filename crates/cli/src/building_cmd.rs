//! `semsim building generate|check`.

use crate::config::SemsimConfig;
use clap::{Args, Subcommand};
use scanner::{generate_building, Building, BuildingGeometry};
use std::path::PathBuf;

/// Building subcommands.
#[derive(Subcommand)]
pub enum BuildingCommand {
    /// Generate a building (corridor, rooms, doors, stairs, clutter); the same seed gives the same building.
    Generate(GenerateArgs),
    /// Validate a building description and summarise it.
    Check(CheckArgs),
}

/// Arguments of `semsim building generate`.
#[derive(Args)]
pub struct GenerateArgs {
    /// Random seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Output file (.toml or .json).
    #[arg(long, value_name = "FILE")]
    out: PathBuf,
}

/// Arguments of `semsim building check`.
#[derive(Args)]
pub struct CheckArgs {
    /// The building file.
    file: PathBuf,
}

/// Runs a building subcommand.
pub fn run(c: BuildingCommand, cfg: &SemsimConfig) -> anyhow::Result<()> {
    match c {
        BuildingCommand::Generate(a) => {
            let b = generate_building(a.seed, &cfg.generator)?;
            b.save(&a.out)?;
            println!("wrote {}: {}", a.out.display(), summary(&b));
        }
        BuildingCommand::Check(a) => {
            let b = Building::load(&a.file)?;
            println!("{}: valid; {}", a.file.display(), summary(&b));
        }
    }
    Ok(())
}

/// One line: what the building holds.
pub fn summary(b: &Building) -> String {
    let doors: Vec<_> = b.walls.iter().flat_map(|w| &w.doors).collect();
    let leaves = doors.iter().filter(|d| d.leaf.is_some()).count();
    let parts = BuildingGeometry::new(b).parts().len();
    format!(
        "{:.1} x {:.1} m, {} walls, {} door openings ({} with leaves), {} staircases, {} boxes, {} solid parts",
        b.floor.max_m[0] - b.floor.min_m[0],
        b.floor.max_m[1] - b.floor.min_m[1],
        b.walls.len(),
        doors.len(),
        leaves,
        b.stairs.len(),
        b.boxes.len(),
        parts
    )
}
