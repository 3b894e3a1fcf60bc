//! `semsim building generate|check`.

use clap::{Args, Subcommand};
use pipeline::Config;
use scanner::{generate_building, Building, Style};
use std::path::PathBuf;

/// Building subcommands.
#[derive(Subcommand)]
pub enum BuildingCommand {
    /// Generate a building of a style (clean, office, garage, hall, mixed); the same seed and
    /// style give the same building.
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
    /// The style: clean (corridor, rooms, doors, stairs, clutter boxes), office (desks and
    /// chairs on legs, cabinets, glass, partial partitions, two staircases), garage (pillars,
    /// cars, beams, ducts, a ramp), hall (open hall, walls not at right angles, pillars) or
    /// mixed (one of them, by seed); default: the configuration's `[generator] style`.
    #[arg(long, value_name = "STYLE", value_parser = parse_style)]
    style: Option<Style>,
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

/// Parses a style's name.
fn parse_style(s: &str) -> Result<Style, String> {
    Style::from_name(s).ok_or_else(|| {
        let names: Vec<&str> = Style::ALL.iter().map(Style::name).collect();
        format!("'{s}' is not a style (one of: {})", names.join(", "))
    })
}

/// Runs a building subcommand.
pub fn run(c: BuildingCommand, cfg: &Config) -> anyhow::Result<()> {
    match c {
        BuildingCommand::Generate(a) => {
            let mut gen = cfg.generator.clone();
            if let Some(style) = a.style {
                gen.style = style;
            }
            let b = generate_building(a.seed, &gen)?;
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
