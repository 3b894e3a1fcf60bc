//! SDFormat 1.9 (Gazebo): the world and the robot, with sim's semantics.
//!
//! * One `<world name="semsim">` with sim's time step and gravity and a sun.
//! * A static model `building`: one link per entity named `<class>_<id>` (`wall_12`,
//!   `stairs_30`), with a box collision and visual per box (coloured by class); door free
//!   spaces as links with a translucent visual only (no collision).
//! * Each door a model `door_<id>` placed at its hinge point: a link `leaf` (the closed leaf,
//!   its mass and inertia) on a `revolute` joint `hinge` to the world about z (+z for doors
//!   opening counter-clockwise, -z for clockwise, so that the joint angle is the opening
//!   angle), `<limit lower upper>` = the door's limits in radians, `<dynamics>` damping = sim's
//!   angular damping x the leaf's moment of inertia about the hinge, friction = the hinge
//!   friction. Joint angle zero is the closed door; the initial opening is the world's
//!   `<state>` (a joint angle, as Gazebo saves and loads worlds).
//! * The robot a model `robot_<id>` at its start pose: link `chassis` (box, mass, centre of
//!   mass), links `wheel_<i>` (cylinders along y, cleats as boxes, the tyre friction as
//!   `mu`/`mu2`) on
//!   `continuous` joints `wheel_<i>_axle` about y (`<limit effort>` = the motor torque,
//!   `velocity` = the top speed over the radius; free-rolling wheels effort 0), and the arm's
//!   links `arm_<name>` on `revolute` joints `arm_<name>_joint` (limits, effort = torque); the
//!   arm's angles are in the `<state>` too. SDF has no actuators: a controller plugin drives
//!   the joints.

use super::parts::{
    box_inertia, by_entity, cylinder_inertia, element_name, hinge_damping_nms, hinge_point,
    leaf_offset, physics, srgb, static_boxes,
};
use super::robot::{arm_axis, cleats, link_inertia, RobotLayout};
use super::xml::{num, nums, Xml};
use cloud::EntityClass;
use sim::{BoxSpec, WorldSpec};

/// The world's name (also in its `<state>`).
const WORLD: &str = "semsim";

/// A pose `x y z roll pitch yaw`.
fn pose(x: &mut Xml, t: [f64; 3], rpy: [f64; 3], relative_to: Option<&str>) {
    let attrs: Vec<(&str, String)> = relative_to
        .map(|r| vec![("relative_to", r.to_string())])
        .unwrap_or_default();
    x.text(
        "pose",
        &attrs,
        &nums(&[t[0], t[1], t[2], rpy[0], rpy[1], rpy[2]]),
    );
}

fn material(x: &mut Xml, class: EntityClass) {
    let c = srgb(class).map(|v| (v * 1e4).round() / 1e4);
    let rgba = nums(&[c[0], c[1], c[2], 1.0]);
    x.open("material", &[]);
    x.text("ambient", &[], &rgba);
    x.text("diffuse", &[], &rgba);
    x.close();
}

fn box_geometry(x: &mut Xml, half: [f64; 3]) {
    x.open("geometry", &[]);
    x.open("box", &[]);
    x.text("size", &[], &nums(&half.map(|h| 2.0 * h)));
    x.close();
    x.close();
}

fn friction(x: &mut Xml, mu: f64) {
    x.open("surface", &[]);
    x.open("friction", &[]);
    x.open("ode", &[]);
    x.text("mu", &[], &num(mu));
    x.text("mu2", &[], &num(mu));
    x.close();
    x.close();
    x.close();
}

