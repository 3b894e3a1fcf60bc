//! Runs the progressive probabilistic Hough transform on an image, as OpenCV's
//! `HoughLinesP(img, rho=1, theta=pi/180, threshold=30, minLineLength=20, maxLineGap=5)` by
//! default, and prints the segments and the time as JSON (used by `bench/hough_vs_opencv.sh`).
//!
//! `cargo run --release -p semantic --example hough -- IMAGE.png [--repeat N] [--threshold T]
//! [--min-length L] [--max-gap G] [--matas]`

use semantic::{hough_lines_p, HoughParams, Unvote};
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let path = args
        .first()
        .ok_or("usage: hough IMAGE.png [--repeat N] ...")?;
    let value = |name: &str| {
        args.iter()
            .position(|a| a == name)
            .and_then(|i| args.get(i + 1))
    };
    let repeat: usize = value("--repeat")
        .map(|v| v.parse())
        .transpose()?
        .unwrap_or(20);
    let mut p = HoughParams::default();
    if let Some(v) = value("--threshold") {
        p.threshold = v.parse()?;
    }
    if let Some(v) = value("--min-length") {
        p.min_line_length_px = v.parse()?;
    }
    if let Some(v) = value("--max-gap") {
        p.max_line_gap_px = v.parse()?;
    }
    if args.iter().any(|a| a == "--matas") {
        p.unvote = Unvote::Matas;
    }
    let img = image::open(path)?.to_luma8();
    let mut times = Vec::new();
    let mut segments = Vec::new();
    for _ in 0..repeat.max(1) {
        let t = Instant::now();
        segments = hough_lines_p(&img, &p);
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
    times.sort_by(f64::total_cmp);
    let out = serde_json::json!({
        "image": path,
        "width": img.width(),
        "height": img.height(),
        "segments": segments.iter().map(|s| [s.a[0], s.a[1], s.b[0], s.b[1]]).collect::<Vec<_>>(),
        "ms_median": times[times.len() / 2],
        "ms_min": times[0],
        "runs": times.len(),
    });
    println!("{out}");
    Ok(())
}
