//! The XY projection image (the paper's input image, Fig. 3): the points of a height band
//! projected onto the floor plane, one pixel per `resolution_m` square.
//!
//! The band defaults to a strip just under the ceiling: there, only walls and the lintels above
//! doors stand (furniture, door leaves and stairs are lower), and the lintels keep a wall's
//! line unbroken across its doors. A pixel's value is either its occupancy (the fraction of
//! the band's `slice_m` slices holding a point) or its point density (count over the 99th
//! percentile count); the binary image keeps pixels whose value reaches `threshold`.
//!
//! The image covers the robust XY extent of the cloud (quantiles `extent_quantile` and
//! `1 - extent_quantile`, so a few stray far points do not blow it up), plus a margin; an image
//! larger than `max_pixels` is an error rather than an allocation of gigabytes.

use crate::error::{Result, SemanticError};
use crate::image_frame::{ImageFrame, Mask};
use crate::points::quantile;
use cloud::check_range;
use glam::Vec3;
use image::GrayImage;
use serde::{Deserialize, Serialize};

/// Which points are projected.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum HeightBand {
    /// From `from_m` below the ceiling up to `to_m` below it (falls back to the top of the
    /// points where no ceiling is found).
    BelowCeiling {
        /// Depth of the band's bottom under the ceiling.
        from_m: f64,
        /// Depth of the band's top under the ceiling.
        to_m: f64,
    },
    /// From `from_m` to `to_m` above the floor.
    AboveFloor {
        /// Height of the band's bottom.
        from_m: f64,
        /// Height of the band's top.
        to_m: f64,
    },
    /// Absolute z in the map frame.
    Absolute {
        /// Bottom of the band.
        min_z_m: f64,
        /// Top of the band.
        max_z_m: f64,
    },
}

/// What a pixel's value measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ProjectionValue {
    /// Fraction of the band's slices that hold a point.
    Occupancy,
    /// Point count, normalised by the 99th percentile of the non-empty pixels' counts.
    Density,
}

/// Configuration of the projection image.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ProjectionConfig {
    /// Pixel edge.
    pub resolution_m: f64,
    /// The projected height band.
    pub band: HeightBand,
    /// What a pixel's value measures.
    pub value: ProjectionValue,
    /// Slice height for [`ProjectionValue::Occupancy`].
    pub slice_m: f64,
    /// Pixels whose value reaches this (0..1) are set in the binary image.
    pub threshold: f64,
    /// Lower quantile of the point coordinates that bounds the image (and 1 minus it the upper).
    pub extent_quantile: f64,
    /// Empty border around the points, in pixels.
    pub margin_px: u32,
    /// Largest image (width x height) this stage allocates.
    pub max_pixels: u64,
}

impl Default for ProjectionConfig {
    fn default() -> Self {
        ProjectionConfig {
            resolution_m: 0.05,
            band: HeightBand::BelowCeiling {
                from_m: 0.6,
                to_m: 0.15,
            },
            value: ProjectionValue::Occupancy,
            slice_m: 0.05,
            threshold: 0.05,
            extent_quantile: 0.0005,
            margin_px: 8,
            max_pixels: 25_000_000,
        }
    }
}

impl ProjectionConfig {
    pub(crate) fn validate(&self) -> Result<()> {
        check_range(
            "projection.resolution_m",
            self.resolution_m,
            1e-3,
            10.0,
            "within 0.001..10 m",
        )?;
        check_range(
            "projection.slice_m",
            self.slice_m,
            1e-3,
            10.0,
            "within 0.001..10 m",
        )?;
        check_range(
            "projection.threshold",
            self.threshold,
            0.0,
            1.0,
            "within 0..1",
        )?;
        check_range(
            "projection.extent_quantile",
            self.extent_quantile,
            0.0,
            0.2,
            "within 0..0.2",
        )?;
        check_range(
            "projection.max_pixels",
            self.max_pixels as f64,
            1.0,
            1e9,
            "within 1..1e9",
        )?;
        let (a, b) = match self.band {
            HeightBand::BelowCeiling { from_m, to_m } => (-from_m, -to_m),
            HeightBand::AboveFloor { from_m, to_m } => (from_m, to_m),
            HeightBand::Absolute { min_z_m, max_z_m } => (min_z_m, max_z_m),
        };
        check_range("projection.band (lower end)", a, -1e4, 1e4, "finite")?;
        check_range(
            "projection.band (upper end)",
            b - a,
            1e-3,
            1e4,
            "above the lower end",
        )?;
        Ok(())
    }

    /// The band's z range in the map frame, given the floor and ceiling heights.
    pub(crate) fn band_z(&self, floor_m: f64, ceiling_m: f64) -> (f64, f64) {
        match self.band {
            HeightBand::BelowCeiling { from_m, to_m } => (ceiling_m - from_m, ceiling_m - to_m),
            HeightBand::AboveFloor { from_m, to_m } => (floor_m + from_m, floor_m + to_m),
            HeightBand::Absolute { min_z_m, max_z_m } => (min_z_m, max_z_m),
        }
    }
}

