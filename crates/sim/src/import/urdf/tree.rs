//! A URDF's links and joints as a tree: each link's frame (joints at zero), the joints below
//! each link, the links held together by fixed joints and their mass, and the shape queries
//! the mapping needs.

use super::{Frame, Geometry, Joint, JointKind, Link, Shape, Urdf};
use glam::DVec3;
use std::collections::HashMap;

/// How far from exact a direction, offset or rotation may be (unit vectors, metres, radians).
pub(super) const TOLERANCE: f64 = 1e-6;

/// The links and joints of a URDF as a tree.
pub(super) struct Tree<'a> {
    pub links: HashMap<&'a str, &'a Link>,
    /// Each link's frame relative to the root (joints at zero).
    pub frames: HashMap<&'a str, Frame>,
    /// The joints by parent link.
    pub below: HashMap<&'a str, Vec<&'a Joint>>,
    pub root: &'a str,
}

pub(super) fn tree(u: &Urdf) -> Result<Tree<'_>, String> {
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

pub(super) fn joint_msg(j: &Joint, msg: impl std::fmt::Display) -> String {
    format!("line {}: joint {:?}: {msg}", j.line, j.name)
}

/// Links reached from `start` through fixed joints only (downwards), `start` first.
pub(super) fn fixed_group<'a>(t: &Tree<'a>, start: &'a str) -> Vec<&'a str> {
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
pub(super) fn mass_of(t: &Tree, group: &[&str], base: &Frame) -> (f64, DVec3) {
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

pub(super) fn first_shape(l: &Link, want: fn(&Geometry) -> bool) -> Option<&Shape> {
    l.shapes.iter().find(|s| want(&s.geometry))
}

pub(super) fn is_box(g: &Geometry) -> bool {
    matches!(g, Geometry::Box(_))
}

pub(super) fn is_cylinder(g: &Geometry) -> bool {
    matches!(g, Geometry::Cylinder { .. })
}

pub(super) fn shape_names(l: &Link) -> String {
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

pub(super) fn parallel(a: DVec3, b: DVec3) -> bool {
    a.dot(b).abs() >= 1.0 - TOLERANCE
}
