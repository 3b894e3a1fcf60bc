//! Pictures: charts drawn with plotters into SVG or PNG (picked by extension), with an embedded
//! font (DejaVu Sans, `assets/LICENSE.DejaVu`) so PNGs need no system fonts.

use crate::error::{PipelineError, Result};
use plotters::prelude::*;
use registration::IcpResult;
use std::path::Path;
use std::sync::Once;

static FONT: Once = Once::new();

fn register_font() {
    FONT.call_once(|| {
        let bytes: &'static [u8] = include_bytes!("../assets/DejaVuSans.ttf");
        // The embedded font is known-good; a failure only means text falls back to nothing.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, bytes);
    });
}

/// One named line of (x, y) points.
pub struct Series {
    /// Legend label.
    pub name: String,
    /// Points.
    pub points: Vec<(f64, f64)>,
}

/// Draws line series with a logarithmic y axis into `path` (`.svg` or `.png`), written atomically.
pub fn line_chart(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> Result<()> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    if ext != "svg" && ext != "png" {
        return Err(PipelineError::bad_input(format!(
            "{}: a plot must be .svg or .png",
            path.display()
        )));
    }
    if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
        if !parent.is_dir() {
            return Err(cloud::CloudError::io(
                path,
                std::io::Error::new(std::io::ErrorKind::NotFound, "its folder does not exist"),
            )
            .into());
        }
    }
    register_font();
    let tmp = path.with_file_name(format!(
        ".{}.{}.tmp.{ext}",
        path.file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default(),
        std::process::id()
    ));
    let drawn = if ext == "svg" {
        draw(
            SVGBackend::new(&tmp, (900, 560)).into_drawing_area(),
            title,
            x_label,
            y_label,
            series,
        )
    } else {
        draw(
            BitMapBackend::new(&tmp, (900, 560)).into_drawing_area(),
            title,
            x_label,
            y_label,
            series,
        )
    };
    let result = drawn
        .map_err(|msg| PipelineError::Plot {
            path: path.to_path_buf(),
            msg,
        })
        .and_then(|()| {
            std::fs::rename(&tmp, path).map_err(|e| cloud::CloudError::io(path, e).into())
        });
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

fn draw<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> std::result::Result<(), String>
where
    DB::ErrorType: 'static,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| format!("drawing the chart: {e}");
    root.fill(&WHITE).map_err(err)?;
    let all = series.iter().flat_map(|s| s.points.iter());
    let (mut x1, mut y0, mut y1) = (1.0f64, f64::INFINITY, f64::NEG_INFINITY);
    for &(x, y) in all.filter(|(x, y)| x.is_finite() && y.is_finite()) {
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if !y0.is_finite() {
        (y0, y1) = (1e-3, 1.0);
    }
    let mut chart = ChartBuilder::on(&root);
    chart
        .caption(title, ("sans-serif", 24))
        .margin(16)
        .x_label_area_size(44)
        .y_label_area_size(72);
    let colors = [BLUE, RED, GREEN, MAGENTA, CYAN, BLACK];
    {
        let (lo, hi) = (y0.max(1e-6) * 0.8, (y1 * 1.25).max(y0.max(1e-6) * 2.0));
        let mut c = chart
            .build_cartesian_2d(0f64..x1, (lo..hi).log_scale())
            .map_err(err)?;
        c.configure_mesh()
            .x_desc(x_label)
            .y_desc(y_label)
            .label_style(("sans-serif", 15))
            .draw()
            .map_err(err)?;
        for (s, color) in series.iter().zip(colors.iter().cycle()) {
            let pts = s.points.iter().map(|&(x, y)| (x, y.max(lo)));
            c.draw_series(LineSeries::new(pts, color.stroke_width(2)))
                .map_err(err)?
                .label(s.name.clone())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
        }
        c.configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .label_font(("sans-serif", 15))
            .draw()
            .map_err(err)?;
    }
    root.present().map_err(err)?;
    Ok(())
}

/// Draws each run's RMSE per iteration (log scale) into `path` (`.svg` or `.png`).
pub fn plot_rmse(path: &Path, runs: &[(String, &IcpResult)]) -> Result<()> {
    let series: Vec<Series> = runs
        .iter()
        .map(|(name, r)| Series {
            name: name.clone(),
            points: r
                .iterations
                .iter()
                .map(|it| (it.iteration as f64, it.rmse_m))
                .collect(),
        })
        .collect();
    line_chart(path, "ICP convergence", "iteration", "RMSE (m)", &series)
}
