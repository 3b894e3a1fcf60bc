//! The whole chain in memory: scans -> registration -> semantic map -> simulated world ->
//! judged outcome. No stage reads what the one before it wrote: every stage runs in memory, and
//! only when the scenario has been judged are the stages' files written, so a run that fails
//! (a scenario naming a door the map does not have, say) leaves no partial output.

use crate::config::Config;
use crate::error::Result;
use crate::map::{build_map, write_map};
use crate::register::{open_registrar, register_scans, write_registration, Registration};
use crate::scan_folder::SequenceInput;
use crate::scans::place_and_merge;
use crate::simulate::{simulate, write_simulation, ScenarioChoice, ScenarioSource};
use cloud::PointCloud;
use glam::DVec3;
use semantic::MapOutput;
use sim::{Outcome, StartPose, WorldSpec};
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};

/// What the chain reports as it goes (the CLI prints it; the console streams it). Every
/// method has an empty default.
pub trait Observer {
    /// Stage `step` of 3 begins.
    fn stage_started(&mut self, _step: usize, _title: &str) {}
    /// The registration device is open (for `auto`: which one, and why).
    fn device_opened(&mut self, _description: &str) {}
    /// `done` of `total` scans registered.
    fn scans_registered(&mut self, _done: usize, _total: usize) {}
    /// The registration is done.
    fn registered(&mut self, _registration: &Registration) {}
    /// The semantic map is done.
    fn mapped(&mut self, _map: &MapOutput) {}
    /// The simulation has reached `sim_time_s` of at most `time_limit_s`; `Break` stops it
    /// cleanly (the outcome then says it was interrupted).
    fn simulating(&mut self, _sim_time_s: f64, _time_limit_s: f64) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }
    /// A scenario was planned in the map's world (no scenario was given).
    fn planned(&mut self, _planned: &sim::PlannedScenario) {}
    /// The scenario ran and was judged; `report` is what `report.md` holds.
    fn simulated(&mut self, _outcome: &Outcome, _report: &str) {}
    /// Every stage's files are written into `dirs`.
    fn written(&mut self, _outcome: &ChainOutcome, _dirs: &ChainDirs) {}
}

/// An observer that reports nothing.
pub struct Quiet;

impl Observer for Quiet {}

/// The output folders of a chain run.
#[derive(Debug, Clone)]
pub struct ChainDirs {
    /// `registration/`: poses.txt, map.pcd, registration.json, config.toml.
    pub registration: PathBuf,
    /// `map/`: semantic_map.json, labels.pcd, the pictures, config.toml.
    pub map: PathBuf,
    /// `simulation/`: events.jsonl, trajectory.csv, report.md, scenario.toml.
    pub simulation: PathBuf,
}

impl ChainDirs {
    /// The three folders under `out`.
    pub fn under(out: &Path) -> ChainDirs {
        ChainDirs {
            registration: out.join("registration"),
            map: out.join("map"),
            simulation: out.join("simulation"),
        }
    }
}

/// What [`scans_to_verdict`] made.
#[derive(Debug)]
pub struct ChainOutcome {
    /// The registered sequence.
    pub registration: Registration,
    /// The registered scans, merged in the world frame (the map's input).
    pub cloud: PointCloud,
    /// The semantic map and its stage images.
    pub map: MapOutput,
    /// The scenario that ran (given, or planned in the map's world).
    pub scenario: ScenarioSource,
    /// The simulation, judged.
    pub simulation: Outcome,
}

impl ChainOutcome {
    /// Whether the scenario's verdict passed.
    pub fn passed(&self) -> bool {
        self.simulation.verdict.passed
    }
}

/// Scans to verdict: registers the scans (already read, in `input`'s order) from their
/// odometry, maps the registered scans, builds the map's world and judges the scenario in it
/// (given, or planned in the map's world from where scan 0's sensor stood), writing each stage
/// into its folder under `out`.
pub fn scans_to_verdict(
    input: &SequenceInput,
    scans: Vec<PointCloud>,
    scenario: &ScenarioChoice,
    cfg: &Config,
    out: &Path,
    observer: &mut dyn Observer,
) -> Result<ChainOutcome> {
    // 1. Registration: scan k against the map of scans 0..k-1, from the odometry (one scan
    //    alone defines the world).
    let title = match scans.len() {
        1 => "registration: one scan, which defines the world (nothing to register)".to_string(),
        n => format!(
            "registration ({}) of {n} scans",
            cfg.registration.icp.method.short_name()
        ),
    };
    observer.stage_started(1, &title);
    let mut registrar = open_registrar(&cfg.registration)?;
    observer.device_opened(registrar.description());
    let registration = register_scans(
        input,
        &scans,
        &cfg.registration,
        &mut registrar,
        &mut |d, t| observer.scans_registered(d, t),
    )?;
    observer.registered(&registration);

    // 2. Semantic map of the scans placed by their registered poses.
    observer.stage_started(2, "semantic map of the registered scans");
    let cloud = place_and_merge(
        &input.scans,
        scans,
        Some(&registration.poses),
        &cfg.transients,
    )?;
    let map = build_map(&cloud, &cfg.semantic)?;
    observer.mapped(&map);

    // 3. The map's world, the scenario (given, or planned from scan 0's sensor position: free
    //    space by construction) run in it and judged.
    observer.stage_started(
        3,
        &format!("simulation of {} in the map's world", scenario.title()),
    );
    let world = WorldSpec::from_semantic_map(&map.map)?;
    let start = first_sensor_in_map(&registration, &map);
    let scenario = scenario.resolve(&world, start)?;
    if let Some(p) = &scenario.planned {
        observer.planned(p);
    }
    let limit_s = scenario.scenario.time_limit_s;
    let simulation = simulate(&world, &scenario, &mut |t| observer.simulating(t, limit_s))?;
    observer.simulated(&simulation, &scenario.report(&simulation));

    // 4. Every stage's files, now that the whole chain has run.
    let outcome = ChainOutcome {
        registration,
        cloud,
        map,
        scenario,
        simulation,
    };
    let dirs = ChainDirs::under(out);
    write_chain(&outcome, &outcome.scenario, cfg, &dirs)?;
    observer.written(&outcome, &dirs);
    Ok(outcome)
}

/// Where scan 0's sensor stood, in the map's frame (the registered world levelled), as a
/// start on the map's floor; `None` without scans.
fn first_sensor_in_map(registration: &Registration, map: &MapOutput) -> Option<StartPose> {
    let world_from_scan = registration.poses.first()?.world_from_scan;
    let map_from_input = map.map.input_from_map().inverse();
    let p: DVec3 = map_from_input.transform_point3(world_from_scan.translation);
    Some(StartPose {
        x_m: p.x,
        y_m: p.y,
        yaw_deg: 0.0,
        z_m: 0.0,
    })
}

/// Writes each stage's files (and the configuration) into its folder.
pub fn write_chain(
    outcome: &ChainOutcome,
    scenario: &ScenarioSource,
    cfg: &Config,
    dirs: &ChainDirs,
) -> Result<()> {
    for dir in [&dirs.registration, &dirs.map, &dirs.simulation] {
        create_dir(dir)?;
    }
    write_registration(&outcome.registration, &dirs.registration)?;
    cfg.write_beside(&dirs.registration)?;
    write_map(&outcome.map, &outcome.cloud, &dirs.map)?;
    cfg.write_beside(&dirs.map)?;
    write_simulation(&outcome.simulation, scenario, &dirs.simulation)?;
    Ok(())
}

/// Creates a folder and its parents.
pub(crate) fn create_dir(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| cloud::CloudError::io(dir, e))?;
    Ok(())
}
