//! Doors: leaves on revolute joints (axis z through the hinge, limits, damping, hinge friction),
//! the opened/closed detector and the free-space detector (entered, left, crossed).

use crate::events::{Emitter, EntityRef, EventConfig, EventKind};
use crate::spec::{DoorSpec, EntityClass};
use crate::world::{cuboid, groups, Part, Tag, World, G_DOOR, G_ROBOT};
use glam::{Quat, Vec3};
use rapier3d::prelude::{
    ColliderHandle, ImpulseJointHandle, PhysicsWorld, Pose, RevoluteJointBuilder, RigidBodyBuilder,
    RigidBodyHandle,
};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// A door leaf in the world.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(crate) struct DoorBody {
    pub entity: u32,
    pub wall: u32,
    pub body: RigidBodyHandle,
    pub collider: ColliderHandle,
    /// `None` once broken.
    pub joint: Option<ImpulseJointHandle>,
    /// +1 if the door opens counter-clockwise.
    pub sign: f64,
    pub break_force_n: Option<f64>,
    pub initial_deg: f64,
}

impl DoorBody {
    /// The opening angle (degrees): the leaf body's yaw (zero when closed) in the opening sense.
    pub(crate) fn angle_deg(&self, physics: &PhysicsWorld) -> f64 {
        let Some(b) = physics.bodies.get(self.body) else {
            return 0.0;
        };
        let x = b.rotation() * Vec3::X;
        self.sign * (x.y as f64).atan2(x.x as f64).to_degrees()
    }
}

/// Builds the leaf body (origin at the hinge, identity rotation when closed) and its hinge.
pub(crate) fn spawn_door(
    physics: &mut PhysicsWorld,
    ground: RigidBodyHandle,
    d: &DoorSpec,
    friction: f32,
) -> DoorBody {
    let sign = d.opens.sign();
    let hinge = Vec3::new(
        d.hinge_m[0] as f32,
        d.hinge_m[1] as f32,
        d.leaf.center_m[2] as f32,
    );
    let open = (sign * d.initial_deg).to_radians() as f32;
    let body = physics.bodies.insert(
        RigidBodyBuilder::dynamic()
            .pose(Pose::from_parts(hinge, Quat::from_rotation_z(open)))
            .angular_damping(d.damping_per_s as f32),
    );
    let c = d.leaf.center_m;
    let rel = Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32) - hinge;
    let tag = Tag {
        entity: d.entity,
        class: EntityClass::Door,
        part: Part::Door,
        index: 0,
    };
    let collider = physics.colliders.insert_with_parent(
        cuboid(&d.leaf)
            .position(Pose::from_parts(
                rel,
                Quat::from_rotation_z(d.leaf.yaw_deg.to_radians() as f32),
            ))
            .mass(d.mass_kg as f32)
            .friction(friction)
            .collision_groups(groups(G_DOOR, G_ROBOT))
            .user_data(tag.pack()),
        body,
        &mut physics.bodies,
    );
    let mut joint = RevoluteJointBuilder::new(Vec3::new(0.0, 0.0, sign as f32))
        .local_anchor1(hinge)
        .local_anchor2(Vec3::ZERO)
        .contacts_enabled(false)
        .limits([d.min_deg.to_radians() as f32, d.max_deg.to_radians() as f32]);
    if d.hinge_friction_nm > 0.0 {
        joint = joint
            .motor_velocity(0.0, 1000.0)
            .motor_max_force(d.hinge_friction_nm as f32);
    }
    let joint = physics.impulse_joints.insert(ground, body, joint, true);
    DoorBody {
        entity: d.entity,
        wall: d.wall,
        body,
        collider,
        joint: Some(joint),
        sign,
        break_force_n: d.break_force_n,
        initial_deg: d.initial_deg,
    }
}

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

/// References for entity ids (unknown ids are skipped).
pub(crate) fn entity_refs(world: &World, ids: &[u32]) -> Vec<EntityRef> {
    ids.iter()
        .filter_map(|id| world.entity(*id))
        .map(EntityRef::from)
        .collect()
}
