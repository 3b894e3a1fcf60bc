//! The door detectors: opened / closed (by the leaf's angle) and the free space's entered /
//! left (with the side, so a crossing can be told from a retreat).

use crate::events::{Emitter, EventConfig, EventKind};
use crate::world::{entity_refs, World};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Tracks each door's open/closed state.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub(crate) struct DoorDetector {
    /// Per door entity: whether it is open.
    open: BTreeMap<u32, bool>,
    /// Per door entity: the widest angle seen (degrees).
    pub widest_deg: BTreeMap<u32, f64>,
}

impl DoorDetector {
    pub(crate) fn new(world: &World, cfg: &EventConfig) -> DoorDetector {
        let mut d = DoorDetector::default();
        for door in &world.doors {
            let a = door.angle_deg(&world.physics);
            d.open.insert(door.entity, a > cfg.door_opened_deg);
            d.widest_deg.insert(door.entity, a);
        }
        d
    }

    pub(crate) fn update(&mut self, world: &World, cfg: &EventConfig, out: &mut Emitter) {
        for door in world.doors.iter().filter(|d| d.joint.is_some()) {
            let a = door.angle_deg(&world.physics);
            let widest = self.widest_deg.entry(door.entity).or_insert(a);
            *widest = widest.max(a);
            let open = self.open.entry(door.entity).or_insert(false);
            let change = if !*open && a > cfg.door_opened_deg {
                Some(EventKind::DoorOpened)
            } else if *open && a < cfg.door_closed_deg {
                Some(EventKind::DoorClosed)
            } else {
                None
            };
            if let Some(kind) = change {
                *open = kind == EventKind::DoorOpened;
                let ents = entity_refs(world, &[door.entity]);
                out.emit(kind, ents, "", &[("angle_deg", a)]);
            }
        }
    }
}

/// Tracks which robot is in which free space, and on which side it came in.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub(crate) struct FreeSpaceDetector {
    /// (robot index, free-space index) -> the side (+1/-1) the robot entered from.
    inside: BTreeMap<(usize, usize), f64>,
}

impl FreeSpaceDetector {
    pub(crate) fn update(&mut self, world: &World, out: &mut Emitter) {
        let np = &world.physics.narrow_phase;
        for (ri, robot) in world.robots.iter().enumerate() {
            let Some(chassis) = world.physics.bodies.get(robot.chassis) else {
                continue;
            };
            let p = chassis.translation();
            for (fi, fs) in world.free_spaces.iter().enumerate() {
                let now = np.intersection_pairs_with(fs.collider).any(|(a, b, hit)| {
                    hit && (a == robot.chassis_collider || b == robot.chassis_collider)
                });
                let side = {
                    let d = [p.x as f64 - fs.center_xy[0], p.y as f64 - fs.center_xy[1]];
                    if d[0] * fs.normal_xy[0] + d[1] * fs.normal_xy[1] >= 0.0 {
                        1.0
                    } else {
                        -1.0
                    }
                };
                let key = (ri, fi);
                let mut ids = vec![robot.entity, fs.entity];
                ids.extend(fs.door);
                match (self.inside.get(&key).copied(), now) {
                    (None, true) => {
                        self.inside.insert(key, side);
                        out.emit(
                            EventKind::DoorFreeSpaceEntered,
                            entity_refs(world, &ids),
                            "",
                            &[("side", side)],
                        );
                    }
                    (Some(from), false) => {
                        self.inside.remove(&key);
                        let crossed = if side != from { 1.0 } else { 0.0 };
                        out.emit(
                            EventKind::DoorFreeSpaceLeft,
                            entity_refs(world, &ids),
                            "",
                            &[("side", side), ("crossed", crossed)],
                        );
                    }
                    _ => {}
                }
            }
        }
    }
}
