//! The progress bar every command shows for work counted in scans.

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
