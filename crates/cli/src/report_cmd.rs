//! `semsim report RUN_DIR --html OUT.html`: a run folder (from `semsim simulate`, `semsim run`
//! or a console session) as one self-contained HTML file to share: the world in 3D, the
//! trajectory with its events marked, the verdict and rules, and a time slider. It opens from
//! disk with no server and no network. The CLI picks the world; the console crate builds the
//! page.

use crate::exit::bad_input;
use clap::Args;
use console::RecordedRun;
use pipeline::ScenarioSource;
use std::path::PathBuf;

/// Arguments of `semsim report`.
#[derive(Args)]
pub struct ReportArgs {
    /// The run folder (events.jsonl, trajectory.csv, report.md, scenario.toml).
    #[arg(value_name = "RUN_DIR")]
    run_dir: PathBuf,
    /// The HTML file to write (written atomically).
    #[arg(long, value_name = "OUT.html")]
    html: PathBuf,
    /// The semantic map the run was simulated in (semantic_map.json); a run folder does not
    /// record it.
    #[arg(long, value_name = "FILE", conflicts_with = "building")]
    map: Option<PathBuf>,
    /// The building the run was simulated in (TOML/JSON, or "default"); default: the run's
    /// scenario's `building` (the built-in building for the default scenario).
    #[arg(long, value_name = "FILE")]
    building: Option<PathBuf>,
    /// A registered point cloud to embed as a layer, downsampled to at most 30,000 points
    /// (about 0.5 MB more in the file); default: none.
    #[arg(long, value_name = "FILE")]
    cloud: Option<PathBuf>,
}

/// Runs `semsim report`.
pub fn run(a: ReportArgs) -> anyhow::Result<()> {
    let recorded = RecordedRun::load(&a.run_dir)?;
    let source = ScenarioSource::load(Some(&a.run_dir.join("scenario.toml")))?;
    let inputs = console::ConsoleInputs {
        map: a.map.clone(),
        building: a.building.clone(),
        ..console::ConsoleInputs::default()
    };
    let world = inputs
        .world_source(&source.scenario, &source.base_dir)
        .load()?;
    if let Some(parent) = a.html.parent().filter(|p| !p.as_os_str().is_empty()) {
        if !parent.is_dir() {
            return Err(bad_input(format!(
                "{}: the folder for the report does not exist",
                parent.display()
            )));
        }
    }
    let cloud = match &a.cloud {
        Some(c) => Some(console::CloudLayer::from_file(
            c,
            console::REPORT_CLOUD_POINTS,
        )?),
        None => None,
    };
    let html = console::report_html(
        &world,
        &source.robot,
        source.scenario.start,
        &recorded,
        cloud.as_ref(),
    )?;
    console::write_report(&a.html, &html)?;
    println!(
        "wrote {} ({} trajectory points, {} events, verdict: {})",
        a.html.display(),
        recorded.trajectory.len(),
        recorded.events.len(),
        recorded.verdict
    );
    Ok(())
}
