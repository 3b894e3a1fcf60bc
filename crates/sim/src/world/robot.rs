//! A robot in the world: its rapier bodies and joints built from a [`RobotModel`] (chassis,
//! wheels on velocity motors, arm links on position servos), skid-steering and its pose.

use super::tags::{groups, Part, Tag, G_DOOR, G_ROBOT, G_SENSOR, G_STATIC};
use crate::error::Result;
use crate::model::{ArmAxis, DriveModel, RobotModel, StartPose, WheelModel};
use cloud::EntityClass;
use glam::{Quat, Vec3};
use rapier3d::prelude::{
    CoefficientCombineRule, ColliderBuilder, ColliderHandle, ImpulseJointHandle, JointAxis,
    MassProperties, MotorModel, PhysicsWorld, Pose, RevoluteJointBuilder, RigidBodyBuilder,
    RigidBodyHandle, SharedShape,
};
use serde::{Deserialize, Serialize};

/// A wheel in the world.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(crate) struct WheelBody {
    pub body: RigidBodyHandle,
    pub collider: ColliderHandle,
    pub joint: ImpulseJointHandle,
    pub radius_m: f64,
    pub y_m: f64,
    pub driven: bool,
}

/// An arm link and the joint at its base.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(crate) struct ArmLinkBody {
    pub name: String,
    pub body: RigidBodyHandle,
    pub collider: ColliderHandle,
    pub joint: Option<ImpulseJointHandle>,
    pub break_force_n: Option<f64>,
    pub break_torque_nm: Option<f64>,
}

/// A robot in the world.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(crate) struct Robot {
    pub entity: u32,
    pub chassis: RigidBodyHandle,
    pub chassis_collider: ColliderHandle,
    pub wheels: Vec<WheelBody>,
    pub arm: Vec<ArmLinkBody>,
    pub drive: DriveModel,
    /// The last (v, w) sent to the motors.
    pub command: (f64, f64),
}

/// Arm joint position servo: stiffness and damping (force-based).
const ARM_STIFFNESS_NM_PER_RAD: f32 = 1.0e5;
const ARM_DAMPING_NMS_PER_RAD: f32 = 100.0;

/// The motors' velocity gain (a stiff velocity constraint, limited by the torque).
const MOTOR_GAIN: f32 = 1000.0;

