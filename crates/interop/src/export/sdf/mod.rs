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

mod elements;
mod robot_model;

use super::parts::{
    box_inertia, by_entity, element_name, hinge_damping_nms, hinge_point, leaf_offset, physics,
    static_boxes,
};
use super::robot::RobotLayout;
use super::xml::{num, nums, Xml};
use cloud::EntityClass;
use elements::{box_shape, inertial, joint, pose, Axis};
use robot_model::{arm_link, robot_model};
use sim::{BoxSpec, WorldSpec};

/// The world's name (also in its `<state>`).
const WORLD: &str = "semsim";

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
