//! The robot model file (TOML): chassis box, wheels (optionally cleated), skid-steering
//! drive and an optional arm with breakable joints; two models are built in: `pioneer3at` and
//! `inspection` (a six-wheel stair climber with a three-joint arm). Robots are data.

use crate::error::{check_finite, check_range, read_text, Result, SimError};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// A robot model: chassis, wheels, drive and an optional arm. Lengths in metres, relative to
/// the chassis centre (x forward, y left, z up).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RobotModel {
    /// Model name.
    pub name: String,
    /// A line for people.
    #[serde(default)]
    pub description: String,
    /// The chassis box.
    pub chassis: ChassisModel,
    /// The wheels (at least two, on both sides).
    pub wheels: Vec<WheelModel>,
    /// The skid-steering drive.
    pub drive: DriveModel,
    /// An optional arm on the chassis.
    #[serde(default)]
    pub arm: Option<ArmModel>,
}

/// The chassis: a box.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChassisModel {
    /// Full size (length x, width y, height z).
    pub size_m: [f64; 3],
    /// Mass (kg).
    pub mass_kg: f64,
    /// Centre of mass relative to the box centre (a low one climbs better).
    #[serde(default)]
    pub com_offset_m: [f64; 3],
}

/// A wheel: a cylinder with its axle along y.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WheelModel {
    /// Wheel centre relative to the chassis centre.
    pub position_m: [f64; 3],
    /// Radius.
    pub radius_m: f64,
    /// Width (along the axle).
    pub width_m: f64,
    /// Mass (kg).
    pub mass_kg: f64,
    /// Whether its motor drives it (otherwise it rolls freely).
    #[serde(default = "yes")]
    pub driven: bool,
    /// Cleats (grousers) around the tyre: 0 = a plain cylinder. Cleats hook onto stair
    /// nosings, which plain tyres can only climb by friction.
    #[serde(default)]
    pub cleats: u32,
    /// How far the cleats stand out of the tyre (m).
    #[serde(default)]
    pub cleat_height_m: f64,
}

fn yes() -> bool {
    true
}

/// Skid steering: each driven wheel has a velocity motor with limited torque.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DriveModel {
    /// Top linear speed (m/s); commands are clamped to it.
    pub max_speed_mps: f64,
    /// Top yaw rate (rad/s).
    pub max_yaw_rate_radps: f64,
    /// Motor torque limit per driven wheel (N m).
    pub max_wheel_torque_nm: f64,
    /// Tyre friction coefficient (used as is: the larger of the pair wins).
    pub wheel_friction: f64,
    /// Effective track multiplier for skid steering (wheels slip sideways when turning).
    #[serde(default = "one")]
    pub skid_factor: f64,
}

fn one() -> f64 {
    1.0
}

/// An arm: a chain of links on revolute joints, each holding its angle with a position motor.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ArmModel {
    /// The first joint's position relative to the chassis centre.
    pub mount_m: [f64; 3],
    /// Links from the base outwards (1 to 6).
    pub links: Vec<LinkModel>,
}

/// The axis of an arm joint, in the parent link's frame (x along the parent link).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ArmAxis {
    /// About z: positive turns the link to the left.
    Yaw,
    /// About -y: positive raises the link.
    Pitch,
}

/// One arm link (a square bar along its own x) and the joint at its base.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LinkModel {
    /// A name for events, e.g. `shoulder`.
    pub name: String,
    /// The joint's axis.
    pub axis: ArmAxis,
    /// Link length.
    pub length_m: f64,
    /// Link cross-section side.
    pub thickness_m: f64,
    /// Link mass (kg).
    pub mass_kg: f64,
    /// The angle the joint holds (degrees).
    #[serde(default)]
    pub angle_deg: f64,
    /// Joint limits (degrees).
    pub min_deg: f64,
    /// Joint limits (degrees).
    pub max_deg: f64,
    /// Motor torque limit (N m).
    pub max_torque_nm: f64,
    /// Force on the joint that breaks it (N); absent = unbreakable.
    #[serde(default)]
    pub break_force_n: Option<f64>,
    /// Bending torque (locked axes and limit) that breaks it (N m); absent = unbreakable.
    #[serde(default)]
    pub break_torque_nm: Option<f64>,
}

