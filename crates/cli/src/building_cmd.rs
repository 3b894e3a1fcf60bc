//! `semsim building generate|check`.

use clap::{Args, Subcommand};
use pipeline::Config;
use scanner::{generate_building, Building};
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
pub fn run(c: BuildingCommand, cfg: &Config) -> anyhow::Result<()> {
    match c {
        BuildingCommand::Generate(a) => {
            let b = generate_building(a.seed, &cfg.generator)?;
            b.save(&a.out)?;
            println!("wrote {}: {}", a.out.display(), b.summary());
        }
        BuildingCommand::Check(a) => {
            let b = Building::load(&a.file)?;
            println!("{}: valid; {}", a.file.display(), b.summary());
        }
    }
    Ok(())
}
