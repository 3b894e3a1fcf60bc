//! `semsim demo`: the whole chain on the built-in default building: building -> virtual scans
//! with ground truth and noisy odometry -> registration from the odometry -> semantic map ->
//! the default scenario judged in the map's world, each stage scored against ground truth.

use clap::Args;
use pipeline::{
    prepare_demo, scans_to_verdict, score_demo, Config, ScenarioChoice, ScenarioSource,
};
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `semsim demo`.
#[derive(Args)]
pub struct DemoArgs {
    /// Output folder.
    #[arg(long, value_name = "DIR", default_value = "semsim-demo")]
    out: PathBuf,
}

/// Runs the demo.
pub fn run(a: DemoArgs, cfg: &Config) -> anyhow::Result<()> {
    pipeline::check_output_dir(&a.out)?;
    let t0 = Instant::now();
    println!("semsim demo -> {}", a.out.display());
    let bar = crate::progress::scan_bar(0, "scanning");
    let mut demo = prepare_demo(&a.out, cfg, &mut |done, total| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
    })?;
    bar.finish_and_clear();
    println!("building: {}", demo.building.summary());
    crate::scan::print_summary(&demo.scanned);
    println!("  wrote {}", demo.building_file.display());

    // The demo's own scenario (it names the default building's door and stairs).
    let scenario = ScenarioChoice::Given(Box::new(ScenarioSource::load(None)?));
    let chain_t0 = Instant::now();
    crate::interrupt::install();
    let mut printer = crate::print::Printer::default();
    let chain = scans_to_verdict(
        &demo.input,
        std::mem::take(&mut demo.scans),
        &scenario,
        cfg,
        &a.out,
        &mut printer,
    )?;
    println!(
        "scans to verdict in {:.1} s",
        chain_t0.elapsed().as_secs_f64()
    );

    let score = score_demo(&demo, &chain);
    let ((om, od), (rm, rd)) = (score.odometry_error, score.registered_error);
    println!(
        "against ground truth: worst pose error odometry {om:.3} m / {od:.2} deg -> registered {rm:.4} m / {rd:.3} deg"
    );
    let ev = &score.map;
    println!(
        "against ground truth: map walls F1 {:.3}, door openings F1 {:.3}, door leaves F1 {:.3}, wall endpoint error {:.3} m, floor {}, ceiling {}{}",
        ev.walls.f1,
        ev.door_openings.f1,
        ev.doors.f1,
        ev.wall_endpoint_error_mean_m,
        if ev.floor.matched == 1 { "found" } else { "missed" },
        if ev.ceiling.matched == 1 { "found" } else { "missed" },
        ev.stairs_matches
            .iter()
            .map(|s| format!(", stairs {}/{} steps", s.steps, s.steps_truth))
            .collect::<String>()
    );
    println!(
        "verdict: {} (rerun: semsim simulate --map {} --scenario {} --out DIR)",
        if chain.passed() { "PASSED" } else { "FAILED" },
        a.out.join("map/semantic_map.json").display(),
        a.out.join("simulation/scenario.toml").display()
    );
    println!("done in {:.1} s", t0.elapsed().as_secs_f64());
    println!(
        "see it in 3D and drive the robot yourself: semsim console --map {} --cloud {} --scenario {} --out {}",
        a.out.join("map/semantic_map.json").display(),
        a.out.join("map/labels.pcd").display(),
        a.out.join("simulation/scenario.toml").display(),
        a.out.join("console").display()
    );
    Ok(())
}
