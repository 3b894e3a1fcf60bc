//! The progressive probabilistic Hough transform (Matas, Galambos & Kittler, "Robust detection
//! of lines using the progressive probabilistic Hough transform", CVIU 78(1), 2000), as
//! OpenCV's `HoughLinesP` (the paper's `CV_HOUGH_PROBABILISTIC`): line segments, each given by
//! its two end pixels.
//!
//! Set pixels are drawn in random order. Each votes in the (theta, rho) accumulator; when the
//! best cell of the lines through it reaches `threshold`, the corridor along that line is
//! walked from the pixel both ways (in 16.16 fixed point, along the major axis) until more than
//! `max_line_gap` consecutive unset pixels; the corridor's pixels leave the image, and the
//! segment is kept if its x or y extent reaches `min_line_length`.
//!
//! The random order comes from OpenCV's multiply-with-carry generator
//! (`state = lo32(state) * 4164903690 + hi32(state)`, seeded with `seed`, OpenCV's is
//! `u64::MAX`), and the accumulator arithmetic copies OpenCV's (single-precision trigonometric
//! table, round-half-even), so with [`Unvote::OpenCv`] the output follows OpenCV's on the same
//! image. [`Unvote::Matas`] follows the paper instead: only pixels that have voted are removed
//! from the accumulator, also for segments too short to keep (OpenCV removes every set pixel of
//! a long segment's corridor, voted or not, and none of a short one's).

use crate::error::Result;
use cloud::check_range;
mod accumulator;
mod ppht;
/// OpenCV's `cvRound` for floats: round half to even.
#[inline(always)]
pub(crate) fn cv_round(v: f32) -> i64 {
    v.round_ties_even() as i64
}

/// `cvRound` for `|v| < 2^22`: adding 1.5 * 2^23 rounds in the default mode (to nearest, ties
/// to even) and leaves the integer in the low mantissa bits, read without a float-to-int
/// conversion (`round_ties_even` is a library call on baseline x86-64, `as` a checked one).
#[inline(always)]
pub(crate) fn cv_round_small(v: f32) -> i32 {
    const MAGIC: f32 = 12_582_912.0;
    (v + MAGIC).to_bits() as i32 - 0x4B40_0000
}

#[cfg(test)]
mod reference;

use image::GrayImage;
pub(crate) use ppht::ppht;
use serde::{Deserialize, Serialize};

/// How the pixels of a walked corridor leave the accumulator.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Unvote {
    /// As OpenCV: after a kept segment, every set pixel of its corridor is subtracted.
    OpenCv,
    /// As Matas et al.: every corridor pixel that has voted is subtracted, kept segment or not.
    Matas,
}

/// Parameters of [`hough_lines_p`], in pixels, as OpenCV's `HoughLinesP`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct HoughParams {
    /// Distance resolution of the accumulator.
    pub rho_px: f64,
    /// Angle resolution of the accumulator, in radians.
    pub theta_rad: f64,
    /// Votes a line needs.
    pub threshold: u32,
    /// Least x or y extent of a kept segment (rounded as OpenCV does).
    pub min_line_length_px: f64,
    /// Largest run of unset pixels bridged along a segment (rounded).
    pub max_line_gap_px: f64,
    /// Seed of the random order (OpenCV: `u64::MAX`).
    pub seed: u64,
    /// Stop after this many segments.
    pub max_lines: usize,
    /// The unvoting rule.
    pub unvote: Unvote,
}

impl Default for HoughParams {
    /// OpenCV's usual call: `HoughLinesP(img, 1, pi/180, 30, minLineLength=20, maxLineGap=5)`.
    fn default() -> Self {
        HoughParams {
            rho_px: 1.0,
            theta_rad: std::f64::consts::PI / 180.0,
            threshold: 30,
            min_line_length_px: 20.0,
            max_line_gap_px: 5.0,
            seed: u64::MAX,
            max_lines: usize::MAX,
            unvote: Unvote::OpenCv,
        }
    }
}

/// A segment between two pixel positions (column x, row y), as OpenCV's `Vec4i`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct PixelSegment {
    /// First end (x, y).
    pub a: [i32; 2],
    /// Second end (x, y).
    pub b: [i32; 2],
}

impl PixelSegment {
    /// Euclidean length in pixels.
    pub fn length_px(&self) -> f64 {
        ((self.b[0] - self.a[0]) as f64).hypot((self.b[1] - self.a[1]) as f64)
    }
}

/// Configuration of the Hough stage inside the semantic map pipeline (lengths in metres,
/// converted with the projection's resolution).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct HoughConfig {
    /// Distance resolution of the accumulator.
    pub rho_px: f64,
    /// Angle resolution of the accumulator.
    pub theta_deg: f64,
    /// Votes a line needs.
    pub threshold_votes: u32,
    /// Least extent of a segment.
    pub min_line_length_m: f64,
    /// Largest gap bridged along a segment.
    pub max_line_gap_m: f64,
    /// Seed of the random order.
    pub seed: u64,
    /// The unvoting rule.
    pub unvote: Unvote,
}

