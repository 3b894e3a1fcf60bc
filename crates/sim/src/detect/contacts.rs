//! Contacts: which robot touches which entity after each step (from rapier's contact pairs,
//! counting only contacts that exchanged an impulse in the step), and the collision detector that turns
//! that into started / continued / stopped events and wall touches. Rapier has no "continued"
//! event; ours comes at a fixed rate per touching pair.
//!
//! Wheel-vs-floor contacts are never collisions (wheels always touch the floor); a chassis or
//! arm touching the floor (after tipping over) is one. Wheel contacts with stair steps drive the
//! climbing events instead; chassis and arm contacts with steps are collisions. Wheels on a
//! ramp are no collision either (the ramp is driven on like the floor); they drive the ramp
//! climbing events.

use crate::events::{Emitter, EventConfig, EventKind};
use crate::world::tags::{Part, Tag};
use crate::world::{entity_refs, World};
use cloud::EntityClass;
use rapier3d::prelude::{ContactManifold, ContactPair};
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, BTreeSet};

/// A wheel standing on or touching a stair block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct WheelOnStairs {
    pub wheel: u16,
    pub stairs: u32,
    pub index: u16,
    /// The contact normal's z (towards the wheel): near 1 on a tread, near 0 on a riser.
    pub normal_z: f64,
}

/// What each robot touches after a step.
#[derive(Debug, Default)]
pub(crate) struct ContactScan {
    /// (robot index, other entity) pairs in collision.
    pub pairs: BTreeSet<(usize, u32)>,
    /// Per robot: wheel contacts with stairs.
    pub wheels_on_stairs: Vec<Vec<WheelOnStairs>>,
    /// Per robot: the wheels touching the floor.
    pub wheels_on_floor: Vec<BTreeSet<u16>>,
    /// Per robot: (ramp entity, wheel) for each wheel touching a ramp.
    pub wheels_on_ramps: Vec<BTreeSet<(u32, u16)>>,
}

pub(crate) fn scan(world: &World) -> ContactScan {
    let min_impulse = world.config.touch_impulse_ns as f32;
    let np = &world.physics.narrow_phase;
    let mut out = ContactScan::default();
    for (ri, robot) in world.robots.iter().enumerate() {
        let mut on_stairs = vec![];
        let mut on_floor = BTreeSet::new();
        let mut on_ramps = BTreeSet::new();
        for c in robot.colliders() {
            let Some(me) = world.tag(c) else { continue };
            for pair in np.contact_pairs_with(c) {
                if !pair.has_any_active_contact() {
                    continue;
                }
                let (other, flip) = if pair.collider1 == c {
                    (pair.collider2, -1.0)
                } else {
                    (pair.collider1, 1.0)
                };
                // (the other entity's tag, the contact normal's z towards `c`) per touch.
                let touches: Vec<(Tag, f64)> = if Some(other) == world.static_compound {
                    compound_touches(pair, pair.collider1 == other, flip, min_impulse)
                        .into_iter()
                        .filter_map(|(sub, nz)| Some((world.static_tag(sub)?, nz)))
                        .collect()
                } else {
                    let Some(tag) = world.tag(other) else {
                        continue;
                    };
                    let mut touching = None;
                    for m in pair.solver_manifolds() {
                        if m.points.iter().map(|p| p.data.impulse).sum::<f32>() > min_impulse {
                            // data.normal points from collider1 to collider2.
                            touching = Some(flip * m.data.normal.z as f64);
                            break;
                        }
                    }
                    touching.map(|nz| (tag, nz)).into_iter().collect()
                };
                for (tag, normal_z) in touches {
                    if tag.entity == robot.entity {
                        continue;
                    }
                    match (tag.class, me.part) {
                        (EntityClass::Floor, Part::Wheel) => {
                            on_floor.insert(me.index);
                        }
                        (EntityClass::Ramp, Part::Wheel) => {
                            on_ramps.insert((tag.entity, me.index));
                        }
                        (EntityClass::Stairs, Part::Wheel) => on_stairs.push(WheelOnStairs {
                            wheel: me.index,
                            stairs: tag.entity,
                            index: tag.index,
                            normal_z,
                        }),
                        _ => {
                            out.pairs.insert((ri, tag.entity));
                        }
                    }
                }
            }
        }
        out.wheels_on_stairs.push(on_stairs);
        out.wheels_on_floor.push(on_floor);
        out.wheels_on_ramps.push(on_ramps);
    }
    out
}

