//! Building a [`WorldSpec`] from a ground-truth [`scanner::Building`]: entity ids and names are
//! those of [`scanner::BuildingGeometry`] (`floor`, `walls[4]`, `walls[4].doors[2].lintel`,
//! `walls[4].doors[2].leaf`, `stairs[0]`, `boxes[1]`); each door opening also gets a free-space
//! entity `walls[4].doors[2].free_space` with the next free ids.

use super::ramp::{MAX_RAMP_BLOCKS, RAMP_STEP_M};
use super::ImportConfig;
use crate::error::{Result, SimError};
use crate::spec::{
    BoxSpec, DoorSpec, FixedBox, FreeSpaceSpec, HingeEnd, OpeningSense, StairsSpec, StepSpec,
    WorldSpec,
};
use cloud::EntityClass;
use scanner::{Building, BuildingGeometry, Door, Hinge, Leaf, Swing, Wall};
use std::collections::HashMap;
use std::path::Path;

/// A wall shorter than this (m) has no direction: it gets no doors and no free spaces.
const MIN_WALL_LENGTH_M: f64 = 1e-9;
/// A door leaf is this much narrower and lower than its opening (m), so that it swings free
/// of the frame and the floor ...
const LEAF_CLEARANCE_M: f64 = 0.01;
/// ... but is at least this long and high (m).
const MIN_LEAF_SIZE_M: f64 = 0.01;
/// The gap under a door leaf (m): half the clearance, the leaf centred in its opening's height.
const LEAF_FLOOR_GAP_M: f64 = 0.005;

impl WorldSpec {
    /// The ground-truth world of a (validated) building, with default door properties.
    pub fn from_building(b: &Building) -> Result<WorldSpec> {
        WorldSpec::from_building_with(b, &ImportConfig::default())
    }

    /// The ground-truth world of a building file (TOML/JSON, see [`Building::load`]), with
    /// default door properties; every error names the file.
    pub fn from_building_file(path: &Path) -> Result<WorldSpec> {
        let b = Building::load(path)?;
        WorldSpec::from_building(&b).map_err(|e| e.in_source(&path.display().to_string()))
    }

    /// The ground-truth world of a (validated) building.
    pub fn from_building_with(b: &Building, cfg: &ImportConfig) -> Result<WorldSpec> {
        cfg.validate()?;
        let geometry = BuildingGeometry::new(b);
        let labels = labels(b);
        let mut spec = WorldSpec {
            name: b.name.clone(),
            ..Default::default()
        };
        // 1. Floor, ceiling, walls, lintels and furniture become fixed boxes; each staircase's
        //    blocks its steps and landing.
        (spec.fixed, spec.stairs) = fixed_and_stairs(b, &geometry, &labels);
        // 2. Wall by wall, each door opening's leaf on its hinge and its free space; the free
        //    spaces take the ids after the geometry's entities.
        let ids: HashMap<&str, u32> = geometry
            .entities()
            .iter()
            .map(|e| (e.name.as_str(), e.id))
            .collect();
        let mut next_id = geometry.entities().iter().map(|e| e.id).max().unwrap_or(0) + 1;
        for (i, w) in b.walls.iter().enumerate() {
            add_openings(&mut spec, i, w, &ids, cfg, &mut next_id)?;
        }
        // 3. The whole world must be consistent.
        spec.validate()?;
        Ok(spec)
    }
}

