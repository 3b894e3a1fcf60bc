//! Test oracle for the Hough engine: a plain, unoptimised progressive probabilistic Hough
//! transform written straight from the description of OpenCV's `HoughLinesProbabilistic`
//! (Matas et al. 2000 as OpenCV implements it: 32-bit accumulator, `cvRound` of
//! `x * cos/rho + y * sin/rho` in single precision, 16.16 fixed-point corridor walks), and
//! the tests that pin the optimised engine in `ppht.rs` to it, segment for segment.
//!
//! Two guards: segment lists fingerprinted from the engine as it was before it was optimised
//! (so a change that moves both engines the same way still fails), and a differential test
//! on many generated images and parameter sets (rho, theta, threshold, gaps, seeds, both
//! unvoting rules), which names the first image where the two lists differ.

use super::cv_round;
use super::ppht::CvRng;
use super::{hough_lines_p, HoughParams, PixelSegment, Unvote};
use image::GrayImage;

/// The reference engine: same contract as `ppht::ppht`, no shortcuts.
pub(crate) fn ppht_reference(
    mut mask: Vec<u8>,
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
    let irho = 1.0f32 / p.rho_px as f32;
    let theta = p.theta_rad as f32 as f64;
    let pi = std::f64::consts::PI;
    let mut numangle = ((pi / theta).floor() as i64 + 1).max(1);
    if numangle > 1 && (pi - (numangle - 1) as f64 * theta).abs() < theta / 2.0 {
        numangle -= 1;
    }
    let numangle = numangle.clamp(1, 100_000) as usize;
    let numrho = cv_round(((width + height) * 2 + 1) as f32 / p.rho_px as f32).max(1) as usize;
    let trig: Vec<(f32, f32)> = (0..numangle)
        .map(|n| {
            let a = n as f64 * theta;
            (
                (a.cos() * irho as f64) as f32,
                (a.sin() * irho as f64) as f32,
            )
        })
        .collect();
    let mut accum = vec![0i32; numangle * numrho];
    let half = (numrho as i64 - 1) / 2;
    let cell = |n: usize, x: i64, y: i64| {
        let r = cv_round(x as f32 * trig[n].0 + y as f32 * trig[n].1) + half;
        n * numrho + r.clamp(0, numrho as i64 - 1) as usize
    };
    let line_length = p.min_line_length_px.round_ties_even().max(0.0) as i64;
    let line_gap = p.max_line_gap_px.round_ties_even().max(0.0) as i64;
    let threshold = p.threshold.min(i32::MAX as u32) as i32;
    let mut points: Vec<(i64, i64)> = Vec::new();
    for y in 0..height {
        for x in 0..width {
            if mask[y * width + x] != 0 {
                points.push((x as i64, y as i64));
            }
        }
    }
    let mut rng = CvRng(if p.seed == 0 { 0xffff_ffff } else { p.seed });
    let (w, h) = (width as i64, height as i64);
    let mut lines = Vec::new();
    let mut count = points.len();
    while count > 0 {
        let idx = rng.uniform(0, count as u32) as usize;
        let (j, i) = points[idx];
        points[idx] = points[count - 1];
        count -= 1;
        if mask[(i * w + j) as usize] == 0 {
            continue;
        }
        let (mut max_val, mut max_n) = (threshold - 1, 0);
        for n in 0..numangle {
            let c = cell(n, j, i);
            accum[c] += 1;
            if max_val < accum[c] {
                max_val = accum[c];
                max_n = n;
            }
        }
        if p.unvote == Unvote::Matas {
            mask[(i * w + j) as usize] = 2;
        }
        if max_val < threshold {
            continue;
        }
        // Walk along the line direction (-sin, cos), one pixel per step on the major axis.
        let (a, b) = (-trig[max_n].1, trig[max_n].0);
        let xflag = a.abs() > b.abs();
        let (x0, y0, dx0, dy0) = if xflag {
            let dy = cv_round(b * 65536.0 / a.abs());
            (j, (i << 16) + (1 << 15), if a > 0.0 { 1 } else { -1 }, dy)
        } else {
            let dx = cv_round(a * 65536.0 / b.abs());
            ((j << 16) + (1 << 15), i, dx, if b > 0.0 { 1 } else { -1 })
        };
        let pixel = |x: i64, y: i64| if xflag { (x, y >> 16) } else { (x >> 16, y) };
        let inside = |(x, y): (i64, i64)| x >= 0 && x < w && y >= 0 && y < h;
        let mut ends = [(j, i); 2];
        for (k, end) in ends.iter_mut().enumerate() {
            let s = if k == 0 { 1 } else { -1 };
            let (mut x, mut y, mut gap) = (x0, y0, 0);
            while inside(pixel(x, y)) {
                let (px, py) = pixel(x, y);
                if mask[(py * w + px) as usize] != 0 {
                    gap = 0;
                    *end = (px, py);
                } else {
                    gap += 1;
                    if gap > line_gap {
                        break;
                    }
                }
                x += s * dx0;
                y += s * dy0;
            }
        }
        let good = (ends[1].0 - ends[0].0).abs() >= line_length
            || (ends[1].1 - ends[0].1).abs() >= line_length;
        for (k, end) in ends.iter().enumerate() {
            let s = if k == 0 { 1 } else { -1 };
            let (mut x, mut y) = (x0, y0);
            while inside(pixel(x, y)) {
                let (px, py) = pixel(x, y);
                let m = &mut mask[(py * w + px) as usize];
                let unvote = match p.unvote {
                    Unvote::OpenCv => *m != 0 && good,
                    Unvote::Matas => *m == 2,
                };
                if unvote {
                    for n in 0..numangle {
                        accum[cell(n, px, py)] -= 1;
                    }
                }
                *m = 0;
                if (px, py) == *end {
                    break;
                }
                x += s * dx0;
                y += s * dy0;
            }
        }
        if good {
            lines.push(PixelSegment {
                a: [ends[0].0 as i32, ends[0].1 as i32],
                b: [ends[1].0 as i32, ends[1].1 as i32],
            });
            if lines.len() >= p.max_lines {
                break;
            }
        }
    }
    lines
}

