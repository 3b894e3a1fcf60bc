//! Where a door leaf swings: the one place that turns a [`DoorInfo`]'s hinge edge and swing
//! side into a sense of rotation and a swept area (the semantic stage keeps obstacles out of
//! it; the simulation hinges the leaf with it).

use super::{DoorInfo, HingeEdge, OrientedBox, SwingSide};
use glam::DVec2;

impl DoorInfo {
    /// Whether the leaf opens counter-clockwise seen from above (z up): from the hinge its free
    /// edge points along the wall segment (hinge at the start edge) or against it (end edge),
    /// and it turns towards its swing side.
    pub fn opens_counter_clockwise(&self) -> bool {
        matches!(
            (self.hinge_edge, self.swing),
            (HingeEdge::Start, SwingSide::Left) | (HingeEdge::End, SwingSide::Right)
        )
    }

    /// The square a leaf of the closed box `closed` (the door entity's geometry, its first axis
    /// along the wall) sweeps opening up to 90 degrees: the bounding box of its quarter circle
    /// about the hinge on the swing side, as tall as the leaf.
    pub fn swing_square(&self, closed: &OrientedBox) -> OrientedBox {
        let (s, c) = closed.yaw_deg.to_radians().sin_cos();
        let (u, w) = (DVec2::new(c, s), closed.size_m[0]);
        // From the hinge to the closed leaf's free edge, then a quarter turn to the swing side.
        let along = match self.hinge_edge {
            HingeEdge::Start => u,
            HingeEdge::End => -u,
        };
        let side = if self.opens_counter_clockwise() {
            along.perp()
        } else {
            -along.perp()
        };
        let centre = DVec2::new(self.hinge_m[0], self.hinge_m[1]) + (along + side) * (w / 2.0);
        OrientedBox {
            center_m: [centre.x, centre.y, closed.center_m[2]],
            size_m: [w, w, closed.size_m[2]],
            yaw_deg: closed.yaw_deg,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn door(hinge_edge: HingeEdge, swing: SwingSide, hinge_x: f64) -> DoorInfo {
        DoorInfo {
            hinge_m: [hinge_x, 0.0, 0.0],
            hinge_axis: [0.0, 0.0, 1.0],
            hinge_edge,
            swing,
            observed_open_deg: 0.0,
        }
    }

    /// A 1 m leaf in a wall along +x from x = 0 to 1: each hinge edge and swing side sweeps
    /// the square on its side of the wall, and turns the matching way.
    #[test]
    fn the_swing_square_lies_on_the_swing_side_beside_the_hinge() {
        let closed = OrientedBox {
            center_m: [0.5, 0.0, 1.0],
            size_m: [1.0, 0.04, 2.0],
            yaw_deg: 0.0,
        };
        for (edge, swing, hinge_x, centre, ccw) in [
            (HingeEdge::Start, SwingSide::Left, 0.0, [0.5, 0.5], true),
            (HingeEdge::Start, SwingSide::Right, 0.0, [0.5, -0.5], false),
            (HingeEdge::End, SwingSide::Left, 1.0, [0.5, 0.5], false),
            (HingeEdge::End, SwingSide::Right, 1.0, [0.5, -0.5], true),
        ] {
            let d = door(edge, swing, hinge_x);
            let sq = d.swing_square(&closed);
            assert!(
                (sq.center_m[0] - centre[0]).abs() < 1e-9
                    && (sq.center_m[1] - centre[1]).abs() < 1e-9,
                "{edge:?} {swing:?}: {:?}",
                sq.center_m
            );
            assert_eq!(sq.size_m, [1.0, 1.0, 2.0]);
            assert_eq!(d.opens_counter_clockwise(), ccw, "{edge:?} {swing:?}");
        }
    }
}