/// Where a robot starts: position on the floor (z = height of the surface under its wheels).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StartPose {
    /// x (m).
    pub x_m: f64,
    /// y (m).
    pub y_m: f64,
    /// Heading (degrees, 0 = +x, 90 = +y).
    #[serde(default)]
    pub yaw_deg: f64,
    /// Height of the surface the wheels stand on (m).
    #[serde(default)]
    pub z_m: f64,
}

impl StartPose {
    /// Checks that every number is finite.
    pub fn validate(&self) -> Result<()> {
        check_finite(
            "start",
            "x_m, y_m, yaw_deg, z_m",
            &[self.x_m, self.y_m, self.yaw_deg, self.z_m],
        )
    }
}

const BUILTINS: [(&str, &str); 2] = [
    ("pioneer3at", include_str!("../data/pioneer3at.toml")),
    ("inspection", include_str!("../data/inspection.toml")),
];

impl RobotModel {
    /// The names of the built-in models.
    pub fn builtin_names() -> Vec<&'static str> {
        BUILTINS.iter().map(|b| b.0).collect()
    }

    /// A built-in model by name (`pioneer3at`, `inspection`).
    pub fn builtin(name: &str) -> Result<RobotModel> {
        let (n, text) =
            BUILTINS
                .iter()
                .find(|b| b.0 == name)
                .ok_or_else(|| SimError::UnknownRobotModel {
                    name: name.to_string(),
                    builtins: Self::builtin_names().join(", "),
                })?;
        RobotModel::from_toml_str(text, &format!("<built-in robot model {n}>"))
    }

    /// A built-in name, or else a model file (relative paths from `base_dir`): TOML, or URDF
    /// when the name ends in `.urdf` (see [`RobotModel::load`]).
    pub fn resolve(name_or_path: &str, base_dir: &Path) -> Result<RobotModel> {
        if BUILTINS.iter().any(|b| b.0 == name_or_path) {
            return RobotModel::builtin(name_or_path);
        }
        let path = base_dir.join(name_or_path);
        if path.is_file() {
            return RobotModel::load(&path);
        }
        Err(SimError::UnknownRobotModel {
            name: name_or_path.to_string(),
            builtins: Self::builtin_names().join(", "),
        })
    }

    /// Loads and validates a model file: a URDF robot description when its name ends in
    /// `.urdf` (any case; see [`RobotModel::load_urdf`]), else semsim's TOML.
    pub fn load(path: &Path) -> Result<RobotModel> {
        let urdf = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("urdf"));
        if urdf {
            return RobotModel::load_urdf(path);
        }
        RobotModel::from_toml_str(&read_text(path)?, &path.display().to_string())
    }

    /// Parses and validates a model; `source` names it in errors.
    pub fn from_toml_str(text: &str, source: &str) -> Result<RobotModel> {
        let m: RobotModel = toml::from_str(text).map_err(|e| SimError::Syntax {
            source_name: source.to_string(),
            msg: e.to_string().trim_end().to_string(),
        })?;
        m.validate().map_err(|e| e.in_source(source))?;
        Ok(m)
    }

    /// Checks sizes, masses and the wheel layout.
    pub fn validate(&self) -> Result<()> {
        let el = format!("robot model {}", self.name);
        let el = el.as_str();
        let c = &self.chassis;
        for s in c.size_m {
            check_range(el, "chassis.size_m", s, 0.01, 10.0, "1 cm to 10 m")?;
        }
        check_range(
            el,
            "chassis.mass_kg",
            c.mass_kg,
            0.1,
            10_000.0,
            "0.1 kg to 10 t",
        )?;
        check_finite(el, "chassis.com_offset_m", &c.com_offset_m)?;
        if self.wheels.len() < 2 || self.wheels.len() > 32 {
            return Err(SimError::Invalid {
                element: el.to_string(),
                msg: format!("needs 2 to 32 wheels, has {}", self.wheels.len()),
            });
        }
        for (i, w) in self.wheels.iter().enumerate() {
            let wel = format!("{el}.wheels[{i}]");
            check_finite(&wel, "position_m", &w.position_m)?;
            check_range(&wel, "radius_m", w.radius_m, 0.01, 2.0, "1 cm to 2 m")?;
            check_range(&wel, "width_m", w.width_m, 0.005, 1.0, "5 mm to 1 m")?;
            check_range(&wel, "mass_kg", w.mass_kg, 0.01, 1000.0, "10 g to 1 t")?;
            check_range(&wel, "cleats", w.cleats as f64, 0.0, 64.0, "0 to 64")?;
            check_range(
                &wel,
                "cleat_height_m",
                w.cleat_height_m,
                0.0,
                w.radius_m,
                "0 to the radius",
            )?;
        }
        let left = self
            .wheels
            .iter()
            .any(|w| w.driven && w.position_m[1] > 0.0);
        let right = self
            .wheels
            .iter()
            .any(|w| w.driven && w.position_m[1] < 0.0);
        if !(left && right) {
            return Err(SimError::Invalid {
                element: el.to_string(),
                msg: "skid steering needs driven wheels on both sides (y > 0 and y < 0)".into(),
            });
        }
        let d = &self.drive;
        check_range(
            el,
            "drive.max_speed_mps",
            d.max_speed_mps,
            0.01,
            20.0,
            "0.01 to 20 m/s",
        )?;
        check_range(
            el,
            "drive.max_yaw_rate_radps",
            d.max_yaw_rate_radps,
            0.01,
            20.0,
            "0.01 to 20 rad/s",
        )?;
        check_range(
            el,
            "drive.max_wheel_torque_nm",
            d.max_wheel_torque_nm,
            0.01,
            1.0e4,
            "0.01 to 1e4 N m",
        )?;
        check_range(
            el,
            "drive.wheel_friction",
            d.wheel_friction,
            0.0,
            5.0,
            "0 to 5",
        )?;
        check_range(el, "drive.skid_factor", d.skid_factor, 0.5, 5.0, "0.5 to 5")?;
        if let Some(arm) = &self.arm {
            check_finite(el, "arm.mount_m", &arm.mount_m)?;
            if arm.links.is_empty() || arm.links.len() > 6 {
                return Err(SimError::Invalid {
                    element: format!("{el}.arm"),
                    msg: format!("needs 1 to 6 links, has {}", arm.links.len()),
                });
            }
            for (i, l) in arm.links.iter().enumerate() {
                let lel = format!("{el}.arm.links[{i}]");
                check_range(&lel, "length_m", l.length_m, 0.01, 5.0, "1 cm to 5 m")?;
                check_range(
                    &lel,
                    "thickness_m",
                    l.thickness_m,
                    0.005,
                    1.0,
                    "5 mm to 1 m",
                )?;
                check_range(&lel, "mass_kg", l.mass_kg, 0.01, 1000.0, "10 g to 1 t")?;
                check_range(&lel, "min_deg", l.min_deg, -180.0, 180.0, "-180 to 180")?;
                check_range(
                    &lel,
                    "max_deg",
                    l.max_deg,
                    l.min_deg,
                    180.0,
                    "min_deg to 180",
                )?;
                check_range(
                    &lel,
                    "angle_deg",
                    l.angle_deg,
                    l.min_deg,
                    l.max_deg,
                    "within the limits",
                )?;
                check_range(
                    &lel,
                    "max_torque_nm",
                    l.max_torque_nm,
                    0.0,
                    1.0e5,
                    "0 to 1e5 N m",
                )?;
                if let Some(f) = l.break_force_n {
                    check_range(&lel, "break_force_n", f, 1.0, 1.0e9, "1 N to 1e9 N")?;
                }
                if let Some(t) = l.break_torque_nm {
                    check_range(&lel, "break_torque_nm", t, 0.1, 1.0e9, "0.1 N m to 1e9 N m")?;
                }
            }
        }
        Ok(())
    }

    /// Height of the chassis centre above the surface the wheels stand on.
    pub fn chassis_height_m(&self) -> f64 {
        self.wheels
            .iter()
            .map(|w| {
                w.radius_m + if w.cleats > 0 { w.cleat_height_m } else { 0.0 } - w.position_m[2]
            })
            .fold(f64::MIN, f64::max)
    }
}
