//! `semsim demo`: the whole chain on the built-in default building: building -> virtual scans
//! with ground truth and noisy odometry -> registration from the odometry -> semantic map ->
//! the default scenario judged in the map's world, each stage scored against ground truth.

use crate::config::SemsimConfig;
use clap::Args;
use scanner::Building;
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
pub fn run(a: DemoArgs, cfg: &SemsimConfig) -> anyhow::Result<()> {
    let t0 = Instant::now();
    let building = Building::default_building()?;
    std::fs::create_dir_all(&a.out).map_err(|e| cloud::CloudError::io(&a.out, e))?;
    let building_path = a.out.join("building.toml");
    building.save(&building_path)?;
    println!("semsim demo -> {}", a.out.display());
    println!("building: {}", crate::building_cmd::summary(&building));
    let summary =
        crate::scan::write_scans(&building, &Building::default_survey_poses(), cfg, &a.out)?;
    summary.print();
    println!("  wrote {}", building_path.display());
    let input = crate::register::collect_sequence(std::slice::from_ref(&a.out), None, None)?;
    let scans = crate::map::read_scans(&input.files, None)?;
    let scenario = sim::Scenario::default_scenario()?;
    let text = sim::Scenario::default_scenario_toml();
    let outcome = crate::run::scans_to_verdict(
        &input,
        scans,
        (&scenario, text, std::path::Path::new(".")),
        cfg,
        &a.out,
    )?;
    report_against_truth(&input, &a.out, &building, &outcome)?;
    println!(
        "verdict: {} (rerun: semsim simulate --map {} --scenario {} --out DIR)",
        if outcome.passed { "PASSED" } else { "FAILED" },
        a.out.join("map/semantic_map.json").display(),
        a.out.join("simulation/scenario.toml").display()
    );
    println!("done in {:.1} s", t0.elapsed().as_secs_f64());
    Ok(())
}

/// Scores the demo's registration (pose errors of odometry and registration) and semantic map
/// (per-class F1, wall endpoint error, stairs) against the ground truth.
fn report_against_truth(
    input: &crate::register::SequenceInput,
    out: &std::path::Path,
    building: &Building,
    outcome: &crate::run::Outcome,
) -> anyhow::Result<()> {
    let registered = cloud::read_poses(&out.join("registration/poses.txt"))?;
    let worst = |poses: &[glam::DAffine3]| {
        poses
            .iter()
            .zip(&input.truth)
            .fold((0.0f64, 0.0f64), |(m, d), (p, t)| {
                let (em, ed) = crate::register::pose_error(
                    &(input.truth[0].inverse() * *t),
                    &(poses[0].inverse() * *p),
                );
                (m.max(em), d.max(ed))
            })
    };
    let (om, od) = worst(&input.odometry);
    let reg: Vec<glam::DAffine3> = registered.iter().map(|p| p.world_from_scan).collect();
    let (rm, rd) = worst(&reg);
    println!(
        "against ground truth: worst pose error odometry {om:.3} m / {od:.2} deg -> registered {rm:.4} m / {rd:.3} deg"
    );
    let ev = semantic::evaluate(&outcome.map, building, Some(&outcome.cloud));
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
    Ok(())
}
