//! The (theta, rho) accumulator of the progressive probabilistic Hough transform (see the
//! `hough` module): one row of `numrho` counts per angle, laid out flat, and the vote and
//! unvote of one pixel.
//!
//! A pixel (x, y) votes for the cell `round(x cos(n theta) / rho + y sin(n theta) / rho) +
//! (numrho - 1) / 2` of every angle row n, with the table of `cos / rho` and `sin / rho` in
//! single precision and rounding half to even, as OpenCV's `HoughLinesProbabilistic` does:
//! bit for bit the same cells. The vote is split in two passes: first the cell index of every
//! angle from the table (independent lanes, which the compiler vectorises), then the
//! increments and the running maximum. The increments hit a different row per angle, so the
//! pass is bound by memory latency; with the arithmetic moved out, more of those loads are in
//! flight at once.

use super::{cv_round, cv_round_small};

/// An accumulator cell: 16 bits while no line can hold 32767 pixels (half the memory, fewer
/// cache misses), else 32.
pub(crate) trait Count: Copy + Default {
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

/// The counts, the trigonometric table and a scratch row of cell indices.
pub(crate) struct Accumulator<C> {
    cells: Vec<C>,
    /// `cos(n theta) / rho` per angle n.
    cos: Vec<f32>,
    /// `sin(n theta) / rho` per angle n.
    sin: Vec<f32>,
    /// `n * numrho`: the start of angle n's row in `cells`.
    row: Vec<u32>,
    /// The cell of each angle for the pixel being voted (filled by `cells_of`).
    index: Vec<u32>,
    numrho: usize,
    half: i32,
    /// `|x cos + y sin| / rho` stays below 2^22 (fast rounding) and every index fits in u32.
    fast: bool,
}

impl<C: Count> Accumulator<C> {
    /// An empty accumulator of `numangle` angles `theta` apart (radians, from 0) and `numrho`
    /// distances `1 / irho` apart, for an image of `width + height = extent` pixels.
    pub fn new(numangle: usize, numrho: usize, theta: f64, irho: f32, extent: usize) -> Self {
        let (cos, sin) = (0..numangle)
            .map(|n| {
                let a = n as f64 * theta;
                (
                    (a.cos() * irho as f64) as f32,
                    (a.sin() * irho as f64) as f32,
                )
            })
            .unzip();
        let total = numangle.saturating_mul(numrho);
        let fast = (extent as f32 * irho.abs()) < 4_000_000.0 && total <= u32::MAX as usize;
        Accumulator {
            cells: vec![C::default(); total],
            cos,
            sin,
            row: (0..numangle).map(|n| (n * numrho) as u32).collect(),
            index: vec![0; numangle],
            numrho,
            half: ((numrho - 1) / 2).min(i32::MAX as usize) as i32,
            fast,
        }
    }

    /// `(cos(n theta), sin(n theta)) / rho` of angle `n`.
    pub fn direction(&self, n: usize) -> (f32, f32) {
        (self.cos[n], self.sin[n])
    }

    /// The rho cell (clamped into the row) of the line through `(x, y)` at angle `n`.
    #[inline(always)]
    fn rho_cell(&self, v: f32) -> i32 {
        let r = if self.fast {
            cv_round_small(v)
        } else {
            cv_round(v).clamp(i32::MIN as i64, i32::MAX as i64) as i32
        };
        r.saturating_add(self.half).clamp(0, self.numrho as i32 - 1)
    }

    /// Fills `index` with the cell of every angle for the pixel `(x, y)` (fast path only).
    #[inline(always)]
    fn cells_of(&mut self, x: f32, y: f32) {
        let last = self.numrho as i32 - 1;
        let half = self.half;
        for (((out, &c), &s), &row) in self
            .index
            .iter_mut()
            .zip(&self.cos)
            .zip(&self.sin)
            .zip(&self.row)
        {
            // Same operations, same order as the scalar `rho_cell`: identical rounding.
            let r = cv_round_small(x * c + y * s);
            *out = row + (r + half).clamp(0, last) as u32;
        }
    }

    /// Adds one vote of `(x, y)` to every angle; returns the largest resulting count above
    /// `floor` and the first angle holding it (`(floor, 0)` if none exceeds it).
    pub fn vote(&mut self, x: f32, y: f32, floor: i32) -> (i32, usize) {
        let (mut max_val, mut max_n) = (floor, 0);
        if self.fast {
            self.cells_of(x, y);
            for (n, &i) in self.index.iter().enumerate() {
                let count = self.cells[i as usize].add(1);
                if max_val < count {
                    max_val = count;
                    max_n = n;
                }
            }
        } else {
            for n in 0..self.cos.len() {
                let r = self.rho_cell(x * self.cos[n] + y * self.sin[n]);
                let count = self.cells[n * self.numrho + r as usize].add(1);
                if max_val < count {
                    max_val = count;
                    max_n = n;
                }
            }
        }
        (max_val, max_n)
    }

    /// Removes one vote of `(x, y)` from every angle.
    pub fn unvote(&mut self, x: f32, y: f32) {
        if self.fast {
            self.cells_of(x, y);
            for &i in &self.index {
                self.cells[i as usize].add(-1);
            }
        } else {
            for n in 0..self.cos.len() {
                let r = self.rho_cell(x * self.cos[n] + y * self.sin[n]);
                self.cells[n * self.numrho + r as usize].add(-1);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vectorised_and_scalar_votes_agree() {
        let theta = std::f64::consts::PI / 180.0;
        let (w, h) = (300usize, 200usize);
        let numrho = cv_round(((w + h) * 2 + 1) as f32).max(1) as usize;
        let mut fast = Accumulator::<i16>::new(180, numrho, theta, 1.0, w + h);
        let mut slow = Accumulator::<i32>::new(180, numrho, theta, 1.0, w + h);
        assert!(fast.fast);
        slow.fast = false;
        let mut s = 12345u64;
        for k in 0..3000 {
            s = s.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
            let (x, y) = (((s >> 33) % w as u64) as f32, ((s >> 13) % h as u64) as f32);
            if k % 3 == 2 {
                fast.unvote(x, y);
                slow.unvote(x, y);
            } else {
                assert_eq!(fast.vote(x, y, 0), slow.vote(x, y, 0));
            }
        }
        let widened: Vec<i32> = fast.cells.iter().map(|&c| c as i32).collect();
        assert_eq!(widened, slow.cells);
    }
}