/// A box collision and visual named `<name>_collision` / `<name>_visual`.
fn box_shape(x: &mut Xml, name: &str, b: &BoxSpec, class: EntityClass, mu: Option<f64>) {
    let rpy = [0.0, 0.0, b.yaw_deg.to_radians()];
    if let Some(mu) = mu {
        x.open("collision", &[("name", format!("{name}_collision"))]);
        pose(x, b.center_m, rpy, None);
        box_geometry(x, b.half_extents_m);
        friction(x, mu);
        x.close();
    }
    x.open("visual", &[("name", format!("{name}_visual"))]);
    pose(x, b.center_m, rpy, None);
    box_geometry(x, b.half_extents_m);
    material(x, class);
    if mu.is_none() {
        x.text("transparency", &[], "0.75");
    }
    x.close();
}

fn inertial(x: &mut Xml, t: [f64; 3], rpy: [f64; 3], mass_kg: f64, i: [f64; 3]) {
    x.open("inertial", &[]);
    pose(x, t, rpy, None);
    x.text("mass", &[], &num(mass_kg));
    x.open("inertia", &[]);
    for (name, v) in [
        ("ixx", i[0]),
        ("ixy", 0.0),
        ("ixz", 0.0),
        ("iyy", i[1]),
        ("iyz", 0.0),
        ("izz", i[2]),
    ] {
        x.text(name, &[], &num(v));
    }
    x.close();
    x.close();
}

/// A joint's `<axis>`: direction, limits (radians; none = unlimited), effort and speed
/// limits (negative = none), dynamics.
struct Axis {
    xyz: [f64; 3],
    limits: Option<(f64, f64)>,
    effort: f64,
    velocity: f64,
    damping: f64,
    friction: f64,
}

fn joint(x: &mut Xml, name: &str, kind: &str, parent: &str, child: &str, ax: &Axis) {
    x.open(
        "joint",
        &[("name", name.to_string()), ("type", kind.to_string())],
    );
    x.text("parent", &[], parent);
    x.text("child", &[], child);
    x.open("axis", &[]);
    x.text("xyz", &[], &nums(&ax.xyz));
    x.open("limit", &[]);
    let (lo, hi) = ax.limits.unwrap_or((-1e16, 1e16));
    x.text("lower", &[], &num(lo));
    x.text("upper", &[], &num(hi));
    x.text("effort", &[], &num(ax.effort));
    x.text("velocity", &[], &num(ax.velocity));
    x.close();
    x.open("dynamics", &[]);
    x.text("damping", &[], &num(ax.damping));
    x.text("friction", &[], &num(ax.friction));
    x.close();
    x.close();
    x.close();
}

/// The SDF document of a (validated) world and robot.
pub(crate) fn write(spec: &WorldSpec, robot: Option<&RobotLayout>) -> String {
    let cfg = physics();
    let mut x = Xml::new();
    x.open("sdf", &[("version", "1.9".into())]);
    x.open("world", &[("name", WORLD.into())]);
    x.comment(&format!(
        "Exported by semsim (interop) from {:?}: names are <class>_<entity id>; metres, \
         radians, kg; z up. Door joint angle = opening angle (0 = closed).",
        spec.name
    ));
    x.open(
        "physics",
        &[("name", "semsim_step".into()), ("type", "ode".into())],
    );
    x.text("max_step_size", &[], &num(cfg.dt_secs));
    x.text("real_time_factor", &[], "1");
    x.close();
    x.text("gravity", &[], &nums(&[0.0, 0.0, -cfg.gravity_mps2]));
    x.open(
        "light",
        &[("name", "sun".into()), ("type", "directional".into())],
    );
    x.text("cast_shadows", &[], "true");
    pose(&mut x, [0.0, 0.0, 10.0], [0.0; 3], None);
    x.text("diffuse", &[], "0.8 0.8 0.8 1");
    x.text("direction", &[], "-0.5 0.1 -0.9");
    x.close();
    building(&mut x, spec, cfg.static_friction);
    for d in &spec.doors {
        let name = element_name(EntityClass::Door, d.entity);
        x.comment(&d.name);
        x.open("model", &[("name", name)]);
        pose(&mut x, hinge_point(d), [0.0; 3], None);
        x.open("link", &[("name", "leaf".into())]);
        let leaf = BoxSpec {
            center_m: leaf_offset(d),
            ..d.leaf
        };
        let rpy = [0.0, 0.0, d.leaf.yaw_deg.to_radians()];
        inertial(
            &mut x,
            leaf.center_m,
            rpy,
            d.mass_kg,
            box_inertia(d.mass_kg, d.leaf.half_extents_m),
        );
        box_shape(
            &mut x,
            "leaf",
            &leaf,
            EntityClass::Door,
            Some(cfg.static_friction),
        );
        x.close();
        let axis = Axis {
            xyz: [0.0, 0.0, d.opens.sign()],
            limits: Some((d.min_deg.to_radians(), d.max_deg.to_radians())),
            effort: -1.0,
            velocity: -1.0,
            damping: hinge_damping_nms(d),
            friction: d.hinge_friction_nm,
        };
        joint(&mut x, "hinge", "revolute", "world", "leaf", &axis);
        x.close();
    }
    if let Some(r) = robot {
        robot_model(&mut x, r);
    }
    state(&mut x, spec, robot);
    x.finish()
}