/// The fixed boxes (in the geometry's part order) and the staircases (by entity id).
fn fixed_and_stairs(
    b: &Building,
    geometry: &BuildingGeometry,
    labels: &HashMap<String, String>,
) -> (Vec<FixedBox>, Vec<StairsSpec>) {
    let mut fixed = Vec::new();
    let mut stairs: HashMap<u32, StairsSpec> = HashMap::new();
    for part in geometry.parts() {
        let id = part.label.entity;
        let Some(ent) = geometry.entities().get(id as usize - 1) else {
            continue;
        };
        let label = || labels.get(&ent.name).cloned().unwrap_or_default();
        let class = part.label.class;
        match class {
            EntityClass::Floor
            | EntityClass::Ceiling
            | EntityClass::Wall
            | EntityClass::WallAboveDoor
            | EntityClass::Furniture
            | EntityClass::Obstacle
            | EntityClass::Column
            | EntityClass::Beam
            | EntityClass::Ramp => {
                for geometry in boxes_of(part) {
                    fixed.push(FixedBox {
                        entity: id,
                        class,
                        name: ent.name.clone(),
                        label: label(),
                        geometry,
                    });
                }
            }
            EntityClass::Stairs => {
                let s = stairs.entry(id).or_insert_with(|| StairsSpec {
                    entity: id,
                    name: ent.name.clone(),
                    label: label(),
                    steps: vec![],
                    landing: None,
                });
                // The staircase's first blocks are its steps, the one after them its landing.
                if s.steps.len() < stair_steps(b, &ent.name) {
                    let index = s.steps.len() as u32;
                    s.steps.push(StepSpec {
                        index,
                        geometry: box_of(part),
                    });
                } else {
                    s.landing = Some(box_of(part));
                }
            }
            // Door leaves are made from the building (closed pose, hinge) by `door_leaf`; a
            // building's geometry has no free-space, robot or unlabelled parts.
            EntityClass::Door
            | EntityClass::Unknown
            | EntityClass::FreeSpaceForDoor
            | EntityClass::Robot => {}
        }
    }
    let mut stairs: Vec<StairsSpec> = stairs.into_values().collect();
    stairs.sort_by_key(|s| s.entity);
    (fixed, stairs)
}

/// A wall's axis: its direction and yaw, and the point a distance along it.
struct WallAxis {
    start: [f64; 2],
    /// The unit vector from the wall's start to its end.
    u: [f64; 2],
    /// The direction's angle from +x (radians).
    yaw: f64,
}

impl WallAxis {
    /// The axis of `w`; `None` for a wall shorter than [`MIN_WALL_LENGTH_M`].
    fn of(w: &Wall) -> Option<WallAxis> {
        let (dx, dy) = (w.end_m[0] - w.start_m[0], w.end_m[1] - w.start_m[1]);
        let len = (dx.powi(2) + dy.powi(2)).sqrt();
        if len <= MIN_WALL_LENGTH_M {
            return None;
        }
        let u = [dx / len, dy / len];
        Some(WallAxis {
            start: w.start_m,
            u,
            yaw: u[1].atan2(u[0]),
        })
    }

    /// The point `s` metres along the wall from its start.
    fn at(&self, s: f64) -> [f64; 2] {
        [self.start[0] + self.u[0] * s, self.start[1] + self.u[1] * s]
    }
}

/// Adds wall `i`'s door leaves and free spaces to `spec`. An opening whose leaf the geometry
/// has no entity for is skipped whole.
fn add_openings(
    spec: &mut WorldSpec,
    i: usize,
    w: &Wall,
    ids: &HashMap<&str, u32>,
    cfg: &ImportConfig,
    next_id: &mut u32,
) -> Result<()> {
    let wall_name = format!("walls[{i}]");
    let wall_id = *ids
        .get(wall_name.as_str())
        .ok_or_else(|| SimError::Invalid {
            element: wall_name.clone(),
            msg: "the building geometry has no entity for this wall".into(),
        })?;
    let Some(axis) = WallAxis::of(w) else {
        return Ok(());
    };
    for (j, d) in w.doors.iter().enumerate() {
        let base = format!("walls[{i}].doors[{j}]");
        let door_id = match &d.leaf {
            Some(leaf) => {
                let name = format!("{base}.leaf");
                let Some(&id) = ids.get(name.as_str()) else {
                    continue;
                };
                let label = if w.name.is_empty() {
                    String::new()
                } else {
                    format!("{}, door {j}", w.name)
                };
                let door = door_leaf(d, leaf, &axis, cfg);
                spec.doors.push(DoorSpec {
                    entity: id,
                    name,
                    label,
                    wall: wall_id,
                    ..door
                });
                Some(id)
            }
            None => None,
        };
        spec.free_spaces.push(FreeSpaceSpec {
            entity: *next_id,
            name: format!("{base}.free_space"),
            door: door_id,
            wall: Some(wall_id),
            geometry: free_space(d, w, &axis, cfg),
        });
        *next_id += 1;
    }
    Ok(())
}

