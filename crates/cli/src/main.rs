//! `semsim`: from 3D laser scans of a building to a judged semantic simulation.
//! A thin binary over the library crates; it maps errors to exit codes
//! (0 success, 1 the job failed, 2 bad input or usage).

mod bench;
mod building_cmd;
mod console_cmd;
mod convert;
mod demo;
mod exit;
mod export;
mod info;
mod interrupt;
mod map;
mod print;
mod progress;
mod register;
mod report_cmd;
mod run;
mod scan;
mod scan_input;
mod simulate;

use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

/// semsim: semantic simulation from 3D laser scans.
#[derive(Parser)]
#[command(name = "semsim", version, about, long_about = None)]
struct Cli {
    /// Optional configuration file (TOML); every run writes the configuration it used beside its outputs.
    #[arg(long, global = true, value_name = "FILE")]
    config: Option<PathBuf>,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run the whole chain on the built-in default building and write everything to a folder.
    Demo(demo::DemoArgs),
    /// Convert a point cloud between formats (picked by extension: .pcd .ply .xyz .txt .3d
    /// .e57 .las .laz; .mcap ROS 2 bags are read).
    Convert(convert::ConvertArgs),
    /// Print what a point cloud file holds.
    Info(info::InfoArgs),
    /// Register scans with ICP: a pair (SOURCE TARGET) or, with --sequence, a whole sequence.
    Register(register::RegisterArgs),
    /// Build the semantic map of a registered cloud (or of scans placed with --poses):
    /// semantic_map.json, labels.pcd and a picture of every stage.
    Map(map::MapArgs),
    /// Export a semantic map's world (or a building's) and optionally a robot for MuJoCo
    /// (mjcf), Gazebo (sdf) or a glTF viewer (gltf).
    Export(export::ExportArgs),
    /// Evaluate results against ground truth.
    #[command(subcommand)]
    Eval(map::EvalCommand),
    /// One command from scans to verdict: register, map, simulate the scenario in the map's
    /// world and judge it (exit 0 pass, 1 fail).
    Run(run::RunArgs),
    /// Scan a building with the virtual 3D laser from one or more poses.
    Scan(scan::ScanArgs),
    /// Run a scenario in a physics world of the building and judge it (exit 0 pass, 1 fail).
    Simulate(simulate::SimulateArgs),
    /// The operator console: a local web page showing the world in 3D, where you drive the
    /// robot live; each session is saved as a run folder.
    Console(console_cmd::ConsoleArgs),
    /// A run folder as one self-contained HTML file (3D world, trajectory, events, verdict).
    Report(report_cmd::ReportArgs),
    /// Benchmarks that print and save figures (ICP on CPU and GPU).
    #[command(subcommand)]
    Bench(bench::BenchCommand),
    /// Generate or check building descriptions.
    #[command(subcommand)]
    Building(building_cmd::BuildingCommand),
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let _ = e.print();
            return ExitCode::from(if e.use_stderr() { 2 } else { 0 });
        }
    };
    let default_config = cli.config.is_none();
    let config = match cli.config.as_deref() {
        Some(path) => pipeline::Config::load(path),
        None => Ok(pipeline::Config::default()),
    };
    let result = config
        .map_err(anyhow::Error::from)
        .and_then(|cfg| match cli.command {
            Command::Demo(a) => demo::run(a, &cfg),
            Command::Convert(a) => convert::run(a),
            Command::Info(a) => info::run(a),
            Command::Export(a) => export::run(a),
            Command::Register(a) => register::run(a, &cfg, default_config),
            Command::Scan(a) => scan::run(a, &cfg),
            Command::Map(a) => map::run(a, &cfg),
            Command::Run(a) => run::run(a, &cfg),
            Command::Eval(c) => map::run_eval(c),
            Command::Building(c) => building_cmd::run(c, &cfg),
            Command::Bench(c) => bench::run(c),
            Command::Simulate(a) => simulate::run(a, &cfg),
            Command::Console(a) => console_cmd::run(a),
            Command::Report(a) => report_cmd::run(a),
        });
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {}", printable(&format!("{e:#}")));
            ExitCode::from(exit::code_for(&e))
        }
    }
}

/// `text` with control characters (NUL bytes from a file, escape sequences) and byte-order marks
/// shown as `\u{..}` escapes, so a message quoting a file never drives the terminal.
fn printable(text: &str) -> String {
    text.chars()
        .map(|c| {
            if (c.is_control() && c != '\n' && c != '\t') || c == '\u{feff}' {
                c.escape_unicode().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}
