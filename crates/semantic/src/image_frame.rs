//! Images in the map frame: where a pixel lies ([`ImageFrame`]) and binary images.

use glam::DVec2;
use image::GrayImage;
use serde::{Deserialize, Serialize};

/// Where an image lies in the map frame: pixel `(col, row)` covers
/// `x in [origin_x + col*res, +res)`, `y in (origin_y - (row+1)*res, origin_y - row*res]`
/// (row 0 is the top, north up).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ImageFrame {
    /// Map x of the image's left edge and y of its top edge.
    pub origin_m: [f64; 2],
    /// Pixel edge.
    pub resolution_m: f64,
    /// Width in pixels.
    pub width_px: u32,
    /// Height in pixels.
    pub height_px: u32,
}

impl ImageFrame {
    /// The same area at `cell_m` cells, or this frame itself if that would exceed
    /// `max_pixels` (the obstacles' and ramps' grids).
    pub(crate) fn at_cell(&self, cell_m: f64, max_pixels: u64) -> ImageFrame {
        let scale = self.resolution_m / cell_m;
        let own = ImageFrame {
            origin_m: self.origin_m,
            resolution_m: cell_m,
            width_px: (self.width_px as f64 * scale).ceil().max(1.0) as u32,
            height_px: (self.height_px as f64 * scale).ceil().max(1.0) as u32,
        };
        if (own.len() as u64) <= max_pixels {
            own
        } else {
            *self
        }
    }

    /// The pixel containing map point `(x, y)`, if inside the image.
    pub fn pixel_of(&self, x: f64, y: f64) -> Option<(u32, u32)> {
        let c = ((x - self.origin_m[0]) / self.resolution_m).floor();
        let r = ((self.origin_m[1] - y) / self.resolution_m).floor();
        (c >= 0.0 && r >= 0.0 && c < self.width_px as f64 && r < self.height_px as f64)
            .then_some((c as u32, r as u32))
    }

    /// The map point of (continuous) pixel coordinates; `(c + 0.5, r + 0.5)` is a pixel's centre.
    pub fn to_map(&self, col: f64, row: f64) -> [f64; 2] {
        [
            self.origin_m[0] + col * self.resolution_m,
            self.origin_m[1] - row * self.resolution_m,
        ]
    }

    /// Continuous pixel coordinates of a map point.
    pub fn to_pixel(&self, x: f64, y: f64) -> [f64; 2] {
        [
            (x - self.origin_m[0]) / self.resolution_m,
            (self.origin_m[1] - y) / self.resolution_m,
        ]
    }

    pub(crate) fn len(&self) -> usize {
        self.width_px as usize * self.height_px as usize
    }
}

/// A binary image: `true` = set.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Mask {
    pub width: usize,
    pub height: usize,
    pub data: Vec<bool>,
}

impl Mask {
    pub fn new(width: usize, height: usize) -> Mask {
        Mask {
            width,
            height,
            data: vec![false; width * height],
        }
    }

    pub fn from_gray(img: &GrayImage) -> Mask {
        Mask {
            width: img.width() as usize,
            height: img.height() as usize,
            data: img.as_raw().iter().map(|&v| v > 0).collect(),
        }
    }

    pub fn get(&self, x: isize, y: isize) -> bool {
        x >= 0
            && y >= 0
            && (x as usize) < self.width
            && (y as usize) < self.height
            && self.data[y as usize * self.width + x as usize]
    }

    #[cfg(test)]
    pub fn count(&self) -> usize {
        self.data.iter().filter(|&&v| v).count()
    }

    pub fn to_gray(&self) -> GrayImage {
        GrayImage::from_raw(
            self.width as u32,
            self.height as u32,
            self.data.iter().map(|&v| if v { 255 } else { 0 }).collect(),
        )
        .unwrap_or_default()
    }
}

/// The inclusive pixel ranges `(col0, col1, row0, row1)` covering the map box `[lo, hi]`,
/// clipped to the image; `None` if it misses the image.
pub(crate) fn pixel_range(
    frame: &ImageFrame,
    lo: DVec2,
    hi: DVec2,
) -> Option<(usize, usize, usize, usize)> {
    let a = frame.to_pixel(lo.x, hi.y);
    let b = frame.to_pixel(hi.x, lo.y);
    let (w, h) = (frame.width_px as f64, frame.height_px as f64);
    let c0 = a[0].floor().max(0.0);
    let r0 = a[1].floor().max(0.0);
    let c1 = b[0].floor().min(w - 1.0);
    let r1 = b[1].floor().min(h - 1.0);
    (c0 <= c1 && r0 <= r1 && c1 >= 0.0 && r1 >= 0.0).then_some((
        c0 as usize,
        c1 as usize,
        r0 as usize,
        r1 as usize,
    ))
}

/// The map XY of a pixel's centre.
pub(crate) fn pixel_center(frame: &ImageFrame, col: f64, row: f64) -> DVec2 {
    let [x, y] = frame.to_map(col + 0.5, row + 0.5);
    DVec2::new(x, y)
}
