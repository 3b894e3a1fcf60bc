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

use crate::error::{check_range, Result};
use image::GrayImage;
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
        )
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

/// OpenCV's `cv::RNG`: multiply-with-carry.
struct CvRng(u64);

impl CvRng {
    fn next(&mut self) -> u32 {
        self.0 = (self.0 as u32 as u64)
            .wrapping_mul(4_164_903_690)
            .wrapping_add(self.0 >> 32);
        self.0 as u32
    }

    fn uniform(&mut self, a: u32, b: u32) -> u32 {
        if a == b {
            a
        } else {
            self.next() % (b - a) + a
        }
    }
}

/// OpenCV's `cvRound` for floats: round half to even.
#[inline(always)]
fn cv_round(v: f32) -> i64 {
    v.round_ties_even() as i64
}

/// `cvRound` for `|v| < 2^22`: adding 1.5 * 2^23 rounds in the default mode (to nearest, ties
/// to even) and leaves the integer in the low mantissa bits, read without a float-to-int
/// conversion (`round_ties_even` is a library call on baseline x86-64, `as` a checked one).
#[inline(always)]
fn cv_round_small(v: f32) -> i32 {
    const MAGIC: f32 = 12_582_912.0;
    (v + MAGIC).to_bits() as i32 - 0x4B40_0000
}

/// An accumulator cell: 16 bits while no line can hold 32767 pixels (half the memory, fewer
/// cache misses), else 32.
trait Count: Copy + Default {
    fn add(&mut self, delta: i32) -> i32;
}

impl Count for i16 {
    #[inline(always)]
    fn add(&mut self, delta: i32) -> i32 {
        *self = self.wrapping_add(delta as i16);
        *self as i32
    }
}

impl Count for i32 {
    #[inline(always)]
    fn add(&mut self, delta: i32) -> i32 {
        *self = self.wrapping_add(delta);
        *self
    }
}

/// Adds `delta` to the accumulator cells of every line through `(x, y)`; returns the largest
/// resulting count above `floor` and its angle index.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn vote<C: Count>(
    accum: &mut [C],
    trig: &[f32],
    numrho: usize,
    half: i32,
    small: bool,
    x: f32,
    y: f32,
    delta: i32,
    floor: i32,
) -> (i32, usize) {
    let (mut max_val, mut max_n) = (floor, 0);
    let last = numrho as i32 - 1;
    for (n, (row, t)) in accum
        .chunks_exact_mut(numrho)
        .zip(trig.chunks_exact(2))
        .enumerate()
    {
        let v = x * t[0] + y * t[1];
        let r = if small {
            cv_round_small(v)
        } else {
            cv_round(v).clamp(i32::MIN as i64, i32::MAX as i64) as i32
        };
        let count = row[(r + half).clamp(0, last) as usize].add(delta);
        if max_val < count {
            max_val = count;
            max_n = n;
        }
    }
    (max_val, max_n)
}

/// Finds line segments in a binary image (non-zero = set) with the progressive probabilistic
/// Hough transform. Deterministic: the same image and parameters give the same segments.
pub fn hough_lines_p(image: &GrayImage, p: &HoughParams) -> Vec<PixelSegment> {
    let mask: Vec<u8> = image.as_raw().iter().map(|&v| u8::from(v > 0)).collect();
    ppht(mask, image.width() as usize, image.height() as usize, p)
}

pub(crate) fn ppht(
    mask: Vec<u8>,
    width: usize,
    height: usize,
    p: &HoughParams,
) -> Vec<PixelSegment> {
    if width == 0
        || height == 0
        || p.rho_px.is_nan()
        || p.rho_px <= 0.0
        || p.theta_rad.is_nan()
        || p.theta_rad <= 0.0
    {
        return Vec::new();
    }
    if width + height < 30_000 {
        ppht_with::<i16>(mask, width, height, p)
    } else {
        ppht_with::<i32>(mask, width, height, p)
    }
}

