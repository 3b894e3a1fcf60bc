//! World exports: a [`sim::WorldSpec`] (and optionally a robot) as MuJoCo MJCF, Gazebo SDF 1.9
//! or glTF 2.0 binary (GLB), with the semantics semsim's own rapier world gives it.
//!
//! What every format carries (details in each writer's docs):
//!
//! | | MJCF ([`mjcf`]) | SDF ([`sdf`]) | GLB ([`gltf`]) |
//! |---|---|---|---|
//! | floor, ceiling, walls, lintels, furniture, stair steps and landings | static box geoms | links of the static model `building` | one mesh per entity |
//! | doors | a body at the hinge, hinge joint about z with the limits, damping and dry friction | a model with a revolute joint to the world | a node at the hinge (rotate about its local +Y) |
//! | door free spaces | box sites | visual-only links | translucent nodes |
//! | robot (optional) | free body, wheels on velocity actuators, arm on position servos | a model with continuous wheel joints and revolute arm joints | a node tree |
//! | entity ids and classes | element names `wall_12`, `door_17_leaf` | link and model names | node names `wall 12` and `extras` |
//!
//! All three are in metres; MJCF and SDF in semsim's frame (z up), glTF in its own (+Y up).

mod gltf;
mod mjcf;
mod parts;
mod robot;
mod sdf;
mod xml;

use crate::error::Result;
use semantic::Relation;
use sim::{RobotModel, StartPose, WorldSpec};
use std::path::Path;
use std::str::FromStr;

/// The formats a world can be exported to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ExportFormat {
    /// MuJoCo's MJCF (XML): loads with `mujoco.MjModel.from_xml_path`.
    Mjcf,
    /// SDFormat 1.9 (XML), for Gazebo.
    Sdf,
    /// glTF 2.0 binary (`.glb`), for viewers (three.js, Blender) and game engines.
    Glb,
}

impl ExportFormat {
    /// Every format.
    pub const ALL: [ExportFormat; 3] = [ExportFormat::Mjcf, ExportFormat::Sdf, ExportFormat::Glb];

    /// The usual file extension, without the dot: `xml` (MuJoCo's own), `sdf`, `glb`.
    pub fn extension(&self) -> &'static str {
        match self {
            ExportFormat::Mjcf => "xml",
            ExportFormat::Sdf => "sdf",
            ExportFormat::Glb => "glb",
        }
    }

    /// The format a file name asks for by its extension (`.xml` or `.mjcf`, `.sdf`, `.glb`;
    /// any case), if any.
    pub fn from_path(path: &Path) -> Option<ExportFormat> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "xml" | "mjcf" => Some(ExportFormat::Mjcf),
            "sdf" => Some(ExportFormat::Sdf),
            "glb" => Some(ExportFormat::Glb),
            _ => None,
        }
    }
}

impl FromStr for ExportFormat {
    type Err = String;

    /// `mjcf`, `sdf`, `gltf` or `glb` (any case).
    fn from_str(s: &str) -> std::result::Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "mjcf" => Ok(ExportFormat::Mjcf),
            "sdf" => Ok(ExportFormat::Sdf),
            "gltf" | "glb" => Ok(ExportFormat::Glb),
            _ => Err(format!(
                "unknown export format {s:?}: expected mjcf, sdf, gltf or glb"
            )),
        }
    }
}

impl std::fmt::Display for ExportFormat {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            ExportFormat::Mjcf => "mjcf",
            ExportFormat::Sdf => "sdf",
            ExportFormat::Glb => "glb",
        })
    }
}

/// What goes into an export besides the world.
#[derive(Debug, Clone, Copy, Default)]
pub struct ExportOptions<'a> {
    /// A robot and where it starts (as in a scenario); it gets the entity id after the
    /// world's largest, as in a simulation.
    pub robot: Option<(&'a RobotModel, StartPose)>,
    /// The semantic map's relations between entities, for the GLB's node `extras` (the
    /// relations the world itself implies, a door `connected_via_joint` to its wall and a free
    /// space `available_inside` its wall, with its door inside it, are always added).
    pub relations: &'a [Relation],
}

/// Exports a world (validated first: a world sim would refuse is refused here too) and the
/// options' robot as the bytes of a file of `format`.
pub fn export_world(
    spec: &WorldSpec,
    format: ExportFormat,
    options: &ExportOptions,
) -> Result<Vec<u8>> {
    spec.validate()?;
    spec.check_limits()?;
    let robot = match options.robot {
        Some((model, start)) => {
            model.validate()?;
            start.validate()?;
            Some(robot::RobotLayout::new(model, &start, spec))
        }
        None => None,
    };
    Ok(match format {
        ExportFormat::Mjcf => mjcf::write(spec, robot.as_ref()).into_bytes(),
        ExportFormat::Sdf => sdf::write(spec, robot.as_ref()).into_bytes(),
        ExportFormat::Glb => gltf::write(spec, robot.as_ref(), options.relations),
    })
}

/// Exports a world (see [`export_world`]) to `path`, atomically: a failed export leaves no
/// file, and an existing file is replaced only by a complete one. Errors name the path.
pub fn write_export(
    path: &Path,
    spec: &WorldSpec,
    format: ExportFormat,
    options: &ExportOptions,
) -> Result<()> {
    let bytes = export_world(spec, format, options)?;
    cloud::write_bytes_atomically(path, &bytes)?;
    Ok(())
}
