//! The robot in MJCF: a free body for the chassis, wheel bodies on hinges with velocity
//! actuators, the arm's chain of bodies on hinges with position servos (see the parent
//! module's docs for the gains).

use super::{a, yaw_attr};
use crate::export::robot::{arm_axis, cleats, link_inertia, RobotLayout};
use crate::export::xml::{num, nums, Xml};

/// The wheel speed error (rad/s) at which a velocity actuator reaches its force limit: sim's
/// motors are stiffer, but at MuJoCo's 1/60 s step stiffer motors make six-wheel robots hop.
const MOTOR_SATURATION_RADPS: f64 = 2.0;
/// The arm angle error (rad) at which a position servo reaches its force limit.
const SERVO_SATURATION_RAD: f64 = 0.05;
/// Friction of the chassis box (as sim's).
const CHASSIS_FRICTION: f64 = 0.5;

/// The robot's bodies: the free chassis, its wheels and its arm chain.
pub(super) fn robot_body(x: &mut Xml, r: &RobotLayout) {
    let m = r.model;
    x.comment(&format!("robot (entity {}): model {}", r.entity, m.name));
    let mut body = vec![a("name", r.chassis_name()), a("pos", nums(&r.position_m))];
    yaw_attr(&mut body, r.yaw_rad);
    x.open("body", &body);
    x.empty("freejoint", &[a("name", format!("{}_free", r.name))]);
    x.empty(
        "inertial",
        &[
            a("pos", nums(&m.chassis.com_offset_m)),
            a("mass", num(m.chassis.mass_kg)),
            a("diaginertia", nums(&r.chassis_inertia())),
        ],
    );
    x.empty(
        "geom",
        &[
            a("name", r.chassis_name()),
            a("class", "robot"),
            a("type", "box"),
            a("material", "robot"),
            a("size", nums(&r.chassis_half_m())),
            a("friction", nums(&[CHASSIS_FRICTION, 0.005, 0.0001])),
        ],
    );
    for (i, w) in m.wheels.iter().enumerate() {
        let name = r.wheel_name(i);
        x.open(
            "body",
            &[a("name", name.clone()), a("pos", nums(&w.position_m))],
        );
        x.empty(
            "joint",
            &[
                a("name", format!("{name}_axle")),
                a("type", "hinge"),
                a("axis", "0 1 0"),
            ],
        );
        x.empty(
            "geom",
            &[
                a("name", name.clone()),
                a("class", "robot"),
                a("type", "cylinder"),
                a("material", "robot"),
                a("size", nums(&[w.radius_m, w.width_m / 2.0])),
                a("euler", nums(&[std::f64::consts::FRAC_PI_2, 0.0, 0.0])),
                a("mass", num(w.mass_kg)),
                a("friction", nums(&[m.drive.wheel_friction, 0.005, 0.0001])),
            ],
        );
        for (k, c) in cleats(w).iter().enumerate() {
            x.empty(
                "geom",
                &[
                    a("name", format!("{name}_cleat_{k}")),
                    a("class", "robot"),
                    a("type", "box"),
                    a("material", "robot"),
                    a("pos", nums(&c.center_m)),
                    a("euler", nums(&[0.0, c.pitch_rad, 0.0])),
                    a("size", nums(&c.half_m)),
                    a("mass", "0"),
                    a("friction", nums(&[m.drive.wheel_friction, 0.005, 0.0001])),
                ],
            );
        }
        x.close();
    }
    if let Some(arm) = &m.arm {
        let mut pos = arm.mount_m;
        for (i, l) in arm.links.iter().enumerate() {
            let name = r.link_name(i);
            let axis = arm_axis(l.axis);
            let angle = l.angle_deg.to_radians();
            let mut body = vec![a("name", name.clone()), a("pos", nums(&pos))];
            if angle != 0.0 {
                body.push(a("axisangle", nums(&[axis[0], axis[1], axis[2], angle])));
            }
            x.open("body", &body);
            x.empty(
                "joint",
                &[
                    a("name", format!("{name}_joint")),
                    a("type", "hinge"),
                    a("axis", nums(&axis)),
                    a(
                        "range",
                        nums(&[l.min_deg.to_radians(), l.max_deg.to_radians()]),
                    ),
                    a("ref", num(angle)),
                ],
            );
            let half = [l.length_m / 2.0, l.thickness_m / 2.0, l.thickness_m / 2.0];
            x.empty(
                "inertial",
                &[
                    a("pos", nums(&[half[0], 0.0, 0.0])),
                    a("mass", num(l.mass_kg)),
                    a(
                        "diaginertia",
                        nums(&link_inertia(l.mass_kg, l.length_m, l.thickness_m)),
                    ),
                ],
            );
            x.empty(
                "geom",
                &[
                    a("name", name),
                    a("class", "robot"),
                    a("type", "box"),
                    a("material", "robot"),
                    a("pos", nums(&[half[0], 0.0, 0.0])),
                    a("size", nums(&half)),
                ],
            );
            pos = [l.length_m, 0.0, 0.0];
        }
        for _ in &arm.links {
            x.close();
        }
    }
    x.close();
}

/// The robot's actuators; returns the `ctrl` of the start keyframe (wheels still, the arm
/// at its angles).
pub(super) fn actuators(x: &mut Xml, r: &RobotLayout) -> Vec<f64> {
    let m = r.model;
    let mut ctrl = vec![];
    x.open("actuator", &[]);
    let torque = m.drive.max_wheel_torque_nm;
    for (i, w) in m.wheels.iter().enumerate() {
        if !w.driven {
            continue;
        }
        let name = r.wheel_name(i);
        let top = m.drive.max_speed_mps / w.radius_m;
        x.empty(
            "velocity",
            &[
                a("name", format!("{name}_motor")),
                a("joint", format!("{name}_axle")),
                a("kv", num(torque / MOTOR_SATURATION_RADPS)),
                a("forcerange", nums(&[-torque, torque])),
                a("ctrlrange", nums(&[-top, top])),
            ],
        );
        ctrl.push(0.0);
    }
    if let Some(arm) = &m.arm {
        for (i, l) in arm.links.iter().enumerate() {
            if l.max_torque_nm <= 0.0 {
                continue;
            }
            let name = r.link_name(i);
            x.empty(
                "position",
                &[
                    a("name", format!("{name}_servo")),
                    a("joint", format!("{name}_joint")),
                    a("kp", num(l.max_torque_nm / SERVO_SATURATION_RAD)),
                    a("dampratio", "1"),
                    a("forcerange", nums(&[-l.max_torque_nm, l.max_torque_nm])),
                    a(
                        "ctrlrange",
                        nums(&[l.min_deg.to_radians(), l.max_deg.to_radians()]),
                    ),
                ],
            );
            ctrl.push(l.angle_deg.to_radians());
        }
    }
    x.close();
    ctrl
}
