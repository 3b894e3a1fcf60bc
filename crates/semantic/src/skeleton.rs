//! Skeletonisation: Zhang-Suen thinning (Zhang & Suen, CACM 27(3), 1984), in place of the
//! paper's Pavlidis thinning (both peel border pixels while keeping 8-connectivity). The thick
//! bands left by the dilation become one-pixel lines along their middle, the wall centre lines
//! the Hough transform then finds ("neighbouring objects are going to be connected for better
//! hough transform result").
//!
//! Two sub-iterations alternate until nothing changes; each deletes, in parallel, the set
//! pixels `P1` with neighbours `P2..P9` (clockwise from north) where
//! `2 <= B(P1) <= 6` (set neighbours), `A(P1) = 1` (0->1 transitions around `P2..P9, P2`), and
//! `P2 P4 P6 = 0, P4 P6 P8 = 0` (first) or `P2 P4 P8 = 0, P2 P6 P8 = 0` (second). Both rules are
//! precomputed as 256-entry tables over the neighbour pattern. As in the original algorithm,
//! an isolated 2 x 2 block vanishes; every larger shape keeps its connectivity.

use crate::image_frame::Mask;
use image::GrayImage;

/// The thinned copy of a binary image (non-zero = set); output pixels are 0 or 255.
pub fn skeletonize(image: &GrayImage) -> GrayImage {
    thin(&Mask::from_gray(image)).to_gray()
}

/// Neighbour offsets P2..P9 as (dx, dy), clockwise from north.
const RING: [(isize, isize); 8] = [
    (0, -1),
    (1, -1),
    (1, 0),
    (1, 1),
    (0, 1),
    (-1, 1),
    (-1, 0),
    (-1, -1),
];

fn table(first: bool) -> [bool; 256] {
    let mut t = [false; 256];
    for (pattern, entry) in t.iter_mut().enumerate() {
        let p = |k: usize| (pattern >> k) & 1 == 1; // bit k = P(k + 2)
        let b = (0..8).filter(|&k| p(k)).count();
        let a = (0..8).filter(|&k| !p(k) && p((k + 1) % 8)).count();
        let (p2, p4, p6, p8) = (p(0), p(2), p(4), p(6));
        let c = if first {
            !(p4 && p6 && (p2 || p8))
        } else {
            !(p2 && p8 && (p4 || p6))
        };
        *entry = (2..=6).contains(&b) && a == 1 && c;
    }
    t
}

pub(crate) fn thin(m: &Mask) -> Mask {
    let (w, h) = (m.width, m.height);
    let pw = w + 2;
    // Padded copy: a one-pixel empty border spares bounds checks.
    let mut img = vec![0u8; pw * (h + 2)];
    let mut live: Vec<usize> = Vec::new();
    for y in 0..h {
        for x in 0..w {
            if m.data[y * w + x] {
                let i = (y + 1) * pw + x + 1;
                img[i] = 1;
                live.push(i);
            }
        }
    }
    let offsets: Vec<isize> = RING.iter().map(|&(dx, dy)| dy * pw as isize + dx).collect();
    let tables = [table(true), table(false)];
    let mut delete = Vec::new();
    loop {
        let mut changed = false;
        for t in &tables {
            delete.clear();
            for &i in &live {
                let mut pattern = 0usize;
                for (k, off) in offsets.iter().enumerate() {
                    pattern |= (img[(i as isize + off) as usize] as usize) << k;
                }
                if t[pattern] {
                    delete.push(i);
                }
            }
            for &i in &delete {
                img[i] = 0;
            }
            if !delete.is_empty() {
                changed = true;
                live.retain(|&i| img[i] == 1);
            }
        }
        if !changed {
            break;
        }
    }
    let mut out = Mask::new(w, h);
    for i in live {
        let (y, x) = (i / pw - 1, i % pw - 1);
        out.data[y * w + x] = true;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn components(m: &Mask) -> usize {
        let mut seen = vec![false; m.data.len()];
        let mut n = 0;
        for start in 0..m.data.len() {
            if !m.data[start] || seen[start] {
                continue;
            }
            n += 1;
            let mut stack = vec![start];
            seen[start] = true;
            while let Some(i) = stack.pop() {
                let (x, y) = ((i % m.width) as isize, (i / m.width) as isize);
                for (dx, dy) in RING {
                    let (a, b) = (x + dx, y + dy);
                    if m.get(a, b) {
                        let j = b as usize * m.width + a as usize;
                        if !seen[j] {
                            seen[j] = true;
                            stack.push(j);
                        }
                    }
                }
            }
        }
        n
    }

    #[test]
    fn thins_bars_to_one_pixel_and_keeps_shapes_connected() {
        let mut m = Mask::new(60, 40);
        let mut set = |x0: usize, x1: usize, y0: usize, y1: usize| {
            for y in y0..y1 {
                for x in x0..x1 {
                    m.data[y * 60 + x] = true;
                }
            }
        };
        set(5, 55, 10, 17); // a horizontal bar 7 px thick
        set(20, 27, 17, 35); // a T-leg
        set(40, 52, 25, 38); // a separate block
        set(45, 47, 30, 33); // (inside it)
        let before = components(&m);
        let s = thin(&m);
        assert_eq!(components(&s), before);
        // The bar's middle column holds exactly one skeleton pixel.
        let col: usize = (0..40).filter(|&y| s.get(12, y)).count();
        assert_eq!(col, 1);
        assert!(s.count() < m.count() / 4);
    }

    #[test]
    fn a_ring_stays_a_ring() {
        let mut m = Mask::new(30, 30);
        for y in 0..30 {
            for x in 0..30 {
                let r = ((x as f64 - 15.0).powi(2) + (y as f64 - 15.0).powi(2)).sqrt();
                m.data[y * 30 + x] = (7.0..11.0).contains(&r);
            }
        }
        let s = thin(&m);
        assert_eq!(components(&s), 1);
        // The ring is not broken: every axis ray from the centre crosses it.
        for (dx, dy) in [(0, -1), (1, 0), (0, 1), (-1, 0)] {
            assert!(
                (1..15).any(|k| s.get(15 + dx * k, 15 + dy * k)),
                "ray {dx},{dy} escapes"
            );
        }
    }
}
