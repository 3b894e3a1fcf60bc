//! Robots from URDF files: [`RobotModel::from_urdf_str`] reads the XML (with `roxmltree`)
//! into links and joints, and [`map`] turns them into a [`RobotModel`].
//!
//! The rules (also in the crate README):
//!
//! * **Chassis**: the root link (the one that is no joint's child), or, when it has no box
//!   geometry (e.g. ROS's `base_footprint`), the link reached from it through a chain of single
//!   `fixed` joints that has one. Its first box (collision, else visual) is the chassis box; its
//!   centre and axes are the model's frame (x forward, y left, z up). The chassis mass is the
//!   `<inertial><mass>` of the chassis and of every link joined to it by `fixed` joints (their
//!   geometry is ignored: sensors, plates); the centre of mass is their mass-weighted average.
//! * **Wheels**: `continuous` joints from the chassis whose child link has a cylinder (collision,
//!   else visual). Position = the cylinder's centre, radius and width (`length`) from the
//!   cylinder, mass from the link's inertial. The cylinder and the joint axis must both lie
//!   along the chassis' y (semsim's motors turn every wheel about +y, forward). A wheel whose
//!   `<limit effort="0">` is free-rolling; every other wheel is driven.
//! * **Arm**: at most one chain of `revolute` joints from the chassis, each joint at the end of
//!   the previous link (`origin xyz="L 0 0"`, no rotation), axis `0 0 1` (yaw) or `0 -1 0`
//!   (pitch; `0 1 0` is pitch with the limits mirrored). Each link is its first box, lying along
//!   its x from the joint (`origin xyz="L/2 0 0"`): length = the box's x, thickness = the larger
//!   of its y and z. Limits give `min_deg`/`max_deg`, `effort` the motor torque; the held angle
//!   is 0 clamped into the limits; URDF has no break limits (none).
//! * **Drive**: top speed = the smallest `<limit velocity>` x radius of the driven wheels
//!   (default 1 m/s), wheel torque = their smallest `<limit effort>` (default 5 N m), tyre
//!   friction = the largest Gazebo `<gazebo reference="WHEEL"><mu1>` (default 1.0). The yaw rate
//!   and skid factor come from an optional `<semsim><drive max_yaw_rate_radps=".."
//!   skid_factor=".."/></semsim>` element (ROS tools ignore unknown elements); defaults: top
//!   speed / half the track, and 1.0.
//! * Refused, with an error naming the file and the joint or link: `prismatic`, `floating` and
//!   `planar` joints, a wheel joint whose link has no cylinder (e.g. a mesh), a second arm or an
//!   arm that branches, any other moving joint that is neither a wheel nor on the arm, links or
//!   joints that do not form one tree, and (when checked as a model) fewer than two wheels.

mod arm;
mod map;
mod tree;

use crate::error::{read_text, Result, SimError};
use crate::model::RobotModel;
use glam::{DQuat, DVec3, EulerRot};
use roxmltree::{Document, Node};
use std::collections::HashMap;
use std::path::Path;

/// A rigid transform: `child = t + r * local`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Frame {
    pub t: DVec3,
    pub r: DQuat,
}

impl Frame {
    pub(crate) const IDENTITY: Frame = Frame {
        t: DVec3::ZERO,
        r: DQuat::IDENTITY,
    };

    /// `self` followed by `local` (a frame given in `self`'s coordinates).
    pub(crate) fn then(&self, local: &Frame) -> Frame {
        Frame {
            t: self.t + self.r * local.t,
            r: (self.r * local.r).normalize(),
        }
    }

    /// The inverse transform.
    pub(crate) fn inverse(&self) -> Frame {
        let r = self.r.inverse();
        Frame {
            t: -(r * self.t),
            r,
        }
    }
}

/// A link's shape.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Geometry {
    /// Full sizes x, y, z.
    Box([f64; 3]),
    /// Along the shape frame's z.
    Cylinder { radius_m: f64, length_m: f64 },
    /// Anything else (sphere, mesh, capsule): named for error messages.
    Other(String),
}

/// One collision (or visual) element of a link.
#[derive(Debug, Clone)]
pub(crate) struct Shape {
    pub origin: Frame,
    pub geometry: Geometry,
}

/// A URDF link.
#[derive(Debug, Clone)]
pub(crate) struct Link {
    pub name: String,
    /// `<inertial>`: its origin (the centre of mass) and mass.
    pub inertial: Option<(Frame, f64)>,
    /// The collision shapes, or the visual ones when the link has no collision.
    pub shapes: Vec<Shape>,
}

/// A URDF joint type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum JointKind {
    Revolute,
    Continuous,
    Prismatic,
    Fixed,
    Floating,
    Planar,
}

/// A joint's `<limit>`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Limit {
    pub lower: f64,
    pub upper: f64,
    pub effort: f64,
    pub velocity: f64,
}

