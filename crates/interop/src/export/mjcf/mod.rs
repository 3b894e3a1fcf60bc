//! MuJoCo MJCF: the world and the robot as MuJoCo loads them, with sim's semantics.
//!
//! * Angles in radians (`<compiler angle="radian" autolimits="true">`), time step 1/60 s,
//!   gravity and friction as sim's defaults, the `implicitfast` integrator (stable with the
//!   stiff velocity and position servos).
//! * Static boxes are geoms of the world body named `<class>_<id>` (`wall_12`; `wall_12_0`,
//!   `wall_12_1` for an entity of several boxes; `stairs_30_step_0`, `stairs_30_landing`).
//! * Each door is a body `door_<id>` at its hinge point with a hinge joint `door_<id>_hinge`
//!   about z (the axis points along +z for doors opening counter-clockwise, -z for clockwise,
//!   so that the joint angle is the opening angle, as in sim), `range` = the door's limits,
//!   `ref` = its initial angle (`qpos0`, so the model starts with the door as open as in sim),
//!   `damping` = sim's angular damping x the leaf's moment of inertia about the hinge,
//!   `frictionloss` = the hinge friction; the leaf geom `door_<id>_leaf` carries the mass.
//!   MuJoCo joints cannot break: break forces are kept as `<custom>` numerics.
//! * Door free spaces are box sites `free_space_for_door_<id>`.
//! * Contacts as sim's collision groups: static geoms (contype 1) and door leaves (2) touch
//!   only the robot (conaffinity 4), the robot (contype 4) touches both but not itself.
//! * The robot `robot_<id>`: a body with a free joint (the chassis box, its mass and centre
//!   of mass), wheel bodies (cylinders, with cleats as massless boxes) on hinge joints about y with `<velocity>` actuators (`ctrl` =
//!   wheel speed in rad/s; `kv` = the motor torque / 2 rad/s, force limited to the torque;
//!   free-rolling wheels get none), arm links on hinge joints with `<position>` servos
//!   (critically damped, `kp` = the link's torque / 0.05 rad, force limited to the torque).
//!   The keyframe `start` holds the arm at its angles: reset to it (`mj_resetDataKeyframe`).

mod robot_bodies;

use super::parts::{
    element_name, hinge_damping_nms, hinge_point, leaf_offset, physics, srgb, static_boxes,
};
use super::robot::RobotLayout;
use super::xml::{num, nums, Attr, Xml};
use cloud::EntityClass;
use robot_bodies::{actuators, robot_body};
use sim::{BoxSpec, WorldSpec};
use std::collections::BTreeSet;

/// Contact bits: static geometry, door leaves, robot parts.
const STATIC_BIT: u32 = 1;
const DOOR_BIT: u32 = 2;
const ROBOT_BIT: u32 = 4;

pub(super) fn a(name: &'static str, value: impl Into<String>) -> Attr<'static> {
    (name, value.into())
}

/// `euler="0 0 yaw"` for a rotation about z (none when zero).
pub(super) fn yaw_attr(attrs: &mut Vec<Attr>, yaw_rad: f64) {
    if yaw_rad != 0.0 {
        attrs.push(a("euler", nums(&[0.0, 0.0, yaw_rad])));
    }
}

fn box_attrs(b: &BoxSpec) -> Vec<Attr<'static>> {
    let mut attrs = vec![
        a("pos", nums(&b.center_m)),
        a("size", nums(&b.half_extents_m)),
    ];
    yaw_attr(&mut attrs, b.yaw_deg.to_radians());
    attrs
}

fn rgba(class: EntityClass, alpha: f64) -> String {
    let c = srgb(class).map(|v| (v * 1e4).round() / 1e4);
    nums(&[c[0], c[1], c[2], alpha])
}