impl Default for HoughConfig {
    fn default() -> Self {
        HoughConfig {
            rho_px: 1.0,
            theta_deg: 1.0,
            threshold_votes: 12,
            min_line_length_m: 0.5,
            max_line_gap_m: 0.25,
            seed: u64::MAX,
            unvote: Unvote::OpenCv,
        }
    }
}

impl HoughConfig {
    pub(crate) fn validate(&self) -> Result<()> {
        check_range(
            "hough.rho_px",
            self.rho_px,
            0.1,
            100.0,
            "within 0.1..100 px",
        )?;
        check_range(
            "hough.theta_deg",
            self.theta_deg,
            0.05,
            45.0,
            "within 0.05..45 deg",
        )?;
        check_range(
            "hough.threshold_votes",
            self.threshold_votes as f64,
            1.0,
            1e6,
            "at least 1",
        )?;
        check_range(
            "hough.min_line_length_m",
            self.min_line_length_m,
            0.0,
            1e4,
            "within 0..10 km",
        )?;
        check_range(
            "hough.max_line_gap_m",
            self.max_line_gap_m,
            0.0,
            1e4,
            "within 0..10 km",
        )?;
        Ok(())
    }

    /// The pixel parameters at `resolution_m`.
    pub fn params(&self, resolution_m: f64) -> HoughParams {
        HoughParams {
            rho_px: self.rho_px,
            theta_rad: self.theta_deg.to_radians(),
            threshold: self.threshold_votes,
            min_line_length_px: self.min_line_length_m / resolution_m,
            max_line_gap_px: self.max_line_gap_m / resolution_m,
            seed: self.seed,
            max_lines: 1_000_000,
            unvote: self.unvote,
        }
    }
}

/// Finds line segments in a binary image (non-zero = set) with the progressive probabilistic
/// Hough transform. Deterministic: the same image and parameters give the same segments.
pub fn hough_lines_p(image: &GrayImage, p: &HoughParams) -> Vec<PixelSegment> {
    let mask: Vec<u8> = image.as_raw().iter().map(|&v| u8::from(v > 0)).collect();
    ppht(mask, image.width() as usize, image.height() as usize, p)
}

#[cfg(test)]
mod tests {
    use super::ppht::CvRng;
    use super::*;

    type Line = ((i32, i32), (i32, i32));

    fn image_with(lines: &[Line], w: u32, h: u32) -> GrayImage {
        let mut img = GrayImage::new(w, h);
        for &((x0, y0), (x1, y1)) in lines {
            let n = (x1 - x0).abs().max((y1 - y0).abs());
            for k in 0..=n {
                let x = x0 + (x1 - x0) * k / n.max(1);
                let y = y0 + (y1 - y0) * k / n.max(1);
                img.put_pixel(x as u32, y as u32, image::Luma([255]));
            }
        }
        img
    }

    #[test]
    fn finds_the_drawn_segments_and_is_deterministic() {
        let img = image_with(
            &[
                ((10, 20), (150, 20)),
                ((40, 40), (40, 180)),
                ((60, 60), (160, 160)),
            ],
            200,
            200,
        );
        let p = HoughParams::default();
        let segs = hough_lines_p(&img, &p);
        assert_eq!(segs, hough_lines_p(&img, &p));
        assert_eq!(segs.len(), 3, "{segs:?}");
        let long: f64 = segs.iter().map(PixelSegment::length_px).sum();
        assert!(long > 140.0 + 140.0 + 140.0 - 6.0, "{segs:?}");
        let matas = hough_lines_p(
            &img,
            &HoughParams {
                unvote: Unvote::Matas,
                ..p
            },
        );
        assert_eq!(matas.len(), 3);
    }

    #[test]
    fn bridges_small_gaps_only() {
        let img = image_with(
            &[
                ((10, 50), (60, 50)),
                ((64, 50), (120, 50)),
                ((135, 50), (190, 50)),
            ],
            200,
            100,
        );
        let segs = hough_lines_p(&img, &HoughParams::default());
        assert_eq!(segs.len(), 2, "{segs:?}");
        assert!(segs
            .iter()
            .any(|s| s.a[0].min(s.b[0]) == 10 && s.a[0].max(s.b[0]) == 120));
    }

    #[test]
    fn fast_rounding_matches_round_half_even() {
        for v in [
            0.0f32,
            0.5,
            1.5,
            2.5,
            -0.5,
            -1.5,
            -2.5,
            3.49,
            -3.51,
            1234.5,
            -1234.5,
            4_000_000.4,
            -4_000_000.6,
        ] {
            assert_eq!(cv_round_small(v) as i64, cv_round(v), "{v}");
        }
    }

    #[test]
    fn opencv_rng_sequence() {
        // cv::RNG rng((uint64)-1); rng.next() -> 4164903689, 4164903689 * 4164903690 + ...
        let mut r = CvRng(u64::MAX);
        let first = r.next();
        assert_eq!(first, (0xffff_ffffu64 * 4_164_903_690 + 0xffff_ffff) as u32);
        assert_eq!(CvRng(u64::MAX).uniform(5, 5), 5);
    }
}
