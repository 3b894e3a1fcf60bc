//! The arm: a chain of revolute joints from the chassis, each at the end of the previous
//! link, each link a box along its x (the rules are in the parent module's docs).

use super::tree::{
    first_shape, fixed_group, is_box, joint_msg, mass_of, shape_names, Tree, TOLERANCE,
};
use super::{Frame, Geometry, Joint, JointKind};
use crate::model::{ArmAxis, ArmModel, LinkModel};
use glam::DVec3;
use std::collections::HashSet;

/// The arm's chain of revolute joints, from its first joint.
pub(super) fn arm(
    t: &Tree,
    first: &Joint,
    to_base: &Frame,
    used: &mut HashSet<String>,
) -> Result<ArmModel, String> {
    let mount = to_base
        .then(&t.frames[first.parent.as_str()])
        .then(&first.origin);
    if mount.r.angle_between(glam::DQuat::IDENTITY) > TOLERANCE {
        return Err(joint_msg(
            first,
            "the arm's first joint is rotated relative to the chassis (use rpy=\"0 0 0\")",
        ));
    }
    let mut links = vec![];
    let mut joint = first;
    loop {
        used.insert(joint.name.clone());
        let l = t.links[joint.child.as_str()];
        let (axis, mirror) = if parallel_same(joint.axis, DVec3::Z) {
            (ArmAxis::Yaw, false)
        } else if parallel_same(joint.axis, -DVec3::Y) {
            (ArmAxis::Pitch, false)
        } else if parallel_same(joint.axis, DVec3::Y) {
            (ArmAxis::Pitch, true)
        } else {
            return Err(joint_msg(
                joint,
                "arm joints turn about z (yaw) or y (pitch) of the previous link",
            ));
        };
        let Some(limit) = joint.limit else {
            return Err(joint_msg(joint, "a revolute joint needs a <limit>"));
        };
        let (mut lo, mut hi) = (limit.lower.to_degrees(), limit.upper.to_degrees());
        if mirror {
            (lo, hi) = (-hi, -lo);
        }
        let Some(s) = first_shape(l, is_box) else {
            return Err(joint_msg(
                joint,
                format!(
                    "arm link {:?} has {}: semsim arm links are boxes",
                    l.name,
                    shape_names(l)
                ),
            ));
        };
        let Geometry::Box(size) = s.geometry else {
            return Err("internal: the arm link shape is not a box".into());
        };
        let along = DVec3::new(size[0] / 2.0, 0.0, 0.0);
        if (s.origin.t - along).length() > TOLERANCE
            || s.origin.r.angle_between(glam::DQuat::IDENTITY) > TOLERANCE
        {
            return Err(format!(
                "link {:?}: an arm link's box lies along its x from the joint (origin \
                 xyz=\"{} 0 0\", no rotation)",
                l.name, along.x
            ));
        }
        let (mass_kg, _) = mass_of(t, &fixed_group(t, &l.name), to_base);
        links.push(LinkModel {
            name: l.name.clone(),
            axis,
            length_m: size[0],
            thickness_m: size[1].max(size[2]),
            mass_kg,
            angle_deg: 0.0_f64.clamp(lo.min(hi), hi.max(lo)),
            min_deg: lo,
            max_deg: hi,
            max_torque_nm: limit.effort,
            break_force_n: None,
            break_torque_nm: None,
        });
        let next: Vec<&Joint> = fixed_group(t, &l.name)
            .iter()
            .flat_map(|g| t.below.get(g).map(|v| v.as_slice()).unwrap_or(&[]))
            .copied()
            .filter(|j| j.kind != JointKind::Fixed)
            .collect();
        match next.as_slice() {
            [] => break,
            [j] if j.kind == JointKind::Revolute && j.parent == l.name => {
                let end = DVec3::new(size[0], 0.0, 0.0);
                if (j.origin.t - end).length() > TOLERANCE
                    || j.origin.r.angle_between(glam::DQuat::IDENTITY) > TOLERANCE
                {
                    return Err(joint_msg(
                        j,
                        format!(
                            "an arm joint sits at the end of the previous link (origin \
                             xyz=\"{} 0 0\", no rotation)",
                            size[0]
                        ),
                    ));
                }
                joint = j;
            }
            [j] => {
                return Err(joint_msg(
                    j,
                    "on the arm: only a chain of revolute joints, each on the previous link, \
                     is supported",
                ))
            }
            [_, j, ..] => {
                return Err(joint_msg(
                    j,
                    format!("the arm branches at link {:?}", l.name),
                ))
            }
        }
    }
    Ok(ArmModel {
        mount_m: mount.t.to_array(),
        links,
    })
}

fn parallel_same(a: DVec3, b: DVec3) -> bool {
    a.dot(b) >= 1.0 - TOLERANCE
}