impl Robot {
    pub(crate) fn spawn(
        physics: &mut PhysicsWorld,
        model: &RobotModel,
        start: &StartPose,
        entity: u32,
    ) -> Result<Robot> {
        let tag = |part: Part, index: usize| {
            Tag {
                entity,
                class: EntityClass::Robot,
                part,
                index: index as u16,
            }
            .pack()
        };
        let robot_groups = groups(G_ROBOT, G_STATIC | G_DOOR | G_SENSOR);
        let yaw = start.yaw_deg.to_radians() as f32;
        let rot = Quat::from_rotation_z(yaw);
        let z = start.z_m + model.chassis_height_m() + 0.002;
        let pose = Pose::from_parts(Vec3::new(start.x_m as f32, start.y_m as f32, z as f32), rot);
        let chassis = physics
            .bodies
            .insert(RigidBodyBuilder::dynamic().pose(pose).can_sleep(false));
        let c = &model.chassis;
        let half = v3(c.size_m) * 0.5;
        let box_mp = MassProperties::from_cuboid(1.0, half);
        let mp = MassProperties::new(
            v3(c.com_offset_m),
            c.mass_kg as f32,
            box_mp.principal_inertia() * (c.mass_kg as f32 / box_mp.mass()),
        );
        let chassis_collider = physics.colliders.insert_with_parent(
            ColliderBuilder::cuboid(half.x, half.y, half.z)
                .mass_properties(mp)
                .friction(0.5)
                .collision_groups(robot_groups)
                .user_data(tag(Part::Chassis, 0)),
            chassis,
            &mut physics.bodies,
        );
        let d = &model.drive;
        let mut wheels = vec![];
        for (i, w) in model.wheels.iter().enumerate() {
            let offset = v3(w.position_m);
            let body = physics.bodies.insert(
                RigidBodyBuilder::dynamic()
                    .pose(Pose::from_parts(pose.transform_point(offset), rot))
                    .can_sleep(false),
            );
            let collider = physics.colliders.insert_with_parent(
                wheel_shape(w)
                    .mass(w.mass_kg as f32)
                    .friction(d.wheel_friction as f32)
                    .friction_combine_rule(CoefficientCombineRule::Max)
                    .collision_groups(robot_groups)
                    .user_data(tag(Part::Wheel, i)),
                body,
                &mut physics.bodies,
            );
            let max_torque = if w.driven {
                d.max_wheel_torque_nm as f32
            } else {
                0.0
            };
            let joint = RevoluteJointBuilder::new(Vec3::Y)
                .local_anchor1(offset)
                .local_anchor2(Vec3::ZERO)
                .contacts_enabled(false)
                .motor_velocity(0.0, MOTOR_GAIN)
                .motor_max_force(max_torque);
            let joint = physics.impulse_joints.insert(chassis, body, joint, true);
            wheels.push(WheelBody {
                body,
                collider,
                joint,
                radius_m: w.radius_m,
                y_m: w.position_m[1],
                driven: w.driven,
            });
        }
        let mut arm = vec![];
        if let Some(a) = &model.arm {
            let mut parent = chassis;
            let mut parent_pose = pose;
            let mut anchor = v3(a.mount_m);
            for (i, l) in a.links.iter().enumerate() {
                let axis = match l.axis {
                    ArmAxis::Yaw => Vec3::Z,
                    ArmAxis::Pitch => -Vec3::Y,
                };
                let angle = l.angle_deg.to_radians() as f32;
                let link_pose = Pose::from_parts(
                    parent_pose.transform_point(anchor),
                    parent_pose.rotation * Quat::from_axis_angle(axis, angle),
                );
                let body = physics
                    .bodies
                    .insert(RigidBodyBuilder::dynamic().pose(link_pose).can_sleep(false));
                let len = l.length_m as f32;
                let t = l.thickness_m as f32 / 2.0;
                let collider = physics.colliders.insert_with_parent(
                    ColliderBuilder::cuboid(len / 2.0, t, t)
                        .position(Pose::from_translation(Vec3::new(len / 2.0, 0.0, 0.0)))
                        .mass(l.mass_kg as f32)
                        .collision_groups(robot_groups)
                        .user_data(tag(Part::ArmLink, i)),
                    body,
                    &mut physics.bodies,
                );
                let joint = RevoluteJointBuilder::new(axis)
                    .local_anchor1(anchor)
                    .local_anchor2(Vec3::ZERO)
                    .contacts_enabled(false)
                    .limits([l.min_deg.to_radians() as f32, l.max_deg.to_radians() as f32])
                    .motor_model(MotorModel::ForceBased)
                    .motor_position(angle, ARM_STIFFNESS_NM_PER_RAD, ARM_DAMPING_NMS_PER_RAD)
                    .motor_max_force(l.max_torque_nm as f32);
                let joint = physics.impulse_joints.insert(parent, body, joint, true);
                arm.push(ArmLinkBody {
                    name: l.name.clone(),
                    body,
                    collider,
                    joint: Some(joint),
                    break_force_n: l.break_force_n,
                    break_torque_nm: l.break_torque_nm,
                });
                parent = body;
                parent_pose = link_pose;
                anchor = Vec3::new(len, 0.0, 0.0);
            }
        }
        Ok(Robot {
            entity,
            chassis,
            chassis_collider,
            wheels,
            arm,
            drive: d.clone(),
            command: (0.0, 0.0),
        })
    }

