//! The scene every identification stage works in: the levelled points, their XY indexes,
//! and the floor, ceiling and projection band heights.

use crate::image_frame::ImageFrame;
use crate::points::XyIndex;
use glam::{DVec2, Vec3};

/// The scene every identification stage works in.
pub(crate) struct Scene<'a> {
    pub points: &'a [Vec3],
    /// All points.
    pub index: &'a XyIndex,
    /// The points off the floor and ceiling (within 5 cm of neither).
    pub upright: &'a XyIndex,
    /// The points in the projection band.
    pub band_index: &'a XyIndex,
    pub floor: f64,
    pub ceiling: f64,
    pub band: (f64, f64),
    /// The middle of the cloud (XY).
    pub middle: DVec2,
}

impl Scene<'_> {
    pub fn xy(&self, i: usize) -> DVec2 {
        DVec2::new(self.points[i].x as f64, self.points[i].y as f64)
    }

    /// A scene whose every index is `index` (tests: flat clouds that need no separate bands).
    #[cfg(test)]
    pub fn with_one_index<'a>(
        points: &'a [Vec3],
        index: &'a XyIndex,
        floor: f64,
        ceiling: f64,
    ) -> Scene<'a> {
        Scene {
            points,
            index,
            upright: index,
            band_index: index,
            floor,
            ceiling,
            band: (floor + 1.0, floor + 1.5),
            middle: DVec2::ZERO,
        }
    }

    /// True for a height `z` at the floor's or the ceiling's (within `tol`).
    pub fn on_slab(&self, z: f64, tol: f64) -> bool {
        (z - self.floor).abs() <= tol || (z - self.ceiling).abs() <= tol
    }
}

/// The cells of the XY indexes are at least this wide ...
const MIN_CELL_M: f64 = 0.25;
/// ... and at most this many across the image's larger side.
const MAX_CELLS_ACROSS: f64 = 4096.0;
/// Points within this of the floor or ceiling height are not upright.
const SLAB_MARGIN_M: f32 = 0.05;

/// The XY indexes a [`Scene`] borrows, and the heights it works with.
pub(crate) struct SceneIndexes {
    /// All points.
    pub index: XyIndex,
    upright: XyIndex,
    band_index: XyIndex,
    lo: DVec2,
    hi: DVec2,
    floor: f64,
    ceiling: f64,
    band: (f64, f64),
}

impl SceneIndexes {
    /// Indexes `points` over the image's area (three indexes built in parallel): all points,
    /// the upright ones (off the `floor` and `ceiling` heights) and those in the projection
    /// `band`.
    pub fn build(
        points: &[Vec3],
        frame: &ImageFrame,
        floor: f64,
        ceiling: f64,
        band: (f64, f64),
    ) -> SceneIndexes {
        let lo = DVec2::from_array(frame.to_map(0.0, frame.height_px as f64));
        let hi = DVec2::from_array(frame.to_map(frame.width_px as f64, 0.0));
        let cell = MIN_CELL_M.max((hi - lo).max_element() / MAX_CELLS_ACROSS);
        let (floor_z, ceiling_z) = (floor as f32, ceiling as f32);
        let (index, (upright, band_index)) = rayon::join(
            || XyIndex::new(points, lo, hi, cell),
            || {
                rayon::join(
                    || {
                        XyIndex::filtered(points, lo, hi, cell, |p| {
                            (p.z - floor_z).abs() > SLAB_MARGIN_M
                                && (p.z - ceiling_z).abs() > SLAB_MARGIN_M
                        })
                    },
                    || {
                        XyIndex::filtered(points, lo, hi, cell, |p| {
                            p.z as f64 >= band.0 && p.z as f64 <= band.1
                        })
                    },
                )
            },
        );
        SceneIndexes {
            index,
            upright,
            band_index,
            lo,
            hi,
            floor,
            ceiling,
            band,
        }
    }

    /// The scene of `points` (those indexed).
    pub fn scene<'a>(&'a self, points: &'a [Vec3]) -> Scene<'a> {
        Scene {
            points,
            index: &self.index,
            upright: &self.upright,
            band_index: &self.band_index,
            floor: self.floor,
            ceiling: self.ceiling,
            band: self.band,
            middle: (self.lo + self.hi) / 2.0,
        }
    }
}
