//! What the planner needs of a robot model: its footprint (half width and half length over
//! chassis and wheels), its height (chassis and stowed arm) and the step rise it climbs, all
//! derived from the model's geometry.

use crate::model::{ArmAxis, RobotModel};

/// A robot's size for planning (metres).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Footprint {
    /// Half the width over the wheels and chassis: the inscribed radius the grid is inflated by.
    pub half_width_m: f64,
    /// Half the length over the wheels and chassis.
    pub half_length_m: f64,
    /// Half the chassis' own length (the body the door sensors see).
    pub chassis_half_length_m: f64,
    /// The highest point above the surface under the wheels (chassis or stowed arm).
    pub height_m: f64,
    /// The highest step the robot climbs.
    pub max_rise_m: f64,
}

/// Cleated wheels hook onto a nosing like a track's grousers and climb a step up to this share
/// of their outer radius (tyre + cleat): the rest of the wheel must reach over the nosing.
/// The built-in inspection robot (0.18 m + 0.03 m cleats) so climbs 0.168 m, its documented
/// "rise up to ~0.17 m".
const CLEATED_RISE_SHARE: f64 = 0.8;

impl Footprint {
    /// The footprint of a model.
    pub fn of(m: &RobotModel) -> Footprint {
        let c = &m.chassis;
        let outer = |w: &crate::model::WheelModel| {
            w.radius_m + if w.cleats > 0 { w.cleat_height_m } else { 0.0 }
        };
        let half_width_m = m
            .wheels
            .iter()
            .map(|w| w.position_m[1].abs() + w.width_m / 2.0)
            .fold(c.size_m[1] / 2.0, f64::max);
        let half_length_m = m
            .wheels
            .iter()
            .map(|w| w.position_m[0].abs() + outer(w))
            .fold(c.size_m[0] / 2.0, f64::max);
        let centre_z = m.chassis_height_m();
        let arm_top = m.arm.as_ref().map_or(0.0, |a| {
            // The stowed arm's highest point: each pitch link rises by length x sin(its
            // accumulated pitch), plus half its thickness.
            let (mut z, mut pitch, mut top) = (a.mount_m[2], 0.0_f64, a.mount_m[2]);
            for l in &a.links {
                if l.axis == ArmAxis::Pitch {
                    pitch += l.angle_deg.to_radians();
                }
                z += l.length_m * pitch.sin();
                top = top.max(z + l.thickness_m / 2.0);
            }
            top
        });
        let height_m = centre_z + (c.size_m[2] / 2.0).max(arm_top);
        let max_rise_m = m
            .wheels
            .iter()
            .map(|w| {
                if w.cleats > 0 && w.cleat_height_m > 0.0 {
                    CLEATED_RISE_SHARE * outer(w)
                } else {
                    friction_rise_m(w.radius_m, m.drive.wheel_friction)
                }
            })
            .fold(f64::INFINITY, f64::min);
        Footprint {
            half_width_m,
            half_length_m,
            chassis_half_length_m: c.size_m[0] / 2.0,
            height_m,
            max_rise_m: if max_rise_m.is_finite() {
                max_rise_m
            } else {
                0.0
            },
        }
    }

    /// The radius the robot sweeps turning in place (the circumscribed circle).
    pub fn turn_radius_m(&self) -> f64 {
        self.half_width_m.hypot(self.half_length_m)
    }
}

/// The kerb a plain tyre of radius `r` climbs by friction alone: it rolls up while the edge's
/// contact normal is no steeper than the friction cone allows, i.e. the contact angle from the
/// vertical `theta` has `tan(theta) <= mu`, so `h = r (1 - cos(theta)) = r (1 - 1/sqrt(1 + mu^2))`.
/// (Pioneer 3-AT, r = 0.1075 m, mu = 0.9: 0.028 m; no stair step.)
fn friction_rise_m(r: f64, mu: f64) -> f64 {
    r * (1.0 - 1.0 / (1.0 + mu * mu).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_inspection_robot_climbs_its_documented_rise_and_the_pioneer_no_stair_step() {
        let i = Footprint::of(&RobotModel::builtin("inspection").expect("built in"));
        assert!((i.max_rise_m - 0.168).abs() < 1e-9, "{i:?}");
        // Wheels at y = 0.25 m, 0.1 m wide: 0.30 m; axles at 0.35 m, outer radius 0.21 m.
        assert!((i.half_width_m - 0.30).abs() < 1e-9, "{i:?}");
        assert!((i.half_length_m - 0.56).abs() < 1e-9, "{i:?}");
        assert!(i.height_m > 0.3 && i.height_m < 0.7, "{i:?}");
        let p = Footprint::of(&RobotModel::builtin("pioneer3at").expect("built in"));
        assert!(p.max_rise_m > 0.02 && p.max_rise_m < 0.05, "{p:?}");
        // The Pioneer 3-AT is 0.497 m wide over its wheels.
        assert!((2.0 * p.half_width_m - 0.495).abs() < 0.01, "{p:?}");
        assert!(p.turn_radius_m() > p.half_width_m);
    }
}
