//! SDF elements the writers share: poses, materials, box shapes with friction, inertials and
//! joints with their axis, limits and dynamics.

use crate::export::parts::srgb;
use crate::export::xml::{num, nums, Xml};
use cloud::EntityClass;
use sim::BoxSpec;

/// A pose `x y z roll pitch yaw`.
pub(super) fn pose(x: &mut Xml, t: [f64; 3], rpy: [f64; 3], relative_to: Option<&str>) {
    let attrs: Vec<(&str, String)> = relative_to
        .map(|r| vec![("relative_to", r.to_string())])
        .unwrap_or_default();
    x.text(
        "pose",
        &attrs,
        &nums(&[t[0], t[1], t[2], rpy[0], rpy[1], rpy[2]]),
    );
}

pub(super) fn material(x: &mut Xml, class: EntityClass) {
    let c = srgb(class).map(|v| (v * 1e4).round() / 1e4);
    let rgba = nums(&[c[0], c[1], c[2], 1.0]);
    x.open("material", &[]);
    x.text("ambient", &[], &rgba);
    x.text("diffuse", &[], &rgba);
    x.close();
}

pub(super) fn box_geometry(x: &mut Xml, half: [f64; 3]) {
    x.open("geometry", &[]);
    x.open("box", &[]);
    x.text("size", &[], &nums(&half.map(|h| 2.0 * h)));
    x.close();
    x.close();
}

pub(super) fn friction(x: &mut Xml, mu: f64) {
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
pub(super) fn box_shape(x: &mut Xml, name: &str, b: &BoxSpec, class: EntityClass, mu: Option<f64>) {
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

pub(super) fn inertial(x: &mut Xml, t: [f64; 3], rpy: [f64; 3], mass_kg: f64, i: [f64; 3]) {
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
pub(super) struct Axis {
    pub xyz: [f64; 3],
    pub limits: Option<(f64, f64)>,
    pub effort: f64,
    pub velocity: f64,
    pub damping: f64,
    pub friction: f64,
}

pub(super) fn joint(x: &mut Xml, name: &str, kind: &str, parent: &str, child: &str, ax: &Axis) {
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
