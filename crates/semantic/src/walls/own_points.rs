//! Own points: every wall rests on points of its own (the issue's "every wall rests on points
//! of its own"). The walls claim the upright points in their slabs (off the floor and
//! ceiling, within the wall's height) in the walls' order, as the per-point labels will; a wall
//! most of whose slab's points an earlier wall had already claimed stands on another's
//! points, not its own: a line cut across the corner where two walls meet, a copy of a wall a
//! few degrees off it, a door leaf against its wall. It would label almost nothing, and in the
//! simulated world it would add a solid slab where the scans saw only the other wall: it is
//! dropped.

use super::WallFit;
use crate::scene::Scene;

/// The least share of the points in a wall's slab that must be its own (claimed by no
/// longer wall): a wall stands on its own points more than on another's. A wall meeting
/// another at a corner or a T shares only the other's thickness of its length; a line across
/// the corner of two walls shares almost all of it. (On the styles bench the true walls hold
/// 69 % or more; the lines that were no wall under 2 % to 26 %.)
pub(crate) const MIN_OWN_SHARE: f64 = 0.5;

/// Keeps the walls that rest on points of their own, claiming in the order given (the order
/// the labels use: longest first as fitted); `tol` is the slab's margin beyond half the
/// wall's thickness. Each kept wall's rules say how many.
pub(crate) fn retain_walls_with_own_points(walls: &mut Vec<WallFit>, sc: &Scene, tol: f64) {
    let mut claimed = vec![false; sc.points.len()];
    walls.retain_mut(|w| {
        let (mut total, mut own) = (0usize, Vec::new());
        sc.upright.for_each_near_line(
            &w.line,
            -tol,
            w.length + tol,
            w.thickness / 2.0 + tol,
            |i, _, _, z| {
                if z < w.z_range.0 - tol || z > w.z_range.1 + tol {
                    return;
                }
                total += 1;
                if !claimed[i] {
                    own.push(i);
                }
            },
        );
        let share = own.len() as f64 / total.max(1) as f64;
        if own.is_empty() || share < MIN_OWN_SHARE {
            return false;
        }
        for &i in &own {
            claimed[i] = true;
        }
        w.rules.push(format!(
            "rests on {} points of its own, {:.0} % of those in its slab (a wall needs {:.0} %: \
             a line across two walls' corner has almost none)",
            own.len(),
            100.0 * share,
            100.0 * MIN_OWN_SHARE
        ));
        true
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::points::XyIndex;
    use glam::{DVec2, Vec3};

    /// Points on a vertical face along `from`..`to`, every 2 cm, from 0.1 to 2.4 m high.
    fn face(from: DVec2, to: DVec2) -> Vec<Vec3> {
        let n = (from.distance(to) / 0.02) as usize;
        (0..=n)
            .flat_map(|k| {
                let p = from.lerp(to, k as f64 / n as f64);
                (1..24).map(move |j| Vec3::new(p.x as f32, p.y as f32, j as f32 * 0.1))
            })
            .collect()
    }

    fn wall(from: DVec2, to: DVec2) -> WallFit {
        let mut w = WallFit::one_sided(from, to, 1.0);
        w.thickness = 0.2;
        w.z_range = (0.0, 2.5);
        w
    }

    /// Regression (garage-8 of the styles bench): a 0.9 m line across the corner of two outer
    /// walls, 17 degrees off the longer one, held 6 points of its own among the 366 in its
    /// slab; it became a wall standing diagonally in the corner.
    #[test]
    fn a_line_across_two_walls_corner_is_no_wall_while_the_wall_meeting_it_stays() {
        let mut points = face(DVec2::new(0.0, 0.0), DVec2::new(10.0, 0.0));
        points.extend(face(DVec2::new(10.0, 0.0), DVec2::new(10.0, 4.0)));
        let index = XyIndex::new(&points, DVec2::new(-1.0, -1.0), DVec2::new(11.0, 5.0), 0.25);
        let sc = Scene::with_one_index(&points, &index, 0.0, 2.5);
        let mut walls = vec![
            wall(DVec2::new(0.0, 0.0), DVec2::new(10.0, 0.0)),
            wall(DVec2::new(10.0, 0.0), DVec2::new(10.0, 4.0)),
            // 0.9 m long, from the long wall 0.35 m before the corner at 17 degrees.
            wall(
                DVec2::new(9.1, 0.0),
                DVec2::new(9.1, 0.0) + DVec2::from_angle(17f64.to_radians()) * 0.9,
            ),
        ];
        retain_walls_with_own_points(&mut walls, &sc, 0.04);
        assert_eq!(walls.len(), 2, "{walls:?}");
        assert!(walls
            .iter()
            .all(|w| w.rules.iter().any(|r| r.contains("of its own"))));
    }
}
