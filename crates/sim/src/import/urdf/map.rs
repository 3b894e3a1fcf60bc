//! From URDF links and joints to a [`RobotModel`]: the chassis and the links fixed to it, the
//! wheels on `continuous` joints, the arm's chain of `revolute` joints, and the drive (the
//! rules are in the parent module's docs).

use super::arm::arm;
use super::tree::{
    first_shape, fixed_group, is_box, is_cylinder, joint_msg, mass_of, parallel, shape_names, tree,
    Tree,
};
use super::{Frame, Geometry, Joint, JointKind, Urdf};
use crate::model::{ChassisModel, DriveModel, RobotModel, WheelModel};
use glam::DVec3;
use std::collections::HashSet;

/// Top speed when no driven wheel has a `<limit velocity>` (m/s).
const DEFAULT_MAX_SPEED_MPS: f64 = 1.0;
/// Wheel motor torque when no driven wheel has a `<limit effort>` (N m).
const DEFAULT_WHEEL_TORQUE_NM: f64 = 5.0;
/// Tyre friction without a Gazebo `<mu1>`.
const DEFAULT_WHEEL_FRICTION: f64 = 1.0;

/// Maps the URDF to a model (validated by the caller).
pub(super) fn to_model(u: &Urdf) -> Result<RobotModel, String> {
    if let Some(j) = u.joints.iter().find(|j| {
        matches!(
            j.kind,
            JointKind::Prismatic | JointKind::Floating | JointKind::Planar
        )
    }) {
        return Err(joint_msg(
            j,
            format!(
                "{:?} joints cannot be mapped to a semsim robot (wheels are continuous joints, \
                 arm joints revolute, fixed joints merge)",
                j.kind
            )
            .to_lowercase(),
        ));
    }
    let t = tree(u)?;
    // The chassis: the root, or down single fixed joints to the first link with a box.
    let mut chassis = t.root;
    let chassis_box = loop {
        let l = t.links[chassis];
        if let Some(s) = first_shape(l, is_box) {
            break s;
        }
        let fixed: Vec<&Joint> = t
            .below
            .get(chassis)
            .map(|v| {
                v.iter()
                    .copied()
                    .filter(|j| j.kind == JointKind::Fixed)
                    .collect()
            })
            .unwrap_or_default();
        match fixed.as_slice() {
            [one] => chassis = one.child.as_str(),
            _ => {
                return Err(format!(
                    "link {chassis:?}: no box geometry for the chassis ({}), and no single fixed \
                     child link to take it from",
                    shape_names(l)
                ))
            }
        }
    };
    let Geometry::Box(size_m) = chassis_box.geometry else {
        return Err("internal: the chassis shape is not a box".into());
    };
    let base = t.frames[chassis].then(&chassis_box.origin);
    let to_base = base.inverse();
    // Everything fixed to the root (above the chassis) is part of the chassis too.
    let group = fixed_group(&t, t.root);
    let members: HashSet<&str> = group.iter().copied().collect();
    let (mass_kg, com) = mass_of(&t, &group, &base);
    if mass_kg <= 0.0 {
        return Err(format!(
            "link {chassis:?}: the chassis (and the links fixed to it) has no <inertial><mass>"
        ));
    }
    let mut wheels = vec![];
    let mut wheel_joints = vec![];
    let mut arm_base: Option<&Joint> = None;
    for l in &group {
        for j in t.below.get(l).map(|v| v.as_slice()).unwrap_or(&[]) {
            if members.contains(j.child.as_str()) {
                continue;
            }
            match j.kind {
                JointKind::Continuous => {
                    wheels.push(wheel(&t, j, &to_base)?);
                    wheel_joints.push(*j);
                }
                JointKind::Revolute => {
                    if let Some(first) = arm_base {
                        return Err(joint_msg(
                            j,
                            format!(
                                "a second arm on the chassis (joint {:?} starts one already); \
                                 semsim robots have at most one",
                                first.name
                            ),
                        ));
                    }
                    arm_base = Some(j);
                }
                _ => {}
            }
        }
    }
    if wheels.is_empty() {
        return Err(format!(
            "no wheels: semsim robots drive on wheels, continuous joints from the chassis link \
             {chassis:?} to links with a cylinder"
        ));
    }
    let mut used: HashSet<String> = wheel_joints.iter().map(|j| j.name.clone()).collect();
    let arm = match arm_base {
        Some(j) => Some(arm(&t, j, &to_base, &mut used)?),
        None => None,
    };
    // Every moving joint must be a wheel or on the arm.
    if let Some(j) = u
        .joints
        .iter()
        .find(|j| j.kind != JointKind::Fixed && !used.contains(&j.name))
    {
        return Err(joint_msg(
            j,
            "moves a part that is neither a wheel on the chassis nor on the arm's chain",
        ));
    }
    let drive = drive(u, &wheels, &wheel_joints);
    Ok(RobotModel {
        name: u.name.clone(),
        description: format!("from URDF robot {:?}", u.name),
        chassis: ChassisModel {
            size_m,
            mass_kg,
            com_offset_m: com.to_array(),
        },
        wheels,
        drive,
        arm,
    })
}

