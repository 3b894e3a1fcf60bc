//! Dilation (paper, eq. 11, OpenCV's `cvDilate`): `dst(x, y) = max src(x + i, y + j)` over a
//! square structuring element of radius `radius_m` (so `2r + 1` pixels wide). It joins the two
//! faces of a wall into one band whose skeleton is the wall's centre line, and bridges small
//! gaps in sparsely seen walls. Computed separably (rows, then columns) with running counts.

use crate::error::Result;
use crate::image_frame::Mask;
use cloud::check_range;
use image::GrayImage;
use serde::{Deserialize, Serialize};

/// Configuration of the dilation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DilationConfig {
    /// Radius of the square structuring element (rounded to whole pixels).
    pub radius_m: f64,
}

impl Default for DilationConfig {
    fn default() -> Self {
        DilationConfig { radius_m: 0.15 }
    }
}

impl DilationConfig {
    pub(crate) fn validate(&self) -> Result<()> {
        check_range(
            "dilation.radius_m",
            self.radius_m,
            0.0,
            10.0,
            "within 0..10 m",
        )?;
        Ok(())
    }

    /// The radius in pixels at `resolution_m`.
    pub(crate) fn radius_px(&self, resolution_m: f64) -> usize {
        (self.radius_m / resolution_m).round().clamp(0.0, 1000.0) as usize
    }
}

/// The dilated copy of a binary image (non-zero = set) with a `(2r+1)`-pixel square element;
/// output pixels are 0 or 255.
pub fn dilate(image: &GrayImage, radius_px: u32) -> GrayImage {
    dilate_mask(&Mask::from_gray(image), radius_px as usize).to_gray()
}

pub(crate) fn dilate_mask(m: &Mask, r: usize) -> Mask {
    if r == 0 {
        return m.clone();
    }
    let (w, h) = (m.width, m.height);
    let rows = pass(&m.data, w, h, r, true);
    let data = pass(&rows, w, h, r, false);
    Mask {
        width: w,
        height: h,
        data,
    }
}

/// One separable max pass along rows (`horizontal`) or columns, with a running count of the
/// set pixels inside the window.
fn pass(src: &[bool], w: usize, h: usize, r: usize, horizontal: bool) -> Vec<bool> {
    let mut out = vec![false; w * h];
    let (lines, len) = if horizontal { (h, w) } else { (w, h) };
    let at = |line: usize, i: usize| {
        if horizontal {
            line * w + i
        } else {
            i * w + line
        }
    };
    for line in 0..lines {
        let mut count = 0usize;
        for i in 0..r.min(len) {
            count += usize::from(src[at(line, i)]);
        }
        for i in 0..len {
            if i + r < len {
                count += usize::from(src[at(line, i + r)]);
            }
            if i > r {
                count -= usize::from(src[at(line, i - r - 1)]);
            }
            out[at(line, i)] = count > 0;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dilates_to_a_square() {
        let mut m = Mask::new(9, 9);
        m.data[4 * 9 + 4] = true;
        let d = dilate_mask(&m, 2);
        assert_eq!(d.count(), 25);
        assert!(d.get(2, 2) && d.get(6, 6) && !d.get(1, 4) && !d.get(7, 4));
        let mut edge = Mask::new(5, 5);
        edge.data[0] = true;
        assert_eq!(dilate_mask(&edge, 1).count(), 4);
    }
}
