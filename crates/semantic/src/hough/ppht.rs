//! The engine of the progressive probabilistic Hough transform (see the `hough` module): the
//! random order, the accumulator and the corridor walks, as OpenCV's `HoughLinesProbabilistic`.

use super::{HoughParams, PixelSegment, Unvote};

/// OpenCV's `cv::RNG`: multiply-with-carry.
pub(crate) struct CvRng(pub u64);

impl CvRng {
    pub fn next(&mut self) -> u32 {
        self.0 = (self.0 as u32 as u64)
            .wrapping_mul(4_164_903_690)
            .wrapping_add(self.0 >> 32);
        self.0 as u32
    }

    pub fn uniform(&mut self, a: u32, b: u32) -> u32 {
        if a == b {
            a
        } else {
            self.next() % (b - a) + a
        }
    }
}

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