/// A URDF joint.
#[derive(Debug, Clone)]
pub(crate) struct Joint {
    pub name: String,
    pub kind: JointKind,
    /// The child link's frame in the parent link's frame (at joint position zero).
    pub origin: Frame,
    pub parent: String,
    pub child: String,
    /// Unit axis in the joint (= child link) frame.
    pub axis: DVec3,
    pub limit: Option<Limit>,
    /// 1-based line of the `<joint>` element.
    pub line: u32,
}

/// The optional `<semsim><drive .../></semsim>` extension.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct DriveExtension {
    pub max_yaw_rate_radps: Option<f64>,
    pub skid_factor: Option<f64>,
}

/// A parsed URDF robot.
#[derive(Debug, Clone)]
pub(crate) struct Urdf {
    pub name: String,
    pub links: Vec<Link>,
    pub joints: Vec<Joint>,
    /// Gazebo `<mu1>` by link name.
    pub mu1: HashMap<String, f64>,
    pub drive: DriveExtension,
}

impl RobotModel {
    /// Reads a URDF file (see the crate README for how links and joints become a model).
    pub fn load_urdf(path: &Path) -> Result<RobotModel> {
        RobotModel::from_urdf_str(&read_text(path)?, path)
    }

    /// Maps a URDF robot description to a validated model; `path` names it in errors.
    pub fn from_urdf_str(text: &str, path: &Path) -> Result<RobotModel> {
        let err = |msg: String| SimError::Urdf {
            path: path.to_path_buf(),
            msg,
        };
        let urdf = parse(text).map_err(err)?;
        let model = map::to_model(&urdf).map_err(err)?;
        model
            .validate()
            .map_err(|e| e.in_source(&path.display().to_string()))?;
        Ok(model)
    }
}

/// `line N: <element name="..">: msg`.
fn at(node: Node, msg: impl std::fmt::Display) -> String {
    let pos = node.document().text_pos_at(node.range().start);
    let tag = node.tag_name().name();
    match node.attribute("name") {
        Some(name) => format!("line {}: <{tag} name=\"{name}\">: {msg}", pos.row),
        None => format!("line {}: <{tag}>: {msg}", pos.row),
    }
}

/// The element children of `node` named `name`.
fn children<'a, 'i>(node: Node<'a, 'i>, name: &'a str) -> impl Iterator<Item = Node<'a, 'i>> {
    node.children()
        .filter(move |c| c.is_element() && c.tag_name().name() == name)
}

fn child<'a, 'i>(node: Node<'a, 'i>, name: &'a str) -> Option<Node<'a, 'i>> {
    children(node, name).next()
}

fn required<'a>(node: Node<'a, '_>, attr: &str) -> Result<&'a str, String> {
    node.attribute(attr)
        .ok_or_else(|| at(node, format!("missing attribute {attr}")))
}

/// Space-separated finite numbers (exactly `n`).
fn numbers(node: Node, attr: &str, text: &str, n: usize) -> Result<Vec<f64>, String> {
    let bad = || {
        at(
            node,
            format!("{attr}=\"{text}\" is not {n} finite number(s)"),
        )
    };
    let v: Vec<f64> = text
        .split_whitespace()
        .map(|s| s.parse::<f64>().map_err(|_| bad()))
        .collect::<Result<_, _>>()?;
    if v.len() != n || v.iter().any(|x| !x.is_finite()) {
        return Err(bad());
    }
    Ok(v)
}

fn number(node: Node, attr: &str) -> Result<Option<f64>, String> {
    node.attribute(attr)
        .map(|t| numbers(node, attr, t, 1).map(|v| v[0]))
        .transpose()
}

fn vec3(node: Node, attr: &str, default: DVec3) -> Result<DVec3, String> {
    match node.attribute(attr) {
        None => Ok(default),
        Some(t) => numbers(node, attr, t, 3).map(|v| DVec3::new(v[0], v[1], v[2])),
    }
}

/// An `<origin xyz rpy>` child (identity when absent). `rpy` = roll about x, then pitch about
/// y, then yaw about z, all about fixed axes.
fn origin(node: Node) -> Result<Frame, String> {
    let Some(o) = child(node, "origin") else {
        return Ok(Frame::IDENTITY);
    };
    let t = vec3(o, "xyz", DVec3::ZERO)?;
    let rpy = vec3(o, "rpy", DVec3::ZERO)?;
    Ok(Frame {
        t,
        r: DQuat::from_euler(EulerRot::ZYX, rpy.z, rpy.y, rpy.x),
    })
}

