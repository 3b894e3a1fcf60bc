//! Ramp climbing, from the wheels' contacts with a ramp's blocks and the robot's place on its
//! slope: climbing starts when a wheel stands on the ramp with the robot's centre
//! `ramp_start_height_m` up the slope; it finishes when every
//! touching wheel stands on the ramp and the robot's centre is within `ramp_top_within_m` of
//! the head along the slope (a ramp's head may end in a drop: the robot stops short of it);
//! it is aborted when all touching wheels are back on the floor first (for `stairs_abort_s`),
//! with how high up the slope the robot's centre got.

use super::contacts::ContactScan;
use crate::events::{Emitter, EventConfig, EventKind};
use crate::ramps::{ramps_of, RampGeometry};
use crate::spec::WorldSpec;
use crate::world::robot::robot_pose;
use crate::world::{entity_refs, World};
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, BTreeSet};

/// One robot on one ramp.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
struct Climb {
    climbing: bool,
    finished: bool,
    /// The highest the robot's centre got up the slope in this climb (m above the foot).
    highest_m: f64,
    /// Since when the climbing robot's wheels have all been on the floor.
    off_since_s: Option<f64>,
}

/// The world's ramps and the climbing state per (robot index, ramp entity).
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub(crate) struct RampDetector {
    ramps: Vec<RampGeometry>,
    climbs: BTreeMap<(usize, u32), Climb>,
}

impl RampDetector {
    /// The detector of the ramps of `spec`.
    pub(crate) fn new(spec: &WorldSpec) -> RampDetector {
        RampDetector {
            ramps: ramps_of(spec),
            climbs: BTreeMap::new(),
        }
    }

    pub(crate) fn update(
        &mut self,
        world: &World,
        scan: &ContactScan,
        cfg: &EventConfig,
        out: &mut Emitter,
    ) {
        let (no_ramps, no_floor) = (BTreeSet::new(), BTreeSet::new());
        for (ri, robot) in world.robots.iter().enumerate() {
            // (borrowed: this runs every physics step)
            let on_ramps = scan.wheels_on_ramps.get(ri).unwrap_or(&no_ramps);
            let on_floor = scan.wheels_on_floor.get(ri).unwrap_or(&no_floor);
            let on_stairs = scan.wheels_on_stairs.get(ri).map_or(0, Vec::len);
            let pose = robot_pose(&world.physics, robot);
            for ramp in &self.ramps {
                let mine = on_ramps.iter().filter(|(r, _)| *r == ramp.entity).count();
                let others = on_ramps.len() - mine + on_floor.len() + on_stairs;
                let t = ramp.along_m([pose.x_m, pose.y_m]);
                let height_m = ramp.rise_m * (t / ramp.length_m.max(1e-9)).clamp(0.0, 1.0);
                let climb = self.climbs.entry((ri, ramp.entity)).or_default();
                let ids = [robot.entity, ramp.entity];
                // Started once the robot's centre is `ramp_start_height_m` up the slope (a
                // wheel grazing the foot's edge, or a path across its lowest centimetres, is
                // no climb).
                let up = height_m >= cfg.ramp_start_height_m && t <= ramp.length_m;
                if !climb.climbing && !climb.finished && mine > 0 && up {
                    climb.climbing = true;
                    climb.highest_m = 0.0;
                    climb.off_since_s = None;
                    out.emit(
                        EventKind::RampClimbingStarted,
                        entity_refs(world, &ids),
                        "",
                        &[],
                    );
                }
                if climb.climbing {
                    if mine > 0 {
                        climb.highest_m = climb.highest_m.max(height_m);
                    }
                    let at_top = t >= ramp.length_m - cfg.ramp_top_within_m && t <= ramp.length_m;
                    if mine > 0 && others == 0 && at_top {
                        climb.climbing = false;
                        climb.finished = true;
                        out.emit(
                            EventKind::RampClimbingFinished,
                            entity_refs(world, &ids),
                            "",
                            &[("height_m", ramp.rise_m)],
                        );
                    } else if mine == 0 && !on_floor.is_empty() {
                        // Back on the floor (for a while: wheels bounce at the foot).
                        let since = *climb.off_since_s.get_or_insert(out.time_s);
                        if out.time_s - since + 1e-9 >= cfg.stairs_abort_s {
                            climb.climbing = false;
                            climb.off_since_s = None;
                            out.emit(
                                EventKind::RampClimbingAborted,
                                entity_refs(world, &ids),
                                "",
                                &[("height_m", climb.highest_m)],
                            );
                        }
                    } else {
                        climb.off_since_s = None;
                    }
                } else if climb.finished && mine == 0 && !on_floor.is_empty() {
                    // Back on the floor after finishing: a new climb may start.
                    climb.finished = false;
                    climb.highest_m = 0.0;
                }
            }
        }
    }
}