/// A wheel from its continuous joint.
fn wheel(t: &Tree, j: &Joint, to_base: &Frame) -> Result<WheelModel, String> {
    let l = t.links[j.child.as_str()];
    let Some(s) = first_shape(l, is_cylinder) else {
        return Err(joint_msg(
            j,
            format!(
                "wheel link {:?} has {}: semsim wheels are cylinders",
                l.name,
                shape_names(l)
            ),
        ));
    };
    let Geometry::Cylinder { radius_m, length_m } = s.geometry else {
        return Err("internal: the wheel shape is not a cylinder".into());
    };
    let joint_frame = to_base.then(&t.frames[j.child.as_str()]);
    let cylinder = joint_frame.then(&s.origin);
    if !parallel(cylinder.r * DVec3::Z, DVec3::Y) {
        return Err(joint_msg(
            j,
            format!(
                "the cylinder of wheel link {:?} does not lie along the chassis' y axis",
                l.name
            ),
        ));
    }
    if !parallel(joint_frame.r * j.axis, DVec3::Y) {
        return Err(joint_msg(
            j,
            "the wheel's axis is not the chassis' y axis (semsim wheels turn about y)",
        ));
    }
    let (mass_kg, _) = mass_of(t, &fixed_group(t, &l.name), to_base);
    if mass_kg <= 0.0 {
        return Err(joint_msg(
            j,
            format!("wheel link {:?} has no <inertial><mass>", l.name),
        ));
    }
    Ok(WheelModel {
        position_m: cylinder.t.to_array(),
        radius_m,
        width_m: length_m,
        mass_kg,
        driven: j.limit.is_none_or(|l| l.effort != 0.0),
        cleats: 0,
        cleat_height_m: 0.0,
    })
}

/// The drive from the wheel joints' limits, Gazebo's `<mu1>` and the `<semsim>` extension.
fn drive(u: &Urdf, wheels: &[WheelModel], joints: &[&Joint]) -> DriveModel {
    let driven: Vec<(&WheelModel, &Joint)> = wheels
        .iter()
        .zip(joints.iter().copied())
        .filter(|(w, _)| w.driven)
        .collect();
    let min_of = |values: Vec<f64>, default: f64| {
        values
            .into_iter()
            .filter(|v| *v > 0.0)
            .reduce(f64::min)
            .unwrap_or(default)
    };
    let max_speed_mps = min_of(
        driven
            .iter()
            .filter_map(|(w, j)| j.limit.map(|l| l.velocity * w.radius_m))
            .collect(),
        DEFAULT_MAX_SPEED_MPS,
    );
    let max_wheel_torque_nm = min_of(
        driven
            .iter()
            .filter_map(|(_, j)| j.limit.map(|l| l.effort))
            .collect(),
        DEFAULT_WHEEL_TORQUE_NM,
    );
    let wheel_friction = joints
        .iter()
        .filter_map(|j| u.mu1.get(&j.child).copied())
        .reduce(f64::max)
        .unwrap_or(DEFAULT_WHEEL_FRICTION);
    let half_track = driven
        .iter()
        .map(|(w, _)| w.position_m[1].abs())
        .fold(0.0, f64::max);
    let max_yaw_rate_radps = u.drive.max_yaw_rate_radps.unwrap_or(if half_track > 0.0 {
        max_speed_mps / half_track
    } else {
        1.0
    });
    DriveModel {
        max_speed_mps,
        max_yaw_rate_radps,
        max_wheel_torque_nm,
        wheel_friction,
        skid_factor: u.drive.skid_factor.unwrap_or(1.0),
    }
}