fn geometry(node: Node) -> Result<Geometry, String> {
    let g = child(node, "geometry").ok_or_else(|| at(node, "no <geometry>"))?;
    let Some(shape) = g.children().find(|c| c.is_element()) else {
        return Err(at(g, "empty geometry"));
    };
    let positive = |attr: &str| -> Result<f64, String> {
        match number(shape, attr)? {
            Some(v) if v > 0.0 => Ok(v),
            Some(v) => Err(at(shape, format!("{attr} = {v} must be positive"))),
            None => Err(at(shape, format!("missing attribute {attr}"))),
        }
    };
    match shape.tag_name().name() {
        "box" => {
            let s = numbers(shape, "size", required(shape, "size")?, 3)?;
            if s.iter().any(|v| *v <= 0.0) {
                return Err(at(shape, "box sizes must be positive"));
            }
            Ok(Geometry::Box([s[0], s[1], s[2]]))
        }
        "cylinder" => Ok(Geometry::Cylinder {
            radius_m: positive("radius")?,
            length_m: positive("length")?,
        }),
        other => Ok(Geometry::Other(other.to_string())),
    }
}

fn link(node: Node) -> Result<Link, String> {
    let name = required(node, "name")?.to_string();
    let inertial = match child(node, "inertial") {
        None => None,
        Some(i) => {
            let m = child(i, "mass").ok_or_else(|| at(i, "no <mass>"))?;
            let mass = number(m, "value")?.ok_or_else(|| at(m, "missing attribute value"))?;
            if mass < 0.0 {
                return Err(at(m, format!("negative mass {mass}")));
            }
            Some((origin(i)?, mass))
        }
    };
    let read = |kind: &str| -> Result<Vec<Shape>, String> {
        children(node, kind)
            .map(|c| {
                Ok(Shape {
                    origin: origin(c)?,
                    geometry: geometry(c)?,
                })
            })
            .collect()
    };
    let mut shapes = read("collision")?;
    if shapes.is_empty() {
        shapes = read("visual")?;
    }
    Ok(Link {
        name,
        inertial,
        shapes,
    })
}

fn joint(node: Node) -> Result<Joint, String> {
    let name = required(node, "name")?.to_string();
    let kind = match required(node, "type")? {
        "revolute" => JointKind::Revolute,
        "continuous" => JointKind::Continuous,
        "prismatic" => JointKind::Prismatic,
        "fixed" => JointKind::Fixed,
        "floating" => JointKind::Floating,
        "planar" => JointKind::Planar,
        other => return Err(at(node, format!("unknown joint type {other:?}"))),
    };
    let link_of = |tag: &str| -> Result<String, String> {
        let e = child(node, tag).ok_or_else(|| at(node, format!("no <{tag}>")))?;
        Ok(required(e, "link")?.to_string())
    };
    let axis = match child(node, "axis") {
        None => DVec3::X,
        Some(a) => {
            let v = vec3(a, "xyz", DVec3::X)?;
            v.try_normalize()
                .ok_or_else(|| at(a, "the axis has zero length"))?
        }
    };
    let limit = match child(node, "limit") {
        None if kind == JointKind::Revolute => {
            return Err(at(node, "a revolute joint needs a <limit>"))
        }
        None => None,
        Some(l) => Some(Limit {
            lower: number(l, "lower")?.unwrap_or(0.0),
            upper: number(l, "upper")?.unwrap_or(0.0),
            effort: number(l, "effort")?.unwrap_or(0.0),
            velocity: number(l, "velocity")?.unwrap_or(0.0),
        }),
    };
    Ok(Joint {
        name,
        kind,
        origin: origin(node)?,
        parent: link_of("parent")?,
        child: link_of("child")?,
        axis,
        limit,
        line: node.document().text_pos_at(node.range().start).row,
    })
}

/// Parses the XML into links and joints (no mapping yet).
pub(crate) fn parse(text: &str) -> Result<Urdf, String> {
    let doc = Document::parse(text).map_err(|e| format!("not well-formed XML: {e}"))?;
    let robot = doc.root_element();
    if robot.tag_name().name() != "robot" {
        return Err(at(
            robot,
            "the root element must be <robot> (not a URDF file?)",
        ));
    }
    let links = children(robot, "link")
        .map(link)
        .collect::<Result<Vec<_>, _>>()?;
    let joints = children(robot, "joint")
        .map(joint)
        .collect::<Result<Vec<_>, _>>()?;
    let mut mu1 = HashMap::new();
    for g in children(robot, "gazebo") {
        if let (Some(link), Some(m)) = (g.attribute("reference"), child(g, "mu1")) {
            let text = m.text().unwrap_or("").trim();
            let v = numbers(m, "mu1", text, 1)?[0];
            mu1.insert(link.to_string(), v);
        }
    }
    let mut drive = DriveExtension::default();
    if let Some(d) = child(robot, "semsim").and_then(|s| child(s, "drive")) {
        drive.max_yaw_rate_radps = number(d, "max_yaw_rate_radps")?;
        drive.skid_factor = number(d, "skid_factor")?;
    }
    Ok(Urdf {
        name: robot.attribute("name").unwrap_or("urdf robot").to_string(),
        links,
        joints,
        mu1,
        drive,
    })
}