fn ppht_with<C: Count>(
    mut mask: Vec<u8>,
    width: usize,
    height: usize,
    p: &HoughParams,
) -> Vec<PixelSegment> {
    let mut lines = Vec::new();
    let rho = p.rho_px as f32;
    let theta = p.theta_rad as f32;
    let irho = 1.0f32 / rho;
    let theta_d = theta as f64;
    let mut numangle = ((std::f64::consts::PI / theta_d).floor() as i64 + 1).max(1);
    if numangle > 1
        && (std::f64::consts::PI - (numangle - 1) as f64 * theta_d).abs() < theta_d / 2.0
    {
        numangle -= 1;
    }
    let numangle = numangle.clamp(1, 100_000) as usize;
    let numrho = cv_round(((width + height) * 2 + 1) as f32 / rho).max(1) as usize;
    let line_length = (p.min_line_length_px.round_ties_even()).max(0.0) as i64;
    let line_gap = (p.max_line_gap_px.round_ties_even()).max(0.0) as i64;
    let threshold = p.threshold.min(i32::MAX as u32) as i32;
    let mut trig = vec![0f32; numangle * 2];
    for n in 0..numangle {
        let a = n as f64 * theta_d;
        trig[2 * n] = (a.cos() * irho as f64) as f32;
        trig[2 * n + 1] = (a.sin() * irho as f64) as f32;
    }
    let half = ((numrho - 1) / 2).min(i32::MAX as usize) as i32;
    // |x cos + y sin| / rho never exceeds (width + height) / rho: the fast rounding holds below 2^22.
    let small = ((width + height) as f32 * irho.abs()) < 4_000_000.0;
    let mut accum = vec![C::default(); numangle * numrho];
    let mut nzloc: Vec<(u32, u32)> = Vec::new();
    for y in 0..height {
        for x in 0..width {
            if mask[y * width + x] != 0 {
                nzloc.push((x as u32, y as u32));
            }
        }
    }
    let mut rng = CvRng(if p.seed == 0 { 0xffff_ffff } else { p.seed });
    const SHIFT: i64 = 16;
    let (w, h) = (width as i64, height as i64);
    let mut count = nzloc.len();
    while count > 0 {
        let idx = rng.uniform(0, count as u32) as usize;
        let (j, i) = (nzloc[idx].0 as i64, nzloc[idx].1 as i64);
        nzloc[idx] = nzloc[count - 1];
        count -= 1;
        if mask[(i * w + j) as usize] == 0 {
            continue;
        }
        let (max_val, max_n) = vote(
            &mut accum,
            &trig,
            numrho,
            half,
            small,
            j as f32,
            i as f32,
            1,
            threshold - 1,
        );
        if p.unvote == Unvote::Matas {
            mask[(i * w + j) as usize] = 2;
        }
        if max_val < threshold {
            continue;
        }
        let a = -trig[2 * max_n + 1];
        let b = trig[2 * max_n];
        let (mut x0, mut y0) = (j, i);
        let (dx0, dy0, xflag);
        if a.abs() > b.abs() {
            xflag = true;
            dx0 = if a > 0.0 { 1 } else { -1 };
            dy0 = cv_round(b * (1 << SHIFT) as f32 / a.abs());
            y0 = (y0 << SHIFT) + (1 << (SHIFT - 1));
        } else {
            xflag = false;
            dy0 = if b > 0.0 { 1 } else { -1 };
            dx0 = cv_round(a * (1 << SHIFT) as f32 / b.abs());
            x0 = (x0 << SHIFT) + (1 << (SHIFT - 1));
        }
        let pixel = |x: i64, y: i64| -> (i64, i64) {
            if xflag {
                (x, y >> SHIFT)
            } else {
                (x >> SHIFT, y)
            }
        };
        let mut line_end = [(j, i); 2];
        for (k, end) in line_end.iter_mut().enumerate() {
            let (mut x, mut y) = (x0, y0);
            let (dx, dy) = if k == 0 { (dx0, dy0) } else { (-dx0, -dy0) };
            let mut gap = 0;
            loop {
                let (j1, i1) = pixel(x, y);
                if j1 < 0 || j1 >= w || i1 < 0 || i1 >= h {
                    break;
                }
                if mask[(i1 * w + j1) as usize] != 0 {
                    gap = 0;
                    *end = (j1, i1);
                } else {
                    gap += 1;
                    if gap > line_gap {
                        break;
                    }
                }
                x += dx;
                y += dy;
            }
        }
        let good_line = (line_end[1].0 - line_end[0].0).abs() >= line_length
            || (line_end[1].1 - line_end[0].1).abs() >= line_length;
        for (k, end) in line_end.iter().enumerate() {
            let (mut x, mut y) = (x0, y0);
            let (dx, dy) = if k == 0 { (dx0, dy0) } else { (-dx0, -dy0) };
            loop {
                let (j1, i1) = pixel(x, y);
                if j1 < 0 || j1 >= w || i1 < 0 || i1 >= h {
                    break;
                }
                let m = &mut mask[(i1 * w + j1) as usize];
                let unvote = match p.unvote {
                    Unvote::OpenCv => *m != 0 && good_line,
                    Unvote::Matas => *m == 2,
                };
                if unvote {
                    vote(
                        &mut accum,
                        &trig,
                        numrho,
                        half,
                        small,
                        j1 as f32,
                        i1 as f32,
                        -1,
                        i32::MAX,
                    );
                }
                *m = 0;
                if (j1, i1) == *end {
                    break;
                }
                x += dx;
                y += dy;
            }
        }
        if good_line {
            lines.push(PixelSegment {
                a: [line_end[0].0 as i32, line_end[0].1 as i32],
                b: [line_end[1].0 as i32, line_end[1].1 as i32],
            });
            if lines.len() >= p.max_lines {
                break;
            }
        }
    }
    lines
}

#[cfg(test)]
mod tests {
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