/// Door `d`'s leaf, closed, on its hinge (entity, names and wall left empty for the caller).
fn door_leaf(d: &Door, leaf: &Leaf, axis: &WallAxis, cfg: &ImportConfig) -> DoorSpec {
    let (yaw, half_turn) = (axis.yaw, axis.yaw + std::f64::consts::PI);
    let (hinge_s, closed_yaw, sense) = match (leaf.hinge, leaf.swing) {
        (Hinge::Start, Swing::Left) => (d.offset_m, yaw, OpeningSense::Ccw),
        (Hinge::Start, Swing::Right) => (d.offset_m, yaw, OpeningSense::Cw),
        (Hinge::End, Swing::Left) => (d.offset_m + d.width_m, half_turn, OpeningSense::Cw),
        (Hinge::End, Swing::Right) => (d.offset_m + d.width_m, half_turn, OpeningSense::Ccw),
    };
    let leaf_len = (d.width_m - LEAF_CLEARANCE_M).max(MIN_LEAF_SIZE_M);
    let leaf_h = (d.height_m - LEAF_CLEARANCE_M).max(MIN_LEAF_SIZE_M);
    let h = axis.at(hinge_s);
    let max_deg = cfg.door_max_deg.max(leaf.open_deg);
    DoorSpec {
        entity: 0,
        name: String::new(),
        label: String::new(),
        wall: 0,
        leaf: BoxSpec {
            center_m: [
                h[0] + closed_yaw.cos() * leaf_len / 2.0,
                h[1] + closed_yaw.sin() * leaf_len / 2.0,
                LEAF_FLOOR_GAP_M + leaf_h / 2.0,
            ],
            half_extents_m: [leaf_len / 2.0, leaf.thickness_m / 2.0, leaf_h / 2.0],
            yaw_deg: closed_yaw.to_degrees(),
        },
        hinge_m: h,
        hinge_end: HingeEnd::Start,
        opens: sense,
        min_deg: 0.0,
        max_deg,
        initial_deg: leaf.open_deg,
        mass_kg: cfg.door_mass_kg,
        damping_per_s: cfg.door_damping_per_s,
        hinge_friction_nm: cfg.door_hinge_friction_nm,
        break_force_n: (cfg.door_break_force_n > 0.0).then_some(cfg.door_break_force_n),
    }
}

/// Door `d`'s free space: its opening, reaching `free_space_margin_m` out of the wall on
/// each side.
fn free_space(d: &Door, w: &Wall, axis: &WallAxis, cfg: &ImportConfig) -> BoxSpec {
    let mid = axis.at(d.offset_m + d.width_m / 2.0);
    BoxSpec {
        center_m: [mid[0], mid[1], d.height_m / 2.0],
        half_extents_m: [
            d.width_m / 2.0,
            w.thickness_m / 2.0 + cfg.free_space_margin_m,
            d.height_m / 2.0,
        ],
        yaw_deg: axis.yaw.to_degrees(),
    }
}