/// The static model: a link per entity, free spaces as visual-only links.
fn building(x: &mut Xml, spec: &WorldSpec, mu: f64) {
    x.open("model", &[("name", "building".into())]);
    x.text("static", &[], "true");
    let boxes = static_boxes(spec);
    for group in by_entity(&boxes) {
        let Some(first) = group.first() else {
            continue;
        };
        x.comment(first.entity_name);
        x.open("link", &[("name", element_name(first.class, first.entity))]);
        for b in &group {
            box_shape(x, &b.part, b.geometry, b.class, Some(mu));
        }
        x.close();
    }
    for f in &spec.free_spaces {
        let name = element_name(EntityClass::FreeSpaceForDoor, f.entity);
        x.open("link", &[("name", name.clone())]);
        box_shape(x, &name, &f.geometry, EntityClass::FreeSpaceForDoor, None);
        x.close();
    }
    x.close();
}

/// The robot's model: chassis, wheels on continuous joints, the arm on revolute joints.
fn robot_model(x: &mut Xml, r: &RobotLayout) {
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
fn arm_link(r: &RobotLayout, i: usize) -> String {
    r.link_name(i)
        .strip_prefix(&format!("{}_", r.name))
        .map(str::to_string)
        .unwrap_or_else(|| format!("arm_{i}"))
}

/// The initial joint angles: open doors and the arm's held angles.
fn state(x: &mut Xml, spec: &WorldSpec, robot: Option<&RobotLayout>) {
    let doors: Vec<_> = spec.doors.iter().filter(|d| d.initial_deg != 0.0).collect();
    let arm: Vec<(String, f64)> = robot
        .and_then(|r| r.model.arm.as_ref().map(|a| (r, a)))
        .map(|(r, a)| {
            a.links
                .iter()
                .enumerate()
                .filter(|(_, l)| l.angle_deg != 0.0)
                .map(|(i, l)| {
                    (
                        format!("{}_joint", arm_link(r, i)),
                        l.angle_deg.to_radians(),
                    )
                })
                .collect()
        })
        .unwrap_or_default();
    if doors.is_empty() && arm.is_empty() {
        return;
    }
    x.open("state", &[("world_name", WORLD.into())]);
    x.text("iterations", &[], "0");
    for d in doors {
        x.open(
            "model",
            &[("name", element_name(EntityClass::Door, d.entity))],
        );
        x.open("joint", &[("name", "hinge".into())]);
        x.text(
            "angle",
            &[("axis", "0".into())],
            &num(d.initial_deg.to_radians()),
        );
        x.close();
        x.close();
    }
    if let (Some(r), false) = (robot, arm.is_empty()) {
        x.open("model", &[("name", r.name.clone())]);
        for (joint, angle) in arm {
            x.open("joint", &[("name", joint)]);
            x.text("angle", &[("axis", "0".into())], &num(angle));
            x.close();
        }
        x.close();
    }
    x.close();
}
