//! A robot as the exports place it: where sim puts its chassis (start pose, the chassis
//! centre above the surface by [`sim::RobotModel::chassis_height_m`] + 2 mm), its entity id
//! (after the world's largest), its element names, and its parts' masses and inertias. The
//! MJCF and SDF writers turn this into bodies and joints the way sim builds rapier bodies:
//! chassis box with its centre of mass, wheels as cylinders with their axle along the
//! chassis' y, arm links as square bars along their x on joints about z (yaw) or -y (pitch).

use super::parts::{box_inertia, element_name};
use cloud::EntityClass;
use sim::{ArmAxis, RobotModel, StartPose, WheelModel, WorldSpec};

/// Where sim starts the chassis above the surface, besides the wheels' reach (m).
const START_CLEARANCE_M: f64 = 0.002;

/// The placed robot.
pub(crate) struct RobotLayout<'a> {
    /// The model.
    pub model: &'a RobotModel,
    /// Its entity id: the world's largest + 1, as sim gives it.
    pub entity: u32,
    /// `robot_<id>`: the prefix of its element names.
    pub name: String,
    /// The chassis centre in the world (m).
    pub position_m: [f64; 3],
    /// Its heading (radians about z).
    pub yaw_rad: f64,
}

impl<'a> RobotLayout<'a> {
    /// Places a (validated) model at a start pose in a world.
    pub(crate) fn new(model: &'a RobotModel, start: &StartPose, spec: &WorldSpec) -> Self {
        let entity = spec.entities().iter().map(|e| e.id).max().unwrap_or(0) + 1;
        RobotLayout {
            model,
            entity,
            name: element_name(EntityClass::Robot, entity),
            position_m: [
                start.x_m,
                start.y_m,
                start.z_m + model.chassis_height_m() + START_CLEARANCE_M,
            ],
            yaw_rad: start.yaw_deg.to_radians(),
        }
    }

    /// The chassis' half extents (m).
    pub(crate) fn chassis_half_m(&self) -> [f64; 3] {
        self.model.chassis.size_m.map(|s| s / 2.0)
    }

    /// The chassis' principal moments of inertia (a uniform box of its mass).
    pub(crate) fn chassis_inertia(&self) -> [f64; 3] {
        box_inertia(self.model.chassis.mass_kg, self.chassis_half_m())
    }

    /// Wheel `i`'s element name.
    pub(crate) fn wheel_name(&self, i: usize) -> String {
        format!("{}_wheel_{i}", self.name)
    }

    /// Arm link `i`'s element name (`robot_43_arm_shoulder`; the index when the link's name
    /// is not a plain identifier).
    pub(crate) fn link_name(&self, i: usize) -> String {
        let plain =
            |n: &str| !n.is_empty() && n.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
        match self.model.arm.as_ref().and_then(|a| a.links.get(i)) {
            Some(l) if plain(&l.name) => format!("{}_arm_{}", self.name, l.name),
            _ => format!("{}_arm_{i}", self.name),
        }
    }

    /// The element name of the chassis body / link.
    pub(crate) fn chassis_name(&self) -> String {
        format!("{}_chassis", self.name)
    }
}

/// An arm joint's axis in its parent link's frame, as sim defines it.
pub(crate) fn arm_axis(axis: ArmAxis) -> [f64; 3] {
    match axis {
        ArmAxis::Yaw => [0.0, 0.0, 1.0],
        ArmAxis::Pitch => [0.0, -1.0, 0.0],
    }
}

/// An arm link's moments of inertia about its centre (a uniform square bar along x).
pub(crate) fn link_inertia(mass_kg: f64, length_m: f64, thickness_m: f64) -> [f64; 3] {
    box_inertia(
        mass_kg,
        [length_m / 2.0, thickness_m / 2.0, thickness_m / 2.0],
    )
}

/// A cleat (grouser) of a wheel: a box standing out of the tyre, in the wheel's frame (axle
/// along y), as sim shapes it.
pub(crate) struct Cleat {
    /// Its centre (m).
    pub center_m: [f64; 3],
    /// Its rotation about the wheel's y (radians).
    pub pitch_rad: f64,
    /// Its half extents (m): radial, along the axle, around the tyre.
    pub half_m: [f64; 3],
}

/// A wheel's cleats (none for a plain tyre): sunk 1 cm (at most a quarter of the radius)
/// into the tyre, as thick as a quarter of their spacing (at most 3 cm).
pub(crate) fn cleats(w: &WheelModel) -> Vec<Cleat> {
    if w.cleats == 0 || w.cleat_height_m <= 0.0 {
        return vec![];
    }
    let (r, h) = (w.radius_m, w.cleat_height_m);
    let sink = 0.01_f64.min(r / 4.0);
    let thick = (std::f64::consts::TAU * r / f64::from(w.cleats) * 0.25).min(0.03);
    let c = r + h / 2.0 - sink / 2.0;
    (0..w.cleats)
        .map(|i| {
            let a = std::f64::consts::TAU * f64::from(i) / f64::from(w.cleats);
            Cleat {
                center_m: [c * a.cos(), 0.0, c * a.sin()],
                pitch_rad: -a,
                half_m: [(h + sink) / 2.0, w.width_m / 2.0, thick / 2.0],
            }
        })
        .collect()
}