/// The boxes of part `p` for the world, whose boxes turn about z only: the part itself, or for
/// a pitched one (a ramp's slab) a run of yawed blocks following its top within [`RAMP_STEP_M`]
/// and as thick (vertically) as the slab.
fn boxes_of(p: &scanner::BoxPart) -> Vec<BoxSpec> {
    if p.pitch_rad == 0.0 {
        return vec![box_of(p)];
    }
    let pitch = f64::from(p.pitch_rad);
    let yaw = f64::from(p.yaw_rad);
    let (sp, cp) = pitch.sin_cos();
    let (dx, dy) = (yaw.cos(), yaw.sin());
    let c = p.center_m.to_array().map(f64::from);
    let h = p.half_extents_m.to_array().map(f64::from);
    // The top face's edge `u` along the slope from the middle: (horizontal offset, z).
    let top = |u: f64| (u * cp - h[2] * sp, c[2] + u * sp + h[2] * cp);
    let n = ((2.0 * h[0] * sp).abs() / RAMP_STEP_M)
        .ceil()
        .clamp(1.0, MAX_RAMP_BLOCKS) as usize;
    let vertical_thickness = 2.0 * h[2] / cp.abs().max(1e-6);
    (0..n)
        .map(|k| {
            let u0 = -h[0] + 2.0 * h[0] * k as f64 / n as f64;
            let u1 = -h[0] + 2.0 * h[0] * (k + 1) as f64 / n as f64;
            let ((s0, z0), (s1, z1)) = (top(u0), top(u1));
            let (s_mid, z_top) = ((s0 + s1) / 2.0, (z0 + z1) / 2.0);
            BoxSpec {
                center_m: [
                    c[0] + dx * s_mid,
                    c[1] + dy * s_mid,
                    z_top - vertical_thickness / 2.0,
                ],
                half_extents_m: [(s1 - s0).abs() / 2.0, h[1], vertical_thickness / 2.0],
                yaw_deg: yaw.to_degrees(),
            }
        })
        .collect()
}

fn box_of(p: &scanner::BoxPart) -> BoxSpec {
    BoxSpec {
        center_m: p.center_m.to_array().map(f64::from),
        half_extents_m: p.half_extents_m.to_array().map(f64::from),
        yaw_deg: f64::from(p.yaw_rad).to_degrees(),
    }
}

/// The number of steps of staircase `stairs[i]`.
fn stair_steps(b: &Building, name: &str) -> usize {
    name.strip_prefix("stairs[")
        .and_then(|s| s.strip_suffix(']'))
        .and_then(|s| s.parse::<usize>().ok())
        .and_then(|i| b.stairs.get(i))
        .map(|s| s.steps as usize)
        .unwrap_or(0)
}

/// Human labels by machine name: the building's own names of walls, stairs and boxes.
fn labels(b: &Building) -> HashMap<String, String> {
    let mut m = HashMap::new();
    for (i, w) in b.walls.iter().enumerate() {
        if !w.name.is_empty() {
            m.insert(format!("walls[{i}]"), w.name.clone());
        }
    }
    for (i, s) in b.stairs.iter().enumerate() {
        if !s.name.is_empty() {
            m.insert(format!("stairs[{i}]"), s.name.clone());
        }
    }
    for (i, f) in b.boxes.iter().enumerate() {
        if !f.name.is_empty() {
            m.insert(format!("boxes[{i}]"), f.name.clone());
        }
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ramp_becomes_blocks_following_its_slope_within_a_centimetre() {
        let text = r#"
            [floor]
            min_m = [0.0, 0.0]
            max_m = [12.0, 6.0]
            [ceiling]
            height_m = 3.0
            [[ramps]]
            start_m = [2.0, 3.0]
            direction_deg = 0.0
            length_m = 8.0
            width_m = 3.0
            rise_m = 1.0
        "#;
        let b = Building::from_toml_str(text, Path::new("ramp.toml")).expect("valid");
        let spec = WorldSpec::from_building(&b).expect("world");
        let blocks: Vec<&FixedBox> = spec.fixed.iter().filter(|f| f.name == "ramps[0]").collect();
        assert!(blocks.len() >= 100, "{} blocks", blocks.len());
        for f in blocks {
            assert_eq!(f.class, EntityClass::Ramp);
            let g = &f.geometry;
            let top = g.center_m[2] + g.half_extents_m[2];
            // The slope's height at the block's middle (the foot is at x = 2).
            let slope = (g.center_m[0] - 2.0) / 8.0;
            assert!(
                (top - slope).abs() < 0.011,
                "block at x {}: top {top}, slope {slope}",
                g.center_m[0]
            );
            assert!(g.yaw_deg.abs() < 1e-9 && (g.half_extents_m[1] - 1.5).abs() < 1e-6);
        }
    }
}
