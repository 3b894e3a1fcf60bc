//! Building a [`WorldSpec`] from a ground-truth [`scanner::Building`]: entity ids and names are
//! those of [`scanner::BuildingGeometry`] (`floor`, `walls[4]`, `walls[4].doors[2].lintel`,
//! `walls[4].doors[2].leaf`, `stairs[0]`, `boxes[1]`); each door opening also gets a free-space
//! entity `walls[4].doors[2].free_space` with the next free ids.

use crate::error::{check_range, Result, SimError};
use crate::spec::{
    BoxSpec, DoorSpec, EntityClass, FixedBox, FreeSpaceSpec, HingeEnd, OpeningSense, StairsSpec,
    StepSpec, WorldSpec,
};
use scanner::{Building, BuildingGeometry, Hinge, Swing};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// How doors and free spaces are made from a building.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ImportConfig {
    /// Door leaf mass (kg).
    pub door_mass_kg: f64,
    /// Door leaf angular damping (1/s).
    pub door_damping_per_s: f64,
    /// Hinge dry friction (N m).
    pub door_hinge_friction_nm: f64,
    /// Hinge force that breaks a door off (N); 0 = unbreakable.
    pub door_break_force_n: f64,
    /// Upper opening limit (degrees); a door initially open wider keeps its angle as the limit.
    pub door_max_deg: f64,
    /// How far the free space reaches out of the wall on each side (m).
    pub free_space_margin_m: f64,
}

impl Default for ImportConfig {
    fn default() -> Self {
        ImportConfig {
            door_mass_kg: 20.0,
            door_damping_per_s: 1.0,
            door_hinge_friction_nm: 2.0,
            door_break_force_n: 800.0,
            door_max_deg: 100.0,
            free_space_margin_m: 0.4,
        }
    }
}

impl ImportConfig {
    /// Checks every field's range (the door's physics and the free space's margin).
    pub(crate) fn validate(&self) -> Result<()> {
        let el = "import config";
        check_range(
            el,
            "door_mass_kg",
            self.door_mass_kg,
            0.1,
            1.0e4,
            "0.1 kg to 10 t",
        )?;
        check_range(
            el,
            "door_max_deg",
            self.door_max_deg,
            1.0,
            180.0,
            "1 to 180 degrees",
        )?;
        check_range(
            el,
            "free_space_margin_m",
            self.free_space_margin_m,
            0.0,
            10.0,
            "0 to 10 m",
        )?;
        check_range(
            el,
            "door_break_force_n",
            self.door_break_force_n,
            0.0,
            1.0e9,
            "0 (unbreakable) or a force in N",
        )?;
        Ok(())
    }
}

impl WorldSpec {
    /// The ground-truth world of a (validated) building, with default door properties.
    pub fn from_building(b: &Building) -> Result<WorldSpec> {
        WorldSpec::from_building_with(b, &ImportConfig::default())
    }