/// A floor plan as the benchmark draws it (outer walls, a corridor with door gaps, cross
/// walls, diagonals, `thick`-pixel strokes) plus salt noise on `noise_permille` of the pixels,
/// from a small xorshift generator so the images never change.
pub(crate) fn plan_image(w: u32, h: u32, thick: i32, noise_permille: u32, seed: u64) -> GrayImage {
    let mut s = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    let mut rnd = move |n: u32| {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s % n.max(1) as u64) as i32
    };
    let mut img = GrayImage::new(w, h);
    let (wi, hi) = (w as i32, h as i32);
    let line = |img: &mut GrayImage, (x0, y0): (i32, i32), (x1, y1): (i32, i32)| {
        let n = (x1 - x0).abs().max((y1 - y0).abs()).max(1);
        for k in 0..=n {
            for t in 0..thick {
                let x = x0 + (x1 - x0) * k / n + if y0 == y1 { 0 } else { t };
                let y = y0 + (y1 - y0) * k / n + if y0 == y1 { t } else { 0 };
                if x >= 0 && y >= 0 && x < wi && y < hi {
                    img.put_pixel(x as u32, y as u32, image::Luma([255]));
                }
            }
        }
    };
    let m = (wi.min(hi) / 20).max(2);
    line(&mut img, (m, m), (wi - m, m));
    line(&mut img, (m, hi - m), (wi - m, hi - m));
    line(&mut img, (m, m), (m, hi - m));
    line(&mut img, (wi - m, m), (wi - m, hi - m));
    let (c0, c1) = (hi * 45 / 100, hi * 55 / 100);
    for y in [c0, c1] {
        let mut x = m;
        while x < wi - m {
            let seg = wi / 10 + rnd((wi / 6) as u32);
            line(&mut img, (x, y), ((x + seg).min(wi - m), y));
            x += seg + wi / 40 + rnd((wi / 40) as u32);
        }
    }
    let mut x = m;
    while x < wi - 2 * m {
        x += wi / 8 + rnd((wi / 8) as u32);
        if x < wi - m {
            line(&mut img, (x, m), (x, c0));
            line(&mut img, (x + rnd(7) - 3, c1), (x, hi - m));
        }
    }
    for _ in 0..3 {
        let p = (
            2 * m + rnd((wi - 4 * m) as u32),
            2 * m + rnd((c0 - 3 * m).max(1) as u32),
        );
        let q = (
            p.0 + rnd((wi / 4) as u32) - wi / 8,
            p.1 + rnd((hi / 5) as u32),
        );
        line(&mut img, p, q);
    }
    for px in img.pixels_mut() {
        if (rnd(1000) as u32) < noise_permille {
            px.0[0] = 255;
        }
    }
    img
}

