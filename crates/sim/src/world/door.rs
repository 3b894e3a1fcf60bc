//! Door leaves on revolute joints (axis z through the hinge, limits, damping, hinge friction).

use super::cuboid;
use super::tags::{groups, Part, Tag, G_DOOR, G_ROBOT};
use crate::spec::DoorSpec;
use cloud::EntityClass;
use glam::{Quat, Vec3};
use rapier3d::prelude::{
    ColliderHandle, ImpulseJointHandle, PhysicsWorld, Pose, RevoluteJointBuilder, RigidBodyBuilder,
    RigidBodyHandle,
};
use serde::{Deserialize, Serialize};

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
