//! A world's ramps read back from their blocks: a ramp enters the world as a run of fixed
//! blocks of class `ramp` following its slope (`import::ramp`), and the planner and the
//! climbing detector need the slope itself: where its foot is, which way is up, how long,
//! wide and high it is.

use crate::spec::{BoxSpec, WorldSpec};
use cloud::EntityClass;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// One ramp's slope, in world coordinates.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub(crate) struct RampGeometry {
    /// The ramp entity.
    pub entity: u32,
    /// Its machine name.
    pub name: String,
    /// The middle of the foot's edge, where the slope meets the floor (XY, m).
    pub foot_m: [f64; 2],
    /// Unit vector uphill (XY).
    pub uphill: [f64; 2],
    /// Horizontal length from foot to head (m).
    pub length_m: f64,
    /// Width across the slope (m).
    pub width_m: f64,
    /// The slope's height at the foot (m, world z).
    pub foot_z_m: f64,
    /// How much the slope rises from foot to head (m).
    pub rise_m: f64,
}

impl RampGeometry {
    /// How far `p` lies from the foot along the slope (m; negative before the foot).
    pub(crate) fn along_m(&self, p: [f64; 2]) -> f64 {
        (p[0] - self.foot_m[0]) * self.uphill[0] + (p[1] - self.foot_m[1]) * self.uphill[1]
    }

    /// The point on the centre line `t` metres up from the foot.
    pub(crate) fn centre_at(&self, t: f64) -> [f64; 2] {
        [
            self.foot_m[0] + self.uphill[0] * t,
            self.foot_m[1] + self.uphill[1] * t,
        ]
    }

    /// The slope's pitch (degrees).
    pub(crate) fn pitch_deg(&self) -> f64 {
        self.rise_m.atan2(self.length_m.max(1e-9)).to_degrees()
    }
}

fn top(b: &BoxSpec) -> f64 {
    b.center_m[2] + b.half_extents_m[2]
}

/// The corners of a box's footprint.
pub(crate) fn corners(b: &BoxSpec) -> [[f64; 2]; 4] {
    let (s, c) = b.yaw_deg.to_radians().sin_cos();
    let [hx, hy, _] = b.half_extents_m;
    [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(i, j)| {
        [
            b.center_m[0] + c * hx * i - s * hy * j,
            b.center_m[1] + s * hx * i + c * hy * j,
        ]
    })
}

/// The ramps of `world`, by entity id: each from its blocks, uphill from its lowest block's
/// top to its highest's, the foot and head where the blocks' footprints end along that line.
/// A ramp of one block, or of blocks all at one height, has no slope and is left out.
pub(crate) fn ramps_of(world: &WorldSpec) -> Vec<RampGeometry> {
    let mut blocks: BTreeMap<u32, (String, Vec<&BoxSpec>)> = BTreeMap::new();
    for f in world.fixed.iter().filter(|f| f.class == EntityClass::Ramp) {
        blocks
            .entry(f.entity)
            .or_insert_with(|| (f.name.clone(), vec![]))
            .1
            .push(&f.geometry);
    }
    blocks
        .into_iter()
        .filter_map(|(entity, (name, bs))| {
            let low = bs.iter().min_by(|a, b| top(a).total_cmp(&top(b)))?;
            let high = bs.iter().max_by(|a, b| top(a).total_cmp(&top(b)))?;
            let d = [
                high.center_m[0] - low.center_m[0],
                high.center_m[1] - low.center_m[1],
            ];
            let n = d[0].hypot(d[1]);
            if n < 1e-6 || top(high) - top(low) < 1e-6 {
                return None;
            }
            let uphill = [d[0] / n, d[1] / n];
            let across = [-uphill[1], uphill[0]];
            let proj = |p: [f64; 2], v: [f64; 2]| {
                (p[0] - low.center_m[0]) * v[0] + (p[1] - low.center_m[1]) * v[1]
            };
            let (mut t, mut s) = (
                [f64::INFINITY, f64::NEG_INFINITY],
                [f64::INFINITY, f64::NEG_INFINITY],
            );
            for p in bs.iter().flat_map(|b| corners(b)) {
                let (a, c) = (proj(p, uphill), proj(p, across));
                t = [t[0].min(a), t[1].max(a)];
                s = [s[0].min(c), s[1].max(c)];
            }
            // The tops follow the slope: its gradient from the lowest to the highest block.
            let gradient = (top(high) - top(low)) / n;
            let mid = (s[0] + s[1]) / 2.0;
            Some(RampGeometry {
                entity,
                name,
                foot_m: [
                    low.center_m[0] + uphill[0] * t[0] + across[0] * mid,
                    low.center_m[1] + uphill[1] * t[0] + across[1] * mid,
                ],
                uphill,
                length_m: t[1] - t[0],
                width_m: s[1] - s[0],
                foot_z_m: top(low) + gradient * t[0],
                rise_m: gradient * (t[1] - t[0]),
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::import::ramp::wedge_blocks;
    use crate::spec::FixedBox;

    #[test]
    fn a_wedge_is_read_back_as_its_slope() {
        // 4 m long, 1.5 m wide, rising 0.5 m towards +y from (1, 0) on z = 0.
        let b = BoxSpec {
            center_m: [1.0, 2.0, 0.25],
            half_extents_m: [2.0, 0.75, 0.25],
            yaw_deg: 90.0,
        };
        let world = WorldSpec {
            fixed: wedge_blocks(&b)
                .into_iter()
                .map(|geometry| FixedBox {
                    entity: 7,
                    class: EntityClass::Ramp,
                    name: "ramp".into(),
                    label: String::new(),
                    geometry,
                })
                .collect(),
            ..WorldSpec::default()
        };
        let r = ramps_of(&world);
        assert_eq!(r.len(), 1);
        let r = &r[0];
        assert_eq!((r.entity, r.name.as_str()), (7, "ramp"));
        let near = |a: f64, b: f64| (a - b).abs() < 1e-6;
        assert!(near(r.foot_m[0], 1.0) && near(r.foot_m[1], 0.0), "{r:?}");
        assert!(near(r.uphill[0], 0.0) && near(r.uphill[1], 1.0), "{r:?}");
        assert!(near(r.length_m, 4.0) && near(r.width_m, 1.5), "{r:?}");
        assert!(near(r.foot_z_m, 0.0) && near(r.rise_m, 0.5), "{r:?}");
        assert!(near(r.along_m([3.0, 2.5]), 2.5));
        assert!((r.pitch_deg() - 0.125_f64.atan().to_degrees()).abs() < 1e-9);
    }
}
