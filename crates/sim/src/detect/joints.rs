//! Breakable joints (rapier has none): after each step the force on each breakable joint is
//! estimated from the impulses of its last solver substep (force = impulse / substep dt), and a
//! joint over its limit is removed and reported. Door hinges break on the linear hinge force;
//! arm joints on the linear force or on the bending torque (the locked angular axes plus the
//! limit; the motor slips at its own torque limit instead of breaking).

use crate::events::{Emitter, EventKind};
use crate::world::tags::{groups, G_DOOR, G_ROBOT, G_STATIC};
use crate::world::{entity_refs, World};
use rapier3d::prelude::{ImpulseJoint, ImpulseJointHandle, PhysicsWorld};

/// Linear force (N) and bending torque (N m) on a revolute joint during its last substep.
pub(crate) fn joint_load(joint: &ImpulseJoint, substep_dt: f64) -> (f64, f64) {
    let i = joint.impulses;
    let f = (i[0] as f64).hypot(i[1] as f64).hypot(i[2] as f64) / substep_dt;
    let limit = joint.data.limits[3].impulse.abs() as f64;
    let t = ((i[4] as f64).hypot(i[5] as f64) + limit) / substep_dt;
    (f, t)
}

fn load(physics: &PhysicsWorld, h: ImpulseJointHandle, substep_dt: f64) -> Option<(f64, f64)> {
    physics
        .impulse_joints
        .get(h)
        .map(|j| joint_load(j, substep_dt))
}

/// Checks every breakable joint after a step; removes and reports the broken ones.
pub(crate) fn break_overloaded(world: &mut World, out: &mut Emitter) {
    let substep_dt = world.config.dt_secs / world.config.solver_iterations.max(1) as f64;
    let mut broken_doors = vec![];
    for (k, door) in world.doors.iter().enumerate() {
        let (Some(h), Some(limit)) = (door.joint, door.break_force_n) else {
            continue;
        };
        if let Some((f, _)) = load(&world.physics, h, substep_dt) {
            if f > limit {
                broken_doors.push((k, h, f, limit));
            }
        }
    }
    for (k, h, f, limit) in broken_doors {
        world.physics.impulse_joints.remove(h, true);
        let door = &mut world.doors[k];
        door.joint = None;
        let (body, collider, entity, wall) = (door.body, door.collider, door.entity, door.wall);
        // A loose leaf falls onto the floor and against walls.
        if let Some(c) = world.physics.colliders.get_mut(collider) {
            c.set_collision_groups(groups(G_DOOR, G_ROBOT | G_STATIC));
        }
        if let Some(b) = world.physics.bodies.get_mut(body) {
            b.wake_up(true);
        }
        // The robots touching it right now are named too.
        let mut ids = vec![entity, wall];
        for r in &world.robots {
            let touching = r.colliders().any(|c| {
                world
                    .physics
                    .narrow_phase
                    .contact_pair(c, collider)
                    .is_some_and(|p| p.has_any_active_contact())
            });
            if touching {
                ids.insert(0, r.entity);
            }
        }
        out.emit(
            EventKind::JointBroken,
            entity_refs(world, &ids),
            "door hinge",
            &[("force_n", f), ("break_force_n", limit)],
        );
    }
    let mut broken_arm = vec![];
    for (ri, robot) in world.robots.iter().enumerate() {
        for (li, link) in robot.arm.iter().enumerate() {
            let Some(h) = link.joint else { continue };
            let Some((f, t)) = load(&world.physics, h, substep_dt) else {
                continue;
            };
            let over_f = link.break_force_n.is_some_and(|l| f > l);
            let over_t = link.break_torque_nm.is_some_and(|l| t > l);
            if over_f || over_t {
                broken_arm.push((ri, li, h, f, t));
            }
        }
    }
    for (ri, li, h, f, t) in broken_arm {
        world.physics.impulse_joints.remove(h, true);
        let robot = &mut world.robots[ri];
        let link = &mut robot.arm[li];
        link.joint = None;
        let detail = format!("arm joint {li} ({})", link.name);
        let entity = robot.entity;
        out.emit(
            EventKind::JointBroken,
            entity_refs(world, &[entity]),
            &detail,
            &[("force_n", f), ("torque_nm", t), ("link", li as f64)],
        );
    }
}
