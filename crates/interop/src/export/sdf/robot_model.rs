//! The robot in SDF: a model with the chassis link, wheel links on continuous joints and the
//! arm's links on revolute joints (see the parent module's docs).

use super::elements::{box_geometry, box_shape, friction, inertial, joint, material, pose, Axis};
use crate::export::parts::cylinder_inertia;
use crate::export::robot::{arm_axis, cleats, link_inertia, RobotLayout};
use crate::export::xml::{num, Xml};
use cloud::EntityClass;
use sim::BoxSpec;

/// The robot's model: chassis, wheels on continuous joints, the arm on revolute joints.
pub(super) fn robot_model(x: &mut Xml, r: &RobotLayout) {
    let m = r.model;
    x.comment(&format!("robot (entity {}): model {}", r.entity, m.name));
    x.open("model", &[("name", r.name.clone())]);
    pose(x, r.position_m, [0.0, 0.0, r.yaw_rad], None);
    x.open("link", &[("name", "chassis".into())]);
    inertial(
        x,
        m.chassis.com_offset_m,
        [0.0; 3],
        m.chassis.mass_kg,
        r.chassis_inertia(),
    );
    let chassis = BoxSpec {
        center_m: [0.0; 3],
        half_extents_m: r.chassis_half_m(),
        yaw_deg: 0.0,
    };
    box_shape(x, "chassis", &chassis, EntityClass::Robot, Some(0.5));
    x.close();
    let top_speed = |radius: f64| m.drive.max_speed_mps / radius;
    for (i, w) in m.wheels.iter().enumerate() {
        let name = format!("wheel_{i}");
        x.open("link", &[("name", name.clone())]);
        pose(x, w.position_m, [0.0; 3], None);
        let (axial, across) = cylinder_inertia(w.mass_kg, w.radius_m, w.width_m);
        inertial(x, [0.0; 3], [0.0; 3], w.mass_kg, [across, axial, across]);
        let along_y = [std::f64::consts::FRAC_PI_2, 0.0, 0.0];
        for kind in ["collision", "visual"] {
            x.open(kind, &[("name", format!("{name}_{kind}"))]);
            pose(x, [0.0; 3], along_y, None);
            x.open("geometry", &[]);
            x.open("cylinder", &[]);
            x.text("radius", &[], &num(w.radius_m));
            x.text("length", &[], &num(w.width_m));
            x.close();
            x.close();
            if kind == "collision" {
                friction(x, m.drive.wheel_friction);
            } else {
                material(x, EntityClass::Robot);
            }
            x.close();
        }
        for (k, c) in cleats(w).iter().enumerate() {
            let cleat = format!("{name}_cleat_{k}");
            x.open("collision", &[("name", format!("{cleat}_collision"))]);
            pose(x, c.center_m, [0.0, c.pitch_rad, 0.0], None);
            box_geometry(x, c.half_m);
            friction(x, m.drive.wheel_friction);
            x.close();
        }
        x.close();
        let axis = Axis {
            xyz: [0.0, 1.0, 0.0],
            limits: None,
            effort: if w.driven {
                m.drive.max_wheel_torque_nm
            } else {
                0.0
            },
            velocity: top_speed(w.radius_m),
            damping: 0.0,
            friction: 0.0,
        };
        joint(
            x,
            &format!("{name}_axle"),
            "continuous",
            "chassis",
            &name,
            &axis,
        );
    }
    if let Some(arm) = &m.arm {
        let mut parent = "chassis".to_string();
        let mut at = arm.mount_m;
        for (i, l) in arm.links.iter().enumerate() {
            let name = arm_link(r, i);
            x.open("link", &[("name", name.clone())]);
            pose(x, at, [0.0; 3], Some(&parent));
            let half = [l.length_m / 2.0, l.thickness_m / 2.0, l.thickness_m / 2.0];
            inertial(
                x,
                [half[0], 0.0, 0.0],
                [0.0; 3],
                l.mass_kg,
                link_inertia(l.mass_kg, l.length_m, l.thickness_m),
            );
            let bar = BoxSpec {
                center_m: [half[0], 0.0, 0.0],
                half_extents_m: half,
                yaw_deg: 0.0,
            };
            box_shape(x, &name, &bar, EntityClass::Robot, Some(0.5));
            x.close();
            let axis = Axis {
                xyz: arm_axis(l.axis),
                limits: Some((l.min_deg.to_radians(), l.max_deg.to_radians())),
                effort: l.max_torque_nm,
                velocity: -1.0,
                damping: 0.0,
                friction: 0.0,
            };
            joint(
                x,
                &format!("{name}_joint"),
                "revolute",
                &parent,
                &name,
                &axis,
            );
            parent = name;
            at = [l.length_m, 0.0, 0.0];
        }
    }
    x.close();
}

/// Arm link `i`'s link name in the robot model (`arm_shoulder`).
pub(super) fn arm_link(r: &RobotLayout, i: usize) -> String {
    r.link_name(i)
        .strip_prefix(&format!("{}_", r.name))
        .map(str::to_string)
        .unwrap_or_else(|| format!("arm_{i}"))
}