    /// The ground-truth world of a (validated) building.
    pub fn from_building_with(b: &Building, cfg: &ImportConfig) -> Result<WorldSpec> {
        cfg.validate()?;
        let geometry = BuildingGeometry::new(b);
        let ids: HashMap<&str, u32> = geometry
            .entities()
            .iter()
            .map(|e| (e.name.as_str(), e.id))
            .collect();
        let labels = labels(b);
        let mut spec = WorldSpec {
            name: b.name.clone(),
            ..Default::default()
        };
        let mut stairs: HashMap<u32, StairsSpec> = HashMap::new();
        for part in geometry.parts() {
            let id = part.label.entity;
            let Some(ent) = geometry.entities().get(id as usize - 1) else {
                continue;
            };
            let class = match part.label.class {
                cloud::SurfaceClass::Floor => EntityClass::Floor,
                cloud::SurfaceClass::Ceiling => EntityClass::Ceiling,
                cloud::SurfaceClass::Wall => EntityClass::Wall,
                cloud::SurfaceClass::WallAboveDoor => EntityClass::WallAboveDoor,
                cloud::SurfaceClass::Furniture => EntityClass::Furniture,
                cloud::SurfaceClass::Stairs => {
                    let s = stairs.entry(id).or_insert_with(|| StairsSpec {
                        entity: id,
                        name: ent.name.clone(),
                        label: labels.get(&ent.name).cloned().unwrap_or_default(),
                        steps: vec![],
                        landing: None,
                    });
                    let steps = stair_steps(b, &ent.name);
                    if s.steps.len() < steps {
                        let index = s.steps.len() as u32;
                        s.steps.push(StepSpec {
                            index,
                            geometry: box_of(part),
                        });
                    } else {
                        s.landing = Some(box_of(part));
                    }
                    continue;
                }
                // Door leaves are made from the building below (closed pose, hinge).
                cloud::SurfaceClass::Door | cloud::SurfaceClass::Unknown => continue,
            };
            spec.fixed.push(FixedBox {
                entity: id,
                class,
                name: ent.name.clone(),
                label: labels.get(&ent.name).cloned().unwrap_or_default(),
                geometry: box_of(part),
            });
        }
        let mut stairs: Vec<StairsSpec> = stairs.into_values().collect();
        stairs.sort_by_key(|s| s.entity);
        spec.stairs = stairs;
        let mut next_id = geometry.entities().iter().map(|e| e.id).max().unwrap_or(0) + 1;
        for (i, w) in b.walls.iter().enumerate() {
            let wall_name = format!("walls[{i}]");
            let wall_id = *ids
                .get(wall_name.as_str())
                .ok_or_else(|| SimError::Invalid {
                    element: wall_name.clone(),
                    msg: "the building geometry has no entity for this wall".into(),
                })?;
            let len =
                ((w.end_m[0] - w.start_m[0]).powi(2) + (w.end_m[1] - w.start_m[1]).powi(2)).sqrt();
            if len <= 1e-9 {
                continue;
            }
            let u = [
                (w.end_m[0] - w.start_m[0]) / len,
                (w.end_m[1] - w.start_m[1]) / len,
            ];
            let yaw = u[1].atan2(u[0]);
            let at = |s: f64| [w.start_m[0] + u[0] * s, w.start_m[1] + u[1] * s];
            for (j, d) in w.doors.iter().enumerate() {
                let base = format!("walls[{i}].doors[{j}]");
                let label = if w.name.is_empty() {
                    String::new()
                } else {
                    format!("{}, door {j}", w.name)
                };
                let door_id = match &d.leaf {
                    Some(leaf) => {
                        let name = format!("{base}.leaf");
                        let Some(&id) = ids.get(name.as_str()) else {
                            continue;
                        };
                        let (hinge_s, closed_yaw, sense) = match (leaf.hinge, leaf.swing) {
                            (Hinge::Start, Swing::Left) => (d.offset_m, yaw, OpeningSense::Ccw),
                            (Hinge::Start, Swing::Right) => (d.offset_m, yaw, OpeningSense::Cw),
                            (Hinge::End, Swing::Left) => (
                                d.offset_m + d.width_m,
                                yaw + std::f64::consts::PI,
                                OpeningSense::Cw,
                            ),
                            (Hinge::End, Swing::Right) => (
                                d.offset_m + d.width_m,
                                yaw + std::f64::consts::PI,
                                OpeningSense::Ccw,
                            ),
                        };
                        let leaf_len = (d.width_m - 0.01).max(0.01);
                        let leaf_h = (d.height_m - 0.01).max(0.01);
                        let h = at(hinge_s);
                        let max_deg = cfg.door_max_deg.max(leaf.open_deg);
                        spec.doors.push(DoorSpec {
                            entity: id,
                            name,
                            label: label.clone(),
                            wall: wall_id,
                            leaf: BoxSpec {
                                center_m: [
                                    h[0] + closed_yaw.cos() * leaf_len / 2.0,
                                    h[1] + closed_yaw.sin() * leaf_len / 2.0,
                                    0.005 + leaf_h / 2.0,
                                ],
                                half_extents_m: [
                                    leaf_len / 2.0,
                                    leaf.thickness_m / 2.0,
                                    leaf_h / 2.0,
                                ],
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
                            break_force_n: (cfg.door_break_force_n > 0.0)
                                .then_some(cfg.door_break_force_n),
                        });
                        Some(id)
                    }
                    None => None,
                };
                let mid = at(d.offset_m + d.width_m / 2.0);
                spec.free_spaces.push(FreeSpaceSpec {
                    entity: next_id,
                    name: format!("{base}.free_space"),
                    door: door_id,
                    wall: Some(wall_id),
                    geometry: BoxSpec {
                        center_m: [mid[0], mid[1], d.height_m / 2.0],
                        half_extents_m: [
                            d.width_m / 2.0,
                            w.thickness_m / 2.0 + cfg.free_space_margin_m,
                            d.height_m / 2.0,
                        ],
                        yaw_deg: yaw.to_degrees(),
                    },
                });
                next_id += 1;
            }
        }
        spec.validate()?;
        Ok(spec)
    }
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
