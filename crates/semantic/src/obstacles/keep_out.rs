//! The cells of the obstacles' (and ramps') grid that are no obstacle's: those within a wall's
//! slab, and those in the footprint of a door leaf or a staircase (see the `obstacles` module,
//! step 1), each grown by a margin (the faces' noise).

use crate::image_frame::{pixel_center, pixel_range, ImageFrame};
use crate::map::OrientedBox;
use crate::walls::WallFit;
use glam::DVec2;

/// Marks the cells whose centres lie in a box's footprint grown by `margin`.
pub(crate) fn exclude_boxes(
    frame: &ImageFrame,
    boxes: &[OrientedBox],
    margin: f64,
    excluded: &mut [bool],
) {
    let w = frame.width_px as usize;
    for b in boxes {
        let (s, co) = b.yaw_deg.to_radians().sin_cos();
        let (axis, centre) = (DVec2::new(co, s), DVec2::new(b.center_m[0], b.center_m[1]));
        let half = DVec2::new(b.size_m[0] / 2.0 + margin, b.size_m[1] / 2.0 + margin);
        let reach = DVec2::splat(half.length());
        let Some((c0, c1, r0, r1)) = pixel_range(frame, centre - reach, centre + reach) else {
            continue;
        };
        for row in r0..=r1 {
            for col in c0..=c1 {
                let r = pixel_center(frame, col as f64, row as f64) - centre;
                if r.dot(axis).abs() <= half.x && r.dot(axis.perp()).abs() <= half.y {
                    excluded[row * w + col] = true;
                }
            }
        }
    }
}

/// Per cell of `frame`: whether it lies within a wall's slab grown by `margin` (its points
/// are the wall's).
pub(crate) fn wall_cells(frame: &ImageFrame, walls: &[WallFit], margin: f64) -> Vec<bool> {
    let w = frame.width_px as usize;
    let mut excluded = vec![false; frame.len()];
    for wall in walls {
        let half = wall.thickness / 2.0 + margin;
        let (a, b) = (wall.start(), wall.end());
        let lo = a.min(b) - DVec2::splat(half);
        let hi = a.max(b) + DVec2::splat(half);
        let Some((c0, c1, r0, r1)) = pixel_range(frame, lo, hi) else {
            continue;
        };
        for row in r0..=r1 {
            for col in c0..=c1 {
                let q = pixel_center(frame, col as f64, row as f64);
                let (s, d) = wall.line.coords(q);
                if d.abs() <= half && s >= -margin && s <= wall.length + margin {
                    excluded[row * w + col] = true;
                }
            }
        }
    }
    excluded
}
