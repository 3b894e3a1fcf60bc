//! The building description: floor, ceiling, walls with door openings and leaves,
//! staircases and furniture boxes. Human-editable TOML (or JSON), documented in the README.
//! All lengths in metres, angles in degrees, the floor's top at z = 0.

use crate::error::{Result, ScannerError};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// A building: the ground truth that virtual scans are taken in.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Building {
    /// A name for people.
    #[serde(default)]
    pub name: String,
    /// The floor slab (its top is at z = 0).
    pub floor: Floor,
    /// The ceiling slab.
    pub ceiling: Ceiling,
    /// Walls, each a vertical box along a segment.
    #[serde(default)]
    pub walls: Vec<Wall>,
    /// Staircases.
    #[serde(default)]
    pub stairs: Vec<Staircase>,
    /// Furniture and clutter.
    #[serde(default)]
    pub boxes: Vec<Furniture>,
    /// Ramps: sloped slabs rising from the floor.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub ramps: Vec<Ramp>,
}

/// The floor slab: a rectangle in the XY plane, top at z = 0.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Floor {
    /// Minimum XY corner.
    pub min_m: [f64; 2],
    /// Maximum XY corner.
    pub max_m: [f64; 2],
    /// Slab thickness (below z = 0).
    #[serde(default = "default_slab_m")]
    pub thickness_m: f64,
}

/// The ceiling slab over the whole floor rectangle.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Ceiling {
    /// Height of the ceiling's underside above the floor.
    pub height_m: f64,
    /// Slab thickness (above `height_m`).
    #[serde(default = "default_slab_m")]
    pub thickness_m: f64,
}

fn default_slab_m() -> f64 {
    0.2
}

/// What a surface is made of, as a laser sees it (the realistic laser's reflectivity; the
/// ideal laser returns from every material alike).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Material {
    /// Plaster, concrete, wood: a matte surface that returns the beam well.
    #[default]
    Matte,
    /// A dark or black surface (tyres, dark paint, black cabinets): returns little light.
    Dark,
    /// Glass: most beams pass through it, a few come back.
    Glass,
}

impl Material {
    /// Whether this is the default (for `skip_serializing_if`).
    pub fn is_matte(&self) -> bool {
        *self == Material::Matte
    }
}

/// A straight wall from `start_m` to `end_m` (its centre line), standing on the floor.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Wall {
    /// Optional name for people.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub name: String,
    /// Start of the centre line (XY).
    pub start_m: [f64; 2],
    /// End of the centre line (XY).
    pub end_m: [f64; 2],
    /// Thickness across the centre line.
    pub thickness_m: f64,
    /// Height; absent means up to the ceiling.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height_m: Option<f64>,
    /// Door openings in this wall.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub doors: Vec<Door>,
    /// What the wall is made of (`glass` for a glass wall).
    #[serde(default, skip_serializing_if = "Material::is_matte")]
    pub material: Material,
}

impl Wall {
    /// Length of the wall's centre line.
    pub fn length_m(&self) -> f64 {
        (self.end_m[0] - self.start_m[0]).hypot(self.end_m[1] - self.start_m[1])
    }

    /// The point of the wall's centre line `s_m` metres from its start (the start itself for a
    /// wall of no length).
    pub fn point_at_m(&self, s_m: f64) -> [f64; 2] {
        let len = self.length_m();
        let t = if len > 0.0 { s_m / len } else { 0.0 };
        [
            self.start_m[0] + (self.end_m[0] - self.start_m[0]) * t,
            self.start_m[1] + (self.end_m[1] - self.start_m[1]) * t,
        ]
    }
}

impl Door {
    /// How far along its wall, from the wall's start, the leaf's hinge stands (the opening's
    /// near or far edge); `None` for an empty opening.
    pub fn hinge_offset_m(&self) -> Option<f64> {
        self.leaf.as_ref().map(|leaf| match leaf.hinge {
            Hinge::Start => self.offset_m,
            Hinge::End => self.offset_m + self.width_m,
        })
    }
}

