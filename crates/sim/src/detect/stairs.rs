//! Stair climbing, from the wheels' contacts with the steps: climbing starts when a wheel first
//! stands on a tread; a step is reached when a wheel stands on it (lower steps skipped over are
//! reported too, in order); climbing finishes when every touching wheel stands on the top (the
//! landing, or the top step without one); it is aborted when all touching wheels are back on
//! the floor first (for `stairs_abort_s`; wheels bounce off the steps).

use super::contacts::ContactScan;
use crate::events::{Emitter, EventConfig, EventKind};
use crate::world::{entity_refs, World};
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, BTreeSet};

/// One robot on one staircase.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
struct Climb {
    climbing: bool,
    finished: bool,
    /// The highest step index reached (-1: none).
    highest: i32,
    /// Since when the climbing robot's wheels have all been on the floor.
    off_since_s: Option<f64>,
}

/// Climbing state per (robot index, stairs entity).
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub(crate) struct StairsDetector {
    climbs: BTreeMap<(usize, u32), Climb>,
}

impl StairsDetector {
    pub(crate) fn update(
        &mut self,
        world: &World,
        scan: &ContactScan,
        cfg: &EventConfig,
        out: &mut Emitter,
    ) {
        for (ri, robot) in world.robots.iter().enumerate() {
            let contacts = scan
                .wheels_on_stairs
                .get(ri)
                .map(Vec::as_slice)
                .unwrap_or(&[]);
            let on_floor = scan.wheels_on_floor.get(ri).cloned().unwrap_or_default();
            for stairs in &world.stairs {
                let top = if stairs.has_landing {
                    stairs.steps
                } else {
                    stairs.steps.saturating_sub(1)
                };
                let mine: Vec<_> = contacts
                    .iter()
                    .filter(|c| c.stairs == stairs.entity)
                    .collect();
                let standing: BTreeSet<u16> = mine
                    .iter()
                    .filter(|c| c.normal_z >= cfg.tread_normal_z)
                    .map(|c| c.index)
                    .collect();
                let climb = self.climbs.entry((ri, stairs.entity)).or_insert(Climb {
                    highest: -1,
                    ..Default::default()
                });
                let ids = [robot.entity, stairs.entity];
                if !climb.climbing && !climb.finished && !standing.is_empty() {
                    climb.climbing = true;
                    climb.highest = -1;
                    out.emit(
                        EventKind::StairsClimbingStarted,
                        entity_refs(world, &ids),
                        "",
                        &[],
                    );
                }
                if climb.climbing {
                    let high = standing.iter().next_back().map(|&i| i as i32).unwrap_or(-1);
                    while climb.highest < high {
                        climb.highest += 1;
                        let detail = if climb.highest == stairs.steps as i32 {
                            "landing"
                        } else {
                            ""
                        };
                        out.emit(
                            EventKind::StairsStepReached,
                            entity_refs(world, &ids),
                            detail,
                            &[("step", climb.highest as f64)],
                        );
                    }
                    // Every wheel that touches anything stands on the top.
                    let touching: BTreeSet<u16> = mine
                        .iter()
                        .map(|c| c.wheel)
                        .chain(on_floor.iter().copied())
                        .collect();
                    let on_top: BTreeSet<u16> = mine
                        .iter()
                        .filter(|c| c.index == top && c.normal_z >= cfg.tread_normal_z)
                        .map(|c| c.wheel)
                        .collect();
                    let all_on_top = !on_top.is_empty()
                        && on_top.len() * 2 >= robot.wheels.len()
                        && touching.iter().all(|w| on_top.contains(w))
                        && mine.iter().all(|c| c.index == top);
                    if all_on_top {
                        climb.climbing = false;
                        climb.finished = true;
                        out.emit(
                            EventKind::StairsClimbingFinished,
                            entity_refs(world, &ids),
                            "",
                            &[("step", top as f64)],
                        );
                    } else if mine.is_empty() && !on_floor.is_empty() {
                        // Back on the floor (for a while: wheels bounce off the steps).
                        let since = *climb.off_since_s.get_or_insert(out.time_s);
                        if out.time_s - since + 1e-9 >= cfg.stairs_abort_s {
                            climb.climbing = false;
                            climb.off_since_s = None;
                            out.emit(
                                EventKind::StairsClimbingAborted,
                                entity_refs(world, &ids),
                                "",
                                &[("step", climb.highest as f64)],
                            );
                        }
                    } else {
                        climb.off_since_s = None;
                    }
                } else if climb.finished && mine.is_empty() && !on_floor.is_empty() {
                    // Back on the floor after finishing: a new climb may start.
                    climb.finished = false;
                    climb.highest = -1;
                }
            }
        }
    }

    /// The highest step reached by robot `ri` on staircase `stairs` (-1: none).
    pub(crate) fn highest(&self, ri: usize, stairs: u32) -> i32 {
        self.climbs
            .get(&(ri, stairs))
            .map(|c| c.highest)
            .unwrap_or(-1)
    }
}