/// The image frame covering the robust extent of `points`.
pub(crate) fn frame_for(points: &[Vec3], c: &ProjectionConfig) -> Result<ImageFrame> {
    let mut xs: Vec<f64> = points.iter().map(|p| p.x as f64).collect();
    let mut ys: Vec<f64> = points.iter().map(|p| p.y as f64).collect();
    let q = c.extent_quantile;
    let (Some(x0), Some(x1), Some(y0), Some(y1)) = (
        quantile(&mut xs, q),
        quantile(&mut xs, 1.0 - q),
        quantile(&mut ys, q),
        quantile(&mut ys, 1.0 - q),
    ) else {
        return Err(SemanticError::EmptyCloud { total: 0 });
    };
    let res = c.resolution_m;
    let margin = c.margin_px as f64 * res;
    let (w_m, h_m) = (x1 - x0 + 2.0 * margin, y1 - y0 + 2.0 * margin);
    let w = (w_m / res).ceil().max(1.0);
    let h = (h_m / res).ceil().max(1.0);
    if w * h > c.max_pixels as f64 || w > u32::MAX as f64 || h > u32::MAX as f64 {
        return Err(SemanticError::ImageTooLarge {
            width_px: w as u64,
            height_px: h as u64,
            width_m: x1 - x0,
            height_m: y1 - y0,
            resolution_m: res,
            max_pixels: c.max_pixels,
        });
    }
    Ok(ImageFrame {
        origin_m: [x0 - margin, y1 + margin],
        resolution_m: res,
        width_px: w as u32,
        height_px: h as u32,
    })
}

/// The projection: per-pixel values (0..1) and the binary image of the band.
pub(crate) struct Projection {
    pub values: Vec<f32>,
    pub binary: Mask,
}

impl Projection {
    /// The values as an 8-bit image.
    pub fn to_gray(&self, frame: &ImageFrame) -> GrayImage {
        GrayImage::from_raw(
            frame.width_px,
            frame.height_px,
            self.values
                .iter()
                .map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)
                .collect(),
        )
        .unwrap_or_default()
    }
}

/// Projects the points with z in `[z0, z1]` into `frame` (paper, 1.3.1: "projection of 3D cloud
/// of points onto XY plane", values from 0 to 1).
pub(crate) fn project(
    points: &[Vec3],
    frame: &ImageFrame,
    (z0, z1): (f64, f64),
    c: &ProjectionConfig,
) -> Projection {
    let n = frame.len();
    let slices = (((z1 - z0) / c.slice_m).ceil() as usize).clamp(1, 64);
    let mut counts = vec![0u32; n];
    let mut occupied = vec![
        0u64;
        if c.value == ProjectionValue::Occupancy {
            n
        } else {
            0
        }
    ];
    for p in points {
        let z = p.z as f64;
        if !(z >= z0 && z <= z1) {
            continue;
        }
        let Some((col, row)) = frame.pixel_of(p.x as f64, p.y as f64) else {
            continue;
        };
        let i = row as usize * frame.width_px as usize + col as usize;
        counts[i] = counts[i].saturating_add(1);
        if let Some(o) = occupied.get_mut(i) {
            let s = (((z - z0) / c.slice_m).floor() as usize).min(slices - 1);
            *o |= 1 << s;
        }
    }
    let values: Vec<f32> = match c.value {
        ProjectionValue::Occupancy => occupied
            .iter()
            .map(|o| o.count_ones() as f32 / slices as f32)
            .collect(),
        ProjectionValue::Density => {
            let mut nz: Vec<f64> = counts
                .iter()
                .filter(|&&v| v > 0)
                .map(|&v| v as f64)
                .collect();
            let top = quantile(&mut nz, 0.99).unwrap_or(1.0).max(1.0) as f32;
            counts.iter().map(|&v| (v as f32 / top).min(1.0)).collect()
        }
    };
    let thr = c.threshold as f32;
    let binary = Mask {
        width: frame.width_px as usize,
        height: frame.height_px as usize,
        data: values.iter().map(|&v| v > 0.0 && v >= thr).collect(),
    };
    Projection { values, binary }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image_frame::pixel_center;

    #[test]
    fn projects_a_band_and_caps_the_size() {
        let c = ProjectionConfig::default();
        let mut pts = Vec::new();
        for i in 0..100 {
            for k in 0..10 {
                pts.push(Vec3::new(i as f32 * 0.02, 1.0, k as f32 * 0.03));
            }
        }
        let frame = frame_for(&pts, &c).expect("fits");
        let p = project(&pts, &frame, (0.0, 0.3), &c);
        assert!(
            p.binary.count() >= 39 && p.binary.count() <= 41,
            "{}",
            p.binary.count()
        );
        let (col, row) = frame.pixel_of(1.0, 1.0).expect("inside");
        let centre = pixel_center(&frame, col as f64, row as f64);
        assert!(
            (centre.x - 1.0).abs() <= 0.025 + 1e-9 && (centre.y - 1.0).abs() <= 0.025 + 1e-9,
            "{centre}"
        );
        let wide = vec![Vec3::ZERO, Vec3::new(10_000.0, 10_000.0, 0.0)];
        let c = ProjectionConfig {
            extent_quantile: 0.0,
            ..c
        };
        assert!(matches!(
            frame_for(&wide, &c),
            Err(SemanticError::ImageTooLarge { .. })
        ));
    }
}
