//! What the commands print about each stage of the chain, and the observer that prints it
//! as [`pipeline::scans_to_verdict`] goes.

use crate::progress::scan_bar;
use indicatif::ProgressBar;
use pipeline::{ChainDirs, ChainOutcome, Observer, Registration};
use semantic::MapOutput;
use std::ops::ControlFlow;
use std::path::Path;

/// Prints the registration table (with errors against ground truth where known).
pub fn registration(reg: &Registration) {
    println!(
        "{:<10} {:>5} {:>10} {:>8} {:>9} {:>10} {:>10}",
        "scan", "iters", "RMSE m", "fitness", "ms", "err m", "err deg"
    );
    for r in &reg.rows {
        let (e_m, e_deg) = (
            r.error_m.unwrap_or(f64::NAN),
            r.error_deg.unwrap_or(f64::NAN),
        );
        println!(
            "{:<10} {:>5} {:>10.4} {:>8.3} {:>9.1} {e_m:>10.4} {e_deg:>10.3}",
            r.scan, r.iterations, r.rmse_m, r.fitness, r.total_ms
        );
    }
}

/// Prints what `write_registration` wrote.
pub fn registration_written(reg: &Registration, dir: &Path) {
    println!(
        "wrote {}/poses.txt, map.pcd ({} points), registration.json",
        dir.display(),
        reg.sequence.map.len()
    );
}

/// Prints the semantic map's stage times and its entity counts.
pub fn map(output: &MapOutput) {
    let times: Vec<String> = output
        .timings
        .iter()
        .map(|t| format!("{} {:.0}", t.stage, t.ms))
        .collect();
    println!(
        "stages (ms): {} = {:.0} ms",
        times.join(", "),
        output.total_ms()
    );
    println!("{}", pipeline::map_summary(&output.map));
}

/// Prints what `write_map` wrote (and the configuration beside it).
pub fn map_written(dir: &Path) {
    println!(
        "wrote {}/semantic_map.json, labels.pcd, {}, config.toml",
        dir.display(),
        pipeline::MAP_PICTURES.join(", ")
    );
}

/// Prints what `write_simulation` wrote.
pub fn simulation_written(dir: &Path) {
    println!(
        "wrote {}/events.jsonl, trajectory.csv, doors.csv, report.md, scenario.toml",
        dir.display()
    );
}

/// `Ok` for a passed verdict; an error (exit 1) naming the report for a failed or interrupted one.
pub fn verdict(outcome: &sim::Outcome, dir: &Path) -> anyhow::Result<()> {
    if let Some(t) = outcome.verdict.interrupted_at_s {
        anyhow::bail!(
            "verdict: FAILED: interrupted at {t:.2} s (events so far in {})",
            dir.display()
        );
    }
    if !outcome.verdict.passed {
        anyhow::bail!("verdict: FAILED (see {})", dir.join("report.md").display());
    }
    println!("verdict: PASSED");
    Ok(())
}

/// Prints the chain's stages as they finish, with a progress bar while scans register.
#[derive(Default)]
pub struct Printer {
    bar: Option<ProgressBar>,
    sim_bar: Option<ProgressBar>,
}

impl Printer {
    /// Clears the progress bars still shown.
    pub fn clear(&mut self) {
        for bar in [self.bar.take(), self.sim_bar.take()].into_iter().flatten() {
            bar.finish_and_clear();
        }
    }
}

impl Observer for Printer {
    fn stage_started(&mut self, step: usize, title: &str) {
        println!("{step}/3 {title}:");
    }

    fn device_opened(&mut self, description: &str) {
        eprintln!("device: {description}");
    }

    fn scans_registered(&mut self, done: usize, total: usize) {
        self.bar
            .get_or_insert_with(|| scan_bar(total, "registering"))
            .set_position(done as u64);
    }

    fn registered(&mut self, reg: &Registration) {
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
        registration(reg);
    }

    fn mapped(&mut self, output: &MapOutput) {
        map(output);
    }

    fn simulating(&mut self, sim_time_s: f64, time_limit_s: f64) -> ControlFlow<()> {
        self.sim_bar
            .get_or_insert_with(|| crate::progress::sim_bar(time_limit_s))
            .set_position(sim_time_s as u64);
        if crate::interrupt::requested() {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    }

    fn simulated(&mut self, _outcome: &sim::Outcome, report: &str) {
        if let Some(bar) = self.sim_bar.take() {
            bar.finish_and_clear();
        }
        println!("{report}");
    }

    fn written(&mut self, outcome: &ChainOutcome, dirs: &ChainDirs) {
        registration_written(&outcome.registration, &dirs.registration);
        map_written(&dirs.map);
        simulation_written(&dirs.simulation);
    }
}