    /// Every collider of the robot with its part.
    pub(crate) fn colliders(&self) -> impl Iterator<Item = ColliderHandle> + '_ {
        std::iter::once(self.chassis_collider)
            .chain(self.wheels.iter().map(|w| w.collider))
            .chain(self.arm.iter().map(|a| a.collider))
    }

    /// Sets the wheel motors for a linear speed `v` (m/s) and yaw rate `w` (rad/s), clamped to
    /// the drive's limits; skid steering: wheel speed = v - w * y * skid_factor.
    pub(crate) fn drive(&mut self, physics: &mut PhysicsWorld, v: f64, w: f64) {
        let v = v.clamp(-self.drive.max_speed_mps, self.drive.max_speed_mps);
        let w = w.clamp(
            -self.drive.max_yaw_rate_radps,
            self.drive.max_yaw_rate_radps,
        );
        if (v, w) == self.command {
            return;
        }
        self.command = (v, w);
        for wheel in self.wheels.iter().filter(|w| w.driven) {
            let speed = v - w * wheel.y_m * self.drive.skid_factor;
            let target = (speed / wheel.radius_m) as f32;
            if let Some(j) = physics.impulse_joints.get_mut(wheel.joint, true) {
                j.data
                    .set_motor_velocity(JointAxis::AngX, target, MOTOR_GAIN);
            }
        }
    }
}

fn v3(a: [f64; 3]) -> Vec3 {
    Vec3::new(a[0] as f32, a[1] as f32, a[2] as f32)
}

/// A robot's pose and speed, from its chassis.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Default)]
pub struct RobotPose {
    /// Chassis centre x (m).
    pub x_m: f64,
    /// Chassis centre y (m).
    pub y_m: f64,
    /// Chassis centre z (m).
    pub z_m: f64,
    /// Roll (degrees, left side up positive).
    pub roll_deg: f64,
    /// Pitch (degrees, nose up positive).
    pub pitch_deg: f64,
    /// Heading (degrees, 0 = +x, counter-clockwise positive).
    pub yaw_deg: f64,
    /// Speed over ground in the chassis' heading (m/s, negative backwards).
    pub speed_mps: f64,
    /// Horizontal speed (m/s).
    pub ground_speed_mps: f64,
    /// Yaw rate (rad/s).
    pub yaw_rate_radps: f64,
}

pub(crate) fn robot_pose(physics: &PhysicsWorld, robot: &Robot) -> RobotPose {
    let Some(b) = physics.bodies.get(robot.chassis) else {
        return RobotPose::default();
    };
    let t = b.translation();
    let r = b.rotation();
    let x = r * Vec3::X;
    let y = r * Vec3::Y;
    let z = r * Vec3::Z;
    let v = b.linvel();
    let heading = Vec3::new(x.x, x.y, 0.0).normalize_or_zero();
    RobotPose {
        x_m: t.x as f64,
        y_m: t.y as f64,
        z_m: t.z as f64,
        roll_deg: (y.z as f64).atan2(z.z as f64).to_degrees(),
        pitch_deg: (x.z as f64).clamp(-1.0, 1.0).asin().to_degrees(),
        yaw_deg: (x.y as f64).atan2(x.x as f64).to_degrees(),
        speed_mps: v.dot(heading) as f64,
        ground_speed_mps: (v.x as f64).hypot(v.y as f64),
        yaw_rate_radps: b.angvel().z as f64,
    }
}

/// A wheel's collider shape: a cylinder along y, with cleats if the model has them.
fn wheel_shape(w: &WheelModel) -> ColliderBuilder {
    let (r, half_w) = (w.radius_m as f32, w.width_m as f32 / 2.0);
    if w.cleats == 0 || w.cleat_height_m <= 0.0 {
        return ColliderBuilder::cylinder(half_w, r);
    }
    let h = w.cleat_height_m as f32;
    let sink = 0.01_f32.min(r / 4.0);
    let thick = (std::f32::consts::TAU * r / w.cleats as f32 * 0.25).min(0.03);
    let mut parts = vec![(Pose::IDENTITY, SharedShape::cylinder(half_w, r))];
    for i in 0..w.cleats {
        let a = std::f32::consts::TAU * i as f32 / w.cleats as f32;
        let c = r + h / 2.0 - sink / 2.0;
        parts.push((
            Pose::from_parts(
                Vec3::new(c * a.cos(), 0.0, c * a.sin()),
                Quat::from_rotation_y(-a),
            ),
            SharedShape::cuboid((h + sink) / 2.0, half_w, thick / 2.0),
        ));
    }
    ColliderBuilder::compound(parts)
}
