//! From URDF links and joints to a [`RobotModel`]: the chassis and the links fixed to it, the
//! wheels on `continuous` joints, the arm's chain of `revolute` joints, and the drive (the
//! rules are in the parent module's docs).

use super::{Frame, Geometry, Joint, JointKind, Link, Shape, Urdf};
use crate::model::{
    ArmAxis, ArmModel, ChassisModel, DriveModel, LinkModel, RobotModel, WheelModel,
};
use glam::DVec3;
use std::collections::{HashMap, HashSet};

/// Top speed when no driven wheel has a `<limit velocity>` (m/s).
const DEFAULT_MAX_SPEED_MPS: f64 = 1.0;
/// Wheel motor torque when no driven wheel has a `<limit effort>` (N m).
const DEFAULT_WHEEL_TORQUE_NM: f64 = 5.0;
/// Tyre friction without a Gazebo `<mu1>`.
const DEFAULT_WHEEL_FRICTION: f64 = 1.0;
/// How far from exact a direction, offset or rotation may be (unit vectors, metres, radians).
const TOLERANCE: f64 = 1e-6;

/// The links and joints of a URDF as a tree.
struct Tree<'a> {
    links: HashMap<&'a str, &'a Link>,
    /// Each link's frame relative to the root (joints at zero).
    frames: HashMap<&'a str, Frame>,
    /// The joints by parent link.
    below: HashMap<&'a str, Vec<&'a Joint>>,
    root: &'a str,
}

fn tree(u: &Urdf) -> Result<Tree<'_>, String> {
    let mut links = HashMap::new();
    for l in &u.links {
        if links.insert(l.name.as_str(), l).is_some() {
            return Err(format!("two links named {:?}", l.name));
        }
    }
    let mut parent_of: HashMap<&str, &Joint> = HashMap::new();
    let mut below: HashMap<&str, Vec<&Joint>> = HashMap::new();
    for j in &u.joints {
        for l in [&j.parent, &j.child] {
            if !links.contains_key(l.as_str()) {
                return Err(joint_msg(
                    j,
                    format!("names link {l:?}, which does not exist"),
                ));
            }
        }
        if parent_of.insert(j.child.as_str(), j).is_some() {
            return Err(joint_msg(j, format!("link {:?} has two parents", j.child)));
        }
        below.entry(j.parent.as_str()).or_default().push(j);
    }
    let roots: Vec<&str> = u
        .links
        .iter()
        .map(|l| l.name.as_str())
        .filter(|n| !parent_of.contains_key(n))
        .collect();
    let root = match roots.as_slice() {
        [one] => *one,
        [] if u.links.is_empty() => return Err("no <link> elements".into()),
        [] => return Err("the joints form a cycle: no link is the root".into()),
        more => return Err(format!("more than one root link: {}", more.join(", "))),
    };
    let mut frames = HashMap::from([(root, Frame::IDENTITY)]);
    let mut todo = vec![root];
    while let Some(l) = todo.pop() {
        for j in below.get(l).map(|v| v.as_slice()).unwrap_or(&[]) {
            let f = frames[l].then(&j.origin);
            frames.insert(j.child.as_str(), f);
            todo.push(j.child.as_str());
        }
    }
    if let Some(l) = u
        .links
        .iter()
        .find(|l| !frames.contains_key(l.name.as_str()))
    {
        return Err(format!(
            "link {:?} is not connected to the root {root:?} (a cycle?)",
            l.name
        ));
    }
    Ok(Tree {
        links,
        frames,
        below,
        root,
    })
}

fn joint_msg(j: &Joint, msg: impl std::fmt::Display) -> String {
    format!("line {}: joint {:?}: {msg}", j.line, j.name)
}

/// Links reached from `start` through fixed joints only (downwards), `start` first.
fn fixed_group<'a>(t: &Tree<'a>, start: &'a str) -> Vec<&'a str> {
    let mut group = vec![start];
    let mut i = 0;
    while i < group.len() {
        for j in t.below.get(group[i]).map(|v| v.as_slice()).unwrap_or(&[]) {
            if j.kind == JointKind::Fixed {
                group.push(j.child.as_str());
            }
        }
        i += 1;
    }
    group
}

/// The total mass of links and their mass-weighted centre in `base`'s coordinates.
fn mass_of(t: &Tree, group: &[&str], base: &Frame) -> (f64, DVec3) {
    let to_base = base.inverse();
    let (mut m, mut mc) = (0.0, DVec3::ZERO);
    for l in group {
        if let Some((o, mass)) = &t.links[l].inertial {
            m += mass;
            mc += *mass * to_base.then(&t.frames[l]).then(o).t;
        }
    }
    (m, if m > 0.0 { mc / m } else { DVec3::ZERO })
}

fn first_shape(l: &Link, want: fn(&Geometry) -> bool) -> Option<&Shape> {
    l.shapes.iter().find(|s| want(&s.geometry))
}

fn is_box(g: &Geometry) -> bool {
    matches!(g, Geometry::Box(_))
}

fn is_cylinder(g: &Geometry) -> bool {
    matches!(g, Geometry::Cylinder { .. })
}

fn shape_names(l: &Link) -> String {
    let names: Vec<&str> = l
        .shapes
        .iter()
        .map(|s| match &s.geometry {
            Geometry::Box(_) => "box",
            Geometry::Cylinder { .. } => "cylinder",
            Geometry::Other(n) => n.as_str(),
        })
        .collect();
    if names.is_empty() {
        "no geometry".into()
    } else {
        format!("only {}", names.join(", "))
    }
}

fn parallel(a: DVec3, b: DVec3) -> bool {
    a.dot(b).abs() >= 1.0 - TOLERANCE
}

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

/// The arm's chain of revolute joints, from its first joint.
fn arm(
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