/// The MJCF document of a (validated) world and robot.
pub(crate) fn write(spec: &WorldSpec, robot: Option<&RobotLayout>) -> String {
    let cfg = physics();
    let mut x = Xml::new();
    let model = if spec.name.is_empty() {
        "semsim world"
    } else {
        spec.name.as_str()
    };
    x.open("mujoco", &[a("model", model)]);
    x.comment(
        "Exported by semsim (interop): names are <class>_<entity id>; lengths in metres, angles \
         in radians, masses in kg; z up. Doors: hinge joints whose angle is the opening angle.",
    );
    x.empty("compiler", &[a("angle", "radian"), a("autolimits", "true")]);
    x.empty(
        "option",
        &[
            a("timestep", num(cfg.dt_secs)),
            a("gravity", nums(&[0.0, 0.0, -cfg.gravity_mps2])),
            a("integrator", "implicitfast"),
        ],
    );
    defaults(&mut x, cfg.static_friction);
    let boxes = static_boxes(spec);
    let mut classes: BTreeSet<EntityClass> = boxes.iter().map(|b| b.class).collect();
    if !spec.doors.is_empty() {
        classes.insert(EntityClass::Door);
    }
    if robot.is_some() {
        classes.insert(EntityClass::Robot);
    }
    x.open("asset", &[]);
    for c in &classes {
        x.empty("material", &[a("name", c.name()), a("rgba", rgba(*c, 1.0))]);
    }
    x.close();
    x.open("worldbody", &[]);
    let mut last_entity = None;
    for b in &boxes {
        if last_entity != Some(b.entity) {
            x.comment(&describe(b.entity_name, b.label));
            last_entity = Some(b.entity);
        }
        let mut attrs = vec![
            a("name", b.part.clone()),
            a("class", "static"),
            a("material", b.class.name()),
        ];
        attrs.extend(box_attrs(b.geometry));
        x.empty("geom", &attrs);
    }
    for d in &spec.doors {
        let name = element_name(EntityClass::Door, d.entity);
        x.comment(&describe(&d.name, &d.label));
        let sign = d.opens.sign();
        let mut body = vec![a("name", name.clone()), a("pos", nums(&hinge_point(d)))];
        yaw_attr(&mut body, (sign * d.initial_deg).to_radians());
        x.open("body", &body);
        x.empty(
            "joint",
            &[
                a("name", format!("{name}_hinge")),
                a("type", "hinge"),
                a("axis", nums(&[0.0, 0.0, sign])),
                a(
                    "range",
                    nums(&[d.min_deg.to_radians(), d.max_deg.to_radians()]),
                ),
                a("ref", num(d.initial_deg.to_radians())),
                a("damping", num(hinge_damping_nms(d))),
                a("frictionloss", num(d.hinge_friction_nm)),
            ],
        );
        let mut leaf = vec![
            a("name", format!("{name}_leaf")),
            a("class", "door"),
            a("material", "door"),
            a("pos", nums(&leaf_offset(d))),
            a("size", nums(&d.leaf.half_extents_m)),
            a("mass", num(d.mass_kg)),
        ];
        yaw_attr(&mut leaf, d.leaf.yaw_deg.to_radians());
        x.empty("geom", &leaf);
        x.close();
    }
    for f in &spec.free_spaces {
        let mut attrs = vec![
            a(
                "name",
                element_name(EntityClass::FreeSpaceForDoor, f.entity),
            ),
            a("class", "free_space"),
            a("rgba", rgba(EntityClass::FreeSpaceForDoor, 0.25)),
        ];
        attrs.extend(box_attrs(&f.geometry));
        x.empty("site", &attrs);
    }
    let mut start_ctrl = vec![];
    if let Some(r) = robot {
        robot_body(&mut x, r);
    }
    x.close();
    if let Some(r) = robot {
        start_ctrl = actuators(&mut x, r);
    }
    custom(&mut x, spec, robot);
    if !start_ctrl.is_empty() {
        x.open("keyframe", &[]);
        x.empty("key", &[a("name", "start"), a("ctrl", nums(&start_ctrl))]);
        x.close();
    }
    x.finish()
}

fn describe(name: &str, label: &str) -> String {
    if label.is_empty() {
        name.to_string()
    } else {
        format!("{name} ({label})")
    }
}

fn defaults(x: &mut Xml, friction: f64) {
    let bits = |t: u32, c: u32| [a("contype", t.to_string()), a("conaffinity", c.to_string())];
    x.open("default", &[]);
    x.empty("geom", &[a("friction", nums(&[friction, 0.005, 0.0001]))]);
    for (class, contype, affinity) in [
        ("static", STATIC_BIT, ROBOT_BIT),
        ("door", DOOR_BIT, ROBOT_BIT),
        ("robot", ROBOT_BIT, STATIC_BIT | DOOR_BIT),
    ] {
        x.open("default", &[a("class", class)]);
        let mut attrs = bits(contype, affinity).to_vec();
        if class != "robot" {
            attrs.insert(0, a("type", "box"));
        }
        x.empty("geom", &attrs);
        x.close();
    }
    x.open("default", &[a("class", "free_space")]);
    x.empty("site", &[a("type", "box"), a("group", "3")]);
    x.close();
    x.close();
}

/// What MuJoCo cannot model, kept as data: break forces (N) and torques (N m).
fn custom(x: &mut Xml, spec: &WorldSpec, robot: Option<&RobotLayout>) {
    let mut numerics: Vec<(String, f64)> = spec
        .doors
        .iter()
        .filter_map(|d| {
            d.break_force_n.map(|f| {
                let name = element_name(EntityClass::Door, d.entity);
                (format!("{name}_hinge_break_force_n"), f)
            })
        })
        .collect();
    if let Some(arm) = robot.and_then(|r| r.model.arm.as_ref().map(|arm| (r, arm))) {
        let (r, arm) = arm;
        for (i, l) in arm.links.iter().enumerate() {
            if let Some(f) = l.break_force_n {
                numerics.push((format!("{}_joint_break_force_n", r.link_name(i)), f));
            }
            if let Some(t) = l.break_torque_nm {
                numerics.push((format!("{}_joint_break_torque_nm", r.link_name(i)), t));
            }
        }
    }
    if numerics.is_empty() {
        return;
    }
    x.open("custom", &[]);
    for (name, v) in numerics {
        x.empty("numeric", &[a("name", name), a("data", num(v))]);
    }
    x.close();
}