/// A door opening in a wall, optionally with a leaf.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Door {
    /// Distance along the wall from its start to the near edge of the opening.
    pub offset_m: f64,
    /// Width of the opening.
    pub width_m: f64,
    /// Height of the opening (the lintel's underside).
    pub height_m: f64,
    /// The door leaf; absent means an empty opening.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub leaf: Option<Leaf>,
}

/// Which edge of the opening carries the hinge.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Hinge {
    /// The edge nearer the wall's start.
    Start,
    /// The edge nearer the wall's end.
    End,
}

/// To which side of the wall the leaf swings, looking from the wall's start to its end.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Swing {
    /// Towards the left-hand side.
    Left,
    /// Towards the right-hand side.
    Right,
}

/// A door leaf hinged at one edge of its opening.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Leaf {
    /// Hinge edge.
    pub hinge: Hinge,
    /// Swing side.
    pub swing: Swing,
    /// Opening angle: 0 closed, 90 wide open.
    pub open_deg: f64,
    /// Leaf thickness.
    #[serde(default = "default_leaf_m")]
    pub thickness_m: f64,
    /// What the leaf is made of (`glass` for a glass door).
    #[serde(default, skip_serializing_if = "Material::is_matte")]
    pub material: Material,
}

fn default_leaf_m() -> f64 {
    0.04
}

/// A straight flight of block steps rising from the floor (or from `base_m` above it: the
/// second flight of a staircase with a mid landing starts on the first one's landing), with an
/// optional top landing. Steps and landing are solid down to the floor.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Staircase {
    /// Optional name for people.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub name: String,
    /// Centre of the first step's front edge, on the floor (XY).
    pub start_m: [f64; 2],
    /// Direction of ascent (0 = +x, 90 = +y).
    pub direction_deg: f64,
    /// Number of steps.
    pub steps: u32,
    /// Height of each step.
    pub rise_m: f64,
    /// Depth of each step's tread.
    pub run_m: f64,
    /// Width across the direction of ascent.
    pub width_m: f64,
    /// Depth of the landing at the top (0 = none).
    #[serde(default)]
    pub landing_m: f64,
    /// Height of the flight's foot above the floor (0: it rises from the floor; a flight
    /// starting on a mid landing: the landing's height).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub base_m: f64,
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

/// A ramp: a straight sloped slab whose top rises from the floor at `start_m` to `rise_m`
/// over `length_m` (measured on the floor) in the direction `direction_deg`. Walkable: its
/// ground-truth class is `ramp` (see the README's building file section).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Ramp {
    /// Optional name for people.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub name: String,
    /// Centre of the ramp's foot (where its top meets the floor), XY.
    pub start_m: [f64; 2],
    /// Direction of ascent (0 = +x, 90 = +y).
    pub direction_deg: f64,
    /// Horizontal length from foot to head.
    pub length_m: f64,
    /// Width across the direction of ascent.
    pub width_m: f64,
    /// Height of the top at the head above the floor.
    pub rise_m: f64,
    /// Slab thickness, measured square to the slope.
    #[serde(default = "default_ramp_thickness_m")]
    pub thickness_m: f64,
}

fn default_ramp_thickness_m() -> f64 {
    0.2
}

impl Ramp {
    /// The slope's angle above the floor (radians).
    pub fn pitch_rad(&self) -> f64 {
        self.rise_m.atan2(self.length_m)
    }

    /// The unit direction of ascent in the floor plane.
    pub fn direction(&self) -> [f64; 2] {
        let a = self.direction_deg.to_radians();
        [a.cos(), a.sin()]
    }
}

/// A box standing anywhere: furniture or clutter (usually on the floor), or, by its `class`,
/// an obstacle such as a parked car or a shelf, a column (pillar) or a beam under the ceiling.
/// Things of several boxes (a table and its legs) are several boxes with one name.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Furniture {
    /// Optional name for people.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub name: String,
    /// Its ground-truth class: `furniture` (default), `obstacle`, `column` or `beam`.
    #[serde(default = "default_box_class", skip_serializing_if = "is_furniture")]
    pub class: cloud::EntityClass,
    /// What it is made of.
    #[serde(default, skip_serializing_if = "Material::is_matte")]
    pub material: Material,
    /// Box centre.
    pub center_m: [f64; 3],
    /// Full box size along its own axes.
    pub size_m: [f64; 3],
    /// Rotation about z.
    #[serde(default)]
    pub yaw_deg: f64,
}

