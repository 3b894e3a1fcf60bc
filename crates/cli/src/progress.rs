//! The progress bars: work counted in scans, and simulated time.

use indicatif::{ProgressBar, ProgressStyle};

/// A bar over `total` scans with `msg` (e.g. "scanning") on its left.
pub fn scan_bar(total: usize, msg: &'static str) -> ProgressBar {
    let bar = ProgressBar::new(total as u64).with_style(
        ProgressStyle::with_template(
            "{msg:>10} [{bar:30}] {pos}/{len} scans, {elapsed} (eta {eta})",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar())
        .progress_chars("=> "),
    );
    bar.set_message(msg);
    bar
}

/// A bar over a simulation's time limit, in simulated seconds.
pub fn sim_bar(time_limit_s: f64) -> ProgressBar {
    let bar = ProgressBar::new(time_limit_s.max(0.0) as u64).with_style(
        ProgressStyle::with_template(
            "{msg:>10} [{bar:30}] {pos}/{len} s simulated, {elapsed} (eta {eta})",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar())
        .progress_chars("=> "),
    );
    bar.set_message("simulating");
    bar
}
