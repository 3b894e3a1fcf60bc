//! semsim's chain as a library: from scans to a judged simulation without the command line.
//!
//! - [`scan_folder`]: the one owner of the scan-folder format (scans + `poses.txt` +
//!   `odometry.txt` + `entities.json`), written by [`write_scan_folder`] and read as a
//!   sequence by [`read_sequence`] (real sequences too: 3DTK `.pose` files, `--odometry`, a
//!   multi-scan E57 or a ROS 2 bag, read by the `interop` crate with [`ReadOptions`]).
//! - [`read_scans`], [`place_and_merge`]: scans read with a range limit, without no-echo
//!   readings ([`find_no_echo`]), mixed pixels ([`find_mixed_pixels`], [`MixedPixelConfig`])
//!   and isolated points ([`find_outliers`], [`OutlierConfig`]),
//!   placed by their poses and merged.
//! - The stages: [`register_scans`], [`build_map`], [`simulate`], each with a writer of its
//!   files; [`scans_to_verdict`] runs all three in memory (no stage reads what the one before
//!   wrote) and reports to an [`Observer`] as it goes.
//! - Ground truth: [`relative_pose_errors`], [`worst_pose_error`]; the demo
//!   ([`prepare_demo`], [`score_demo`]); the ICP benchmark ([`bench_icp_case`]); charts
//!   ([`plot_rmse`], drawn with an embedded DejaVu Sans, `assets/LICENSE.DejaVu`).
//! - [`export_world_file`]: a map's or building's world (and a robot) for MuJoCo, Gazebo or a
//!   glTF viewer.
//! - [`Config`]: one section per stage, as `--config` files hold it.
//!
//! ```no_run
//! use pipeline::{read_scans, read_sequence, scans_to_verdict, Config, Quiet, ScenarioChoice};
//! use std::path::{Path, PathBuf};
//!
//! # fn main() -> pipeline::Result<()> {
//! let input = read_sequence(&[PathBuf::from("semsim-demo")], None, None, &Default::default())?;
//! let scans = read_scans(&input.scans, Some(30.0))?;
//! // No scenario file: one is planned in the map's world (`[plan]` of the configuration).
//! let scenario = ScenarioChoice::from_file_or_plan(None, &Config::default().plan)?;
//! let outcome = scans_to_verdict(&input, scans, &scenario, &Config::default(), Path::new("out"), &mut Quiet)?;
//! println!("{} walls, verdict {}", outcome.map.map.of_class(cloud::EntityClass::Wall).count(), outcome.passed());
//! # Ok(())
//! # }
//! ```
//!
//! ```
//! // Pose errors against ground truth are taken relative to each sequence's first pose.
//! use glam::{DAffine3, DVec3};
//! let truth = [DAffine3::IDENTITY, DAffine3::from_translation(DVec3::X)];
//! let moved = [DAffine3::from_translation(DVec3::Y), DAffine3::from_translation(DVec3::new(1.02, 1.0, 0.0))];
//! let (m, deg) = pipeline::worst_pose_error(&truth, &moved);
//! assert!((m - 0.02).abs() < 1e-9 && deg < 1e-9);
//! ```
#![warn(missing_docs)]

mod bench_icp;
mod chain;
mod config;
mod demo;
mod error;
mod export;
mod guard;
mod guess;
mod map;
mod mixed_pixels;
mod no_echo;
mod outliers;
mod plot;
mod register;
pub mod scan_folder;
mod scans;
mod score;
mod simulate;
mod truth;

pub use bench_icp::{bench_icp_case, icp_bench_cases, open_bench_gpu, IcpBenchRow};
pub use chain::{scans_to_verdict, write_chain, ChainDirs, ChainOutcome, Observer, Quiet};
pub use config::Config;
pub use demo::{prepare_demo, score_demo, DemoScans, DemoScore};
pub use error::{PipelineError, Result};
pub use export::{export_world_file, parse_start, ExportSummary, WorldSource};
pub use guard::{check_output_dir, refuse_overwriting_inputs};
pub use guess::{guess_from_text, parse_guess};
pub use interop::ExportFormat;
pub use interop::ReadOptions;
pub use map::{build_map, map_summary, write_map, MAP_PICTURES};
pub use mixed_pixels::{find_mixed_pixels, remove_mixed_pixels, MixedPixelConfig};
pub use no_echo::{
    drop_no_echo, find_no_echo, NoEcho, NO_ECHO_BAND_M, NO_ECHO_MIN_POINTS, NO_ECHO_MIN_SHARE,
};
pub use outliers::{find_outliers, remove_outliers, OutlierConfig, OUTLIER_MIN_POINTS};
pub use plot::{line_chart, plot_rmse, Series};
pub use register::{
    clear_transients_from_map, open_registrar, register_scans, write_registration, PairReport,
    Registration, ScanRow,
};
pub use registration::{drop_transients, find_transients, TransientConfig};
pub use scan_folder::{
    read_scan_set, read_sequence, write_scan_folder, ScanFolderSummary, ScanSource, SequenceInput,
};
pub use scans::{merge_scan_files, place_and_merge, read_scans, read_scans_with};
pub use score::score_map_file;
pub use simulate::{
    simulate, world_and_scenario, write_simulation, ScenarioChoice, ScenarioSource,
};
pub use truth::{relative_pose_errors, worst_pose_error};