fn default_box_class() -> cloud::EntityClass {
    cloud::EntityClass::Furniture
}

fn is_furniture(c: &cloud::EntityClass) -> bool {
    *c == cloud::EntityClass::Furniture
}

/// The classes a building's box may have.
pub const BOX_CLASSES: [cloud::EntityClass; 4] = [
    cloud::EntityClass::Furniture,
    cloud::EntityClass::Obstacle,
    cloud::EntityClass::Column,
    cloud::EntityClass::Beam,
];

const BUILTIN: &str = include_str!("../data/default_building.toml");

impl Building {
    /// The embedded default building (`crates/scanner/data/default_building.toml`).
    pub fn default_building() -> Result<Building> {
        Building::from_toml_str(BUILTIN, Path::new("<built-in default building>"))
    }

    /// Scan poses through the default building: down the corridor, through the stair room's
    /// door, into the stair room (the demo's survey).
    pub fn default_survey_poses() -> Vec<crate::pose::ScanPose> {
        [
            (1.5, 0.0, 0.0),
            (4.0, 0.1, 0.0),
            (6.5, -0.1, 0.0),
            (9.0, 0.0, 0.0),
            (11.5, 0.1, 0.0),
            (14.4, 0.0, 45.0),
            (14.45, 1.2, 80.0),
            (14.9, 2.2, 0.0),
            (17.5, 2.5, 0.0),
        ]
        .into_iter()
        .map(|(x_m, y_m, yaw_deg)| crate::pose::ScanPose { x_m, y_m, yaw_deg })
        .collect()
    }

    /// Parses and validates a TOML description; `path` only names the source in errors.
    pub fn from_toml_str(text: &str, path: &Path) -> Result<Building> {
        let b: Building = toml::from_str(text).map_err(|e| ScannerError::Syntax {
            path: path.to_path_buf(),
            msg: e.to_string().trim_end().to_string(),
        })?;
        b.validate(path)?;
        Ok(b)
    }

    /// Loads and validates a building file (`.toml`, or `.json`).
    pub fn load(path: &Path) -> Result<Building> {
        let text = std::fs::read_to_string(path).map_err(|e| cloud::CloudError::io(path, e))?;
        let is_json = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("json"));
        if is_json {
            Building::from_json_str(&text, path)
        } else {
            Building::from_toml_str(&text, path)
        }
    }

    /// Parses and validates a JSON description; `path` only names the source in errors.
    pub fn from_json_str(text: &str, path: &Path) -> Result<Building> {
        let b: Building = serde_json::from_str(text).map_err(|e| ScannerError::Syntax {
            path: path.to_path_buf(),
            msg: e.to_string(),
        })?;
        b.validate(path)?;
        Ok(b)
    }

    /// Writes the building as TOML (or JSON for a `.json` path), atomically.
    pub fn save(&self, path: &Path) -> Result<()> {
        let is_json = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("json"));
        let text = if is_json {
            serde_json::to_string_pretty(self).map_err(|e| syntax(path, e))?
        } else {
            toml::to_string(self).map_err(|e| syntax(path, e))?
        };
        cloud::write_bytes_atomically(path, text.as_bytes())?;
        Ok(())
    }

    /// The height of wall `w` (its own, or the ceiling's).
    pub fn wall_height_m(&self, w: &Wall) -> f64 {
        w.height_m.unwrap_or(self.ceiling.height_m)
    }
}

fn syntax(path: &Path, e: impl std::fmt::Display) -> ScannerError {
    ScannerError::Syntax {
        path: path.to_path_buf(),
        msg: e.to_string(),
    }
}