/// The sub-shapes of the static compound (collider 1 of the pair if `static_is_1`) that
/// exchanged more than `min_impulse` with the other collider in the last step, each with the
/// contact normal's z (times `flip`), in the order of the pair's manifolds.
///
/// Rapier hands the solver "clusters" instead of the per-sub-shape manifolds when a pair has
/// several (merging manifolds with nearly the same normal, e.g. the floor and a stair tread):
/// their points are copies of the manifolds' points (moved into collider 1's frame), and only
/// they receive impulses, so each impulse goes back to the manifold its point was copied from.
fn compound_touches(
    pair: &ContactPair,
    static_is_1: bool,
    flip: f64,
    min_impulse: f32,
) -> Vec<(u32, f64)> {
    let Some(rigid) = pair.rigid() else {
        return vec![];
    };
    let sub = |m: &ContactManifold| {
        if static_is_1 {
            m.subshape1
        } else {
            m.subshape2
        }
    };
    // (sub-shape, impulse, normal z), by first appearance.
    let mut acc: Vec<(u32, f32, f64)> = vec![];
    let mut add = |m: &ContactManifold, impulse: f32| {
        let s = sub(m);
        match acc.iter_mut().find(|a| a.0 == s) {
            Some(a) => a.1 += impulse,
            None => acc.push((s, impulse, flip * m.data.normal.z as f64)),
        }
    };
    if rigid.solver_clusters.is_empty() {
        for m in &rigid.manifolds {
            add(m, m.points.iter().map(|p| p.data.impulse).sum());
        }
    } else {
        for cluster in &rigid.solver_clusters {
            for p in cluster.points.iter().filter(|p| p.data.impulse > 0.0) {
                let origin = rigid.manifolds.iter().find(|m| {
                    m.points.iter().any(|q| {
                        let q1 = match m.subshape_pos1() {
                            Some(pos1) => *pos1 * q.local_p1,
                            None => q.local_p1,
                        };
                        q1 == p.local_p1
                    })
                });
                if let Some(m) = origin {
                    add(m, p.data.impulse);
                }
            }
        }
    }
    acc.into_iter()
        .filter(|a| a.1 > min_impulse)
        .map(|a| (a.0, a.2))
        .collect()
}

/// One touching pair.
#[derive(Debug, Clone, Serialize, Deserialize)]
struct PairState {
    started_s: f64,
    last_touch_s: f64,
    next_continued_s: f64,
}

/// Collision started / continued / stopped and wall touches, per (robot, entity) pair.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub(crate) struct ContactDetector {
    active: BTreeMap<(usize, u32), PairState>,
    /// Per robot index: total time touching any wall (s).
    pub wall_contact_s: BTreeMap<usize, f64>,
}

impl ContactDetector {
    pub(crate) fn update(
        &mut self,
        world: &World,
        scan: &ContactScan,
        cfg: &EventConfig,
        out: &mut Emitter,
    ) {
        let t = out.time_s;
        let period = if cfg.contact_rate_hz > 0.0 {
            1.0 / cfg.contact_rate_hz
        } else {
            f64::INFINITY
        };
        let mut wall_now = BTreeSet::new();
        for &(ri, other) in &scan.pairs {
            let Some(robot) = world.robots.get(ri) else {
                continue;
            };
            let class = world.entity(other).map(|e| e.class);
            let is_wall = class.is_some_and(touches_as_wall);
            if is_wall {
                wall_now.insert(ri);
            }
            let ents = || entity_refs(world, &[robot.entity, other]);
            match self.active.get_mut(&(ri, other)) {
                None => {
                    self.active.insert(
                        (ri, other),
                        PairState {
                            started_s: t,
                            last_touch_s: t,
                            next_continued_s: t + period,
                        },
                    );
                    out.emit(EventKind::CollisionStarted, ents(), "", &[]);
                    if is_wall {
                        out.emit(EventKind::WallTouched, ents(), "", &[]);
                    }
                }
                Some(p) => {
                    p.last_touch_s = t;
                    if t + 1e-9 >= p.next_continued_s {
                        p.next_continued_s += period;
                        let d = t - p.started_s;
                        out.emit(
                            EventKind::CollisionContinued,
                            ents(),
                            "",
                            &[("duration_s", d)],
                        );
                    }
                }
            }
        }
        let released: Vec<(usize, u32)> = self
            .active
            .iter()
            .filter(|(_, p)| {
                p.last_touch_s < t && t - p.last_touch_s + 1e-9 >= cfg.contact_release_s
            })
            .map(|(k, _)| *k)
            .collect();
        for key in released {
            if let Some(p) = self.active.remove(&key) {
                let Some(robot) = world.robots.get(key.0) else {
                    continue;
                };
                let d = p.last_touch_s - p.started_s;
                out.emit(
                    EventKind::CollisionStopped,
                    entity_refs(world, &[robot.entity, key.1]),
                    "",
                    &[("duration_s", d)],
                );
            }
        }
        for ri in wall_now {
            *self.wall_contact_s.entry(ri).or_insert(0.0) += world.dt_secs();
        }
    }
}

/// Classes a robot "touches a wall" with: walls and the lintels above doors.
fn touches_as_wall(class: EntityClass) -> bool {
    matches!(class, EntityClass::Wall | EntityClass::WallAboveDoor)
}
