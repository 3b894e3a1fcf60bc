//! The engine of the progressive probabilistic Hough transform (see the `hough` module): the
//! random order and the corridor walks (the accumulator is `accumulator.rs`), as OpenCV's
//! `HoughLinesProbabilistic`.

use super::accumulator::{Accumulator, Count};
use super::cv_round;
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
    // Small images (every case with 16-bit counts): pixel positions packed 16 + 16 bits, half
    // the memory of the randomly indexed list of set pixels.
    if width + height < 30_000 {
        ppht_with::<i16, u32>(mask, width, height, p)
    } else {
        ppht_with::<i32, u64>(mask, width, height, p)
    }
}

/// A set pixel's position (x, y) packed in one integer, low half x.
trait Packed: Copy {
    fn pack(x: usize, y: usize) -> Self;
    fn unpack(self) -> (i64, i64);
}

impl Packed for u32 {
    #[inline(always)]
    fn pack(x: usize, y: usize) -> Self {
        (y as u32) << 16 | x as u32
    }
    #[inline(always)]
    fn unpack(self) -> (i64, i64) {
        ((self & 0xffff) as i64, (self >> 16) as i64)
    }
}

impl Packed for u64 {
    #[inline(always)]
    fn pack(x: usize, y: usize) -> Self {
        (y as u64) << 32 | x as u64
    }
    #[inline(always)]
    fn unpack(self) -> (i64, i64) {
        ((self & 0xffff_ffff) as i64, (self >> 32) as i64)
    }
}

fn ppht_with<C: Count, L: Packed>(
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
    let mut acc = Accumulator::<C>::new(numangle, numrho, theta_d, irho, width + height);
    let mut nzloc: Vec<L> = Vec::new();
    for y in 0..height {
        for x in 0..width {
            if mask[y * width + x] != 0 {
                nzloc.push(L::pack(x, y));
            }
        }
    }
    let mut rng = CvRng(if p.seed == 0 { 0xffff_ffff } else { p.seed });
    const SHIFT: i64 = 16;
    let (w, h) = (width as i64, height as i64);
    let mut count = nzloc.len();
    while count > 0 {
        let idx = rng.uniform(0, count as u32) as usize;
        let (j, i) = nzloc[idx].unpack();
        nzloc[idx] = nzloc[count - 1];
        count -= 1;
        if mask[(i * w + j) as usize] == 0 {
            continue;
        }
        let (max_val, max_n) = acc.vote(j as f32, i as f32, threshold - 1);
        if p.unvote == Unvote::Matas {
            mask[(i * w + j) as usize] = 2;
        }
        if max_val < threshold {
            continue;
        }
        let (cos, sin) = acc.direction(max_n);
        let (a, b) = (-sin, cos);
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
                    acc.unvote(j1 as f32, i1 as f32);
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