/// FNV-1a over the segment list, in order.
fn fingerprint(segs: &[PixelSegment]) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    for s in segs {
        for v in [s.a[0], s.a[1], s.b[0], s.b[1]] {
            for byte in v.to_le_bytes() {
                h = (h ^ byte as u64).wrapping_mul(0x0100_0000_01b3);
            }
        }
    }
    h
}

fn params(threshold: u32, min_len: f64, gap: f64, unvote: Unvote) -> HoughParams {
    HoughParams {
        threshold,
        min_line_length_px: min_len,
        max_line_gap_px: gap,
        unvote,
        ..HoughParams::default()
    }
}

/// Image (width, height, stroke, noise per mille, seed), parameters, and the expected number
/// of segments and their fingerprint.
type Case = (u32, u32, i32, u32, u64, HoughParams, usize, u64);

#[test]
fn segments_match_the_pre_optimisation_engine() {
    // (w, h, stroke, noise per mille, seed, params) -> (segments, fingerprint), recorded
    // from the engine before the accumulator and walk were optimised.
    let cases: [Case; 6] = [
        (
            510,
            510,
            1,
            10,
            1,
            HoughParams::default(),
            36,
            0x4bcc_9f82_7807_cf0b,
        ),
        (
            640,
            480,
            2,
            10,
            2,
            HoughParams::default(),
            57,
            0x8b31_a1f7_f8ae_97c7,
        ),
        (
            300,
            700,
            3,
            20,
            3,
            params(12, 10.0, 5.0, Unvote::OpenCv),
            110,
            0xc4f7_6176_452c_8acc,
        ),
        (
            400,
            400,
            2,
            10,
            4,
            params(30, 20.0, 5.0, Unvote::Matas),
            54,
            0x1b79_1da5_dfe1_95e8,
        ),
        (
            350,
            260,
            1,
            5,
            5,
            HoughParams {
                rho_px: 2.0,
                theta_rad: 2f64.to_radians(),
                seed: 12345,
                ..params(20, 15.0, 3.0, Unvote::OpenCv)
            },
            30,
            0xe022_1f5e_7e05_e7b2,
        ),
        (
            1000,
            1000,
            3,
            10,
            6,
            HoughParams::default(),
            97,
            0xfa0f_99c2_8bc6_95af,
        ),
    ];
    let mut report = Vec::new();
    for (w, h, thick, noise, seed, p, n, fp) in cases {
        let segs = hough_lines_p(&plan_image(w, h, thick, noise, seed), &p);
        report.push(format!("{w}x{h}: {} {:#x}", segs.len(), fingerprint(&segs)));
        if (segs.len(), fingerprint(&segs)) != (n, fp) {
            report.push("  ^ differs".into());
        }
    }
    assert!(
        !report.iter().any(|l| l.contains("differs")),
        "{}",
        report.join("\n")
    );
}

#[test]
fn optimised_engine_equals_the_reference() {
    let sets = [
        HoughParams::default(),
        params(12, 10.0, 5.0, Unvote::OpenCv),
        params(25, 20.0, 2.0, Unvote::Matas),
        params(5, 3.0, 0.0, Unvote::OpenCv),
        HoughParams {
            rho_px: 0.5,
            theta_rad: 0.5f64.to_radians(),
            seed: 7,
            ..params(20, 20.0, 5.0, Unvote::OpenCv)
        },
        HoughParams {
            rho_px: 3.0,
            theta_rad: 3f64.to_radians(),
            seed: 0,
            max_lines: 4,
            ..params(10, 8.0, 4.0, Unvote::Matas)
        },
    ];
    for (k, p) in sets.iter().enumerate() {
        for seed in 0..4u64 {
            let (w, h) = (
                60 + (seed as u32 * 97 + k as u32 * 31) % 300,
                40 + (seed as u32 * 53) % 250,
            );
            let img = plan_image(
                w,
                h,
                1 + (seed % 3) as i32,
                5 + 10 * (seed % 3) as u32,
                seed,
            );
            let mask = img.as_raw().iter().map(|&v| u8::from(v > 0)).collect();
            let want = ppht_reference(mask, w as usize, h as usize, p);
            let got = hough_lines_p(&img, p);
            assert_eq!(got, want, "params #{k}, image {w}x{h} seed {seed}");
        }
    }
}
