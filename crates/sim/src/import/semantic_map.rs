//! Building a [`WorldSpec`] from a semantic map (`semantic::SemanticMap`, the map built from
//! scans): walls from their solid boxes, the floor from the parts where it was seen (and under
//! each ramp and an apron before its foot), lintels and ceiling as fixed boxes; ramps as blocks
//! following their slope; each door
//! leaf hinged to the wall it is `connected_via_joint` to; free spaces linked to their door and
//! wall through `available_inside`; stairs from their step and landing boxes.
//!
//! Semantic entities have ids but no names: each gets `<class>_<id>` (e.g. `door_13`,
//! `free_space_for_door_14`, `stairs_21`), usable in scenarios like the ids themselves.

use super::ramp::wedge_blocks;
use super::ImportConfig;
use crate::error::Result;
use crate::spec::{
    BoxSpec, DoorSpec, FixedBox, FreeSpaceSpec, HingeEnd, OpeningSense, StairsSpec, StepSpec,
    WorldSpec,
};
use cloud::EntityClass;
use semantic::{OrientedBox, RelationType, SemanticMap};
use std::path::Path;

/// The name a semantic entity gets in the simulation.
pub(crate) fn semantic_name(class: EntityClass, id: u32) -> String {
    format!("{}_{id}", class.name())
}

fn box_of(b: &OrientedBox) -> BoxSpec {
    BoxSpec {
        center_m: b.center_m,
        half_extents_m: b.size_m.map(|s| s / 2.0),
        yaw_deg: b.yaw_deg,
    }
}

/// The floor under a ramp (rising along its box's x axis) and `apron_m` beyond its foot: a
/// slab 0.2 m thick whose top is at `top_z_m` (the floor's).
fn ramp_apron(ramp: &BoxSpec, top_z_m: f64, apron_m: f64) -> BoxSpec {
    let (s, c) = ramp.yaw_deg.to_radians().sin_cos();
    let thickness = 0.2;
    BoxSpec {
        center_m: [
            ramp.center_m[0] - c * apron_m / 2.0,
            ramp.center_m[1] - s * apron_m / 2.0,
            top_z_m - thickness / 2.0,
        ],
        half_extents_m: [
            ramp.half_extents_m[0] + apron_m / 2.0,
            ramp.half_extents_m[1],
            thickness / 2.0,
        ],
        yaw_deg: ramp.yaw_deg,
    }
}

impl WorldSpec {
    /// The world of a semantic map, with default door properties.
    pub fn from_semantic_map(map: &SemanticMap) -> Result<WorldSpec> {
        WorldSpec::from_semantic_map_with(map, &ImportConfig::default())
    }

    /// The world of a semantic map file (`semantic_map.json`, see `semantic::SemanticMap::load`),
    /// with default door properties; every error names the file.
    pub fn from_semantic_map_file(path: &Path) -> Result<WorldSpec> {
        WorldSpec::from_semantic_map_file_with(path, &ImportConfig::default())
    }

    /// The world of a semantic map file; every error names the file.
    pub fn from_semantic_map_file_with(path: &Path, cfg: &ImportConfig) -> Result<WorldSpec> {
        let map = SemanticMap::load(path)?;
        WorldSpec::from_semantic_map_with(&map, cfg)
            .map_err(|e| e.in_source(&path.display().to_string()))
    }

    /// The world of a semantic map. A door not `connected_via_joint` to a wall is an error
    /// ([`crate::SimError::DoorWithoutWall`]), as are degenerate boxes.
    pub fn from_semantic_map_with(map: &SemanticMap, cfg: &ImportConfig) -> Result<WorldSpec> {
        cfg.validate()?;
        let related = |kind: RelationType, a: u32, class: EntityClass| {
            map.relations_of(kind)
                .filter(|r| r.a == a)
                .find(|r| map.entity(r.b).is_some_and(|e| e.class == class))
                .map(|r| r.b)
        };
        let mut spec = WorldSpec {
            name: "semantic map".into(),
            ..Default::default()
        };
        for e in &map.entities {
            let fixed = |class: EntityClass, b: &OrientedBox| FixedBox {
                entity: e.id,
                class,
                name: semantic_name(class, e.id),
                label: String::new(),
                geometry: box_of(b),
            };
            match e.class {
                // Obstacles, columns and beams are fixed bodies: the robot collides with what
                // the scans saw (and passes under a beam above its height).
                // The floor where it was seen (version 3), else its box.
                EntityClass::Floor => match &e.floor {
                    Some(f) if !f.parts.is_empty() => {
                        for b in &f.parts {
                            spec.fixed.push(fixed(EntityClass::Floor, b));
                        }
                    }
                    _ => spec.fixed.push(fixed(EntityClass::Floor, &e.geometry)),
                },
                EntityClass::Ceiling
                | EntityClass::WallAboveDoor
                | EntityClass::Obstacle
                | EntityClass::Column
                | EntityClass::Beam => spec.fixed.push(fixed(e.class, &e.geometry)),
                // A ramp rises along its box's x axis: blocks following its slope, on the
                // floor, which runs under it and `ramp_apron_m` beyond its foot.
                EntityClass::Ramp => {
                    let ramp = box_of(&e.geometry);
                    for geometry in wedge_blocks(&ramp) {
                        spec.fixed.push(FixedBox {
                            geometry,
                            ..fixed(EntityClass::Ramp, &e.geometry)
                        });
                    }
                    if let Some(floor) = map.entities.iter().find(|f| f.class == EntityClass::Floor)
                    {
                        let top = floor.geometry.center_m[2] + floor.geometry.size_m[2] / 2.0;
                        spec.fixed.push(FixedBox {
                            entity: floor.id,
                            class: EntityClass::Floor,
                            name: semantic_name(EntityClass::Floor, floor.id),
                            label: String::new(),
                            geometry: ramp_apron(&ramp, top, cfg.ramp_apron_m),
                        });
                    }
                }
                EntityClass::Wall => match &e.wall {
                    Some(w) if !w.solid_boxes.is_empty() => {
                        for b in &w.solid_boxes {
                            spec.fixed.push(fixed(EntityClass::Wall, b));
                        }
                    }
                    _ => spec.fixed.push(fixed(EntityClass::Wall, &e.geometry)),
                },
                EntityClass::Door => {
                    let Some(d) = &e.door else { continue };
                    let mut leaf = box_of(&e.geometry);
                    leaf.half_extents_m[1] = leaf.half_extents_m[1].max(0.01);
                    let yaw = leaf.yaw_deg.to_radians();
                    let along = (d.hinge_m[0] - leaf.center_m[0]) * yaw.cos()
                        + (d.hinge_m[1] - leaf.center_m[1]) * yaw.sin();
                    let hinge_end = if along < 0.0 {
                        HingeEnd::Start
                    } else {
                        HingeEnd::End
                    };
                    let opens = if d.opens_counter_clockwise() {
                        OpeningSense::Ccw
                    } else {
                        OpeningSense::Cw
                    };
                    let max_deg = cfg.door_max_deg.max(d.observed_open_deg);
                    spec.doors.push(DoorSpec {
                        entity: e.id,
                        name: semantic_name(EntityClass::Door, e.id),
                        label: String::new(),
                        wall: related(RelationType::ConnectedViaJoint, e.id, EntityClass::Wall)
                            .unwrap_or(0),
                        leaf,
                        hinge_m: [d.hinge_m[0], d.hinge_m[1]],
                        hinge_end,
                        opens,
                        min_deg: 0.0,
                        max_deg,
                        initial_deg: d.observed_open_deg.clamp(0.0, max_deg),
                        mass_kg: cfg.door_mass_kg,
                        damping_per_s: cfg.door_damping_per_s,
                        hinge_friction_nm: cfg.door_hinge_friction_nm,
                        break_force_n: (cfg.door_break_force_n > 0.0)
                            .then_some(cfg.door_break_force_n),
                    });
                }
                EntityClass::FreeSpaceForDoor => {
                    let door = map
                        .relations_of(RelationType::AvailableInside)
                        .filter(|r| r.b == e.id)
                        .find(|r| {
                            map.entity(r.a)
                                .is_some_and(|x| x.class == EntityClass::Door)
                        })
                        .map(|r| r.a);
                    spec.free_spaces.push(FreeSpaceSpec {
                        entity: e.id,
                        name: semantic_name(EntityClass::FreeSpaceForDoor, e.id),
                        door,
                        wall: related(RelationType::AvailableInside, e.id, EntityClass::Wall),
                        geometry: box_of(&e.geometry),
                    });
                }
                EntityClass::Stairs => {
                    let Some(s) = &e.stairs else { continue };
                    spec.stairs.push(StairsSpec {
                        entity: e.id,
                        name: semantic_name(EntityClass::Stairs, e.id),
                        label: String::new(),
                        steps: s
                            .steps
                            .iter()
                            .enumerate()
                            .map(|(i, b)| StepSpec {
                                index: i as u32,
                                geometry: box_of(b),
                            })
                            .collect(),
                        landing: s.landing.as_ref().map(box_of),
                    });
                }
                // A semantic map holds none of these (see `semantic::MAP_CLASSES`).
                EntityClass::Unknown | EntityClass::Furniture | EntityClass::Robot => {}
            }
        }
        spec.validate()?;
        Ok(spec)
    }
}

#[cfg(test)]
mod obstacle_tests {
    use super::*;
    use crate::{run_scenario, RobotModel, Scenario};

    /// A version 2 map: the door map (version 1, read as 2) with an obstacle pushed into its
    /// wall, a column and a beam above the robot's way.
    fn map_with_obstacles() -> SemanticMap {
        let mut map = SemanticMap::from_json_str(
            &fixtures::door_wall_map_json("right", 0.0, fixtures::DOOR_RELATIONS),
            Path::new("map.json"),
        )
        .expect("door map");
        let info = |z: [f64; 2]| semantic::ObstacleInfo {
            z_range_m: z,
            clearance_m: z[0],
            hull_m: Vec::new(),
            fill: 1.0,
        };
        let entity = |id: u32, class: EntityClass, c: [f64; 3], s: [f64; 3]| semantic::Entity {
            id,
            class,
            geometry: OrientedBox {
                center_m: c,
                size_m: s,
                yaw_deg: 0.0,
            },
            support_points: 100,
            confidence: 0.9,
            rules: Vec::new(),
            wall: None,
            door: None,
            opening: None,
            stairs: None,
            obstacle: Some(info([c[2] - s[2] / 2.0, c[2] + s[2] / 2.0])),
            floor: None,
        };
        // Through the wall at x = 6 (y 1 .. 2), a column, and a beam over the way at 2.2 m.
        map.entities.push(entity(
            7,
            EntityClass::Obstacle,
            [6.0, 1.5, 0.75],
            [1.0, 1.0, 1.5],
        ));
        map.entities.push(entity(
            8,
            EntityClass::Column,
            [3.0, 1.8, 1.25],
            [0.4, 0.4, 2.5],
        ));
        map.entities.push(entity(
            9,
            EntityClass::Beam,
            [3.5, 0.0, 2.35],
            [0.3, 4.4, 0.3],
        ));
        map
    }

    /// Regression (issue #15): a map whose obstacle overlaps a wall still builds a world, and
    /// the robot drives under the beam into the door it pushes open.
    #[test]
    fn a_map_whose_obstacle_overlaps_a_wall_builds_a_world() {
        let map = map_with_obstacles();
        let text = map.to_json_string();
        let map = SemanticMap::from_json_str(&text, Path::new("v2.json")).expect("v2 map");
        let spec = WorldSpec::from_semantic_map(&map).expect("world");
        for (id, class) in [
            (7, EntityClass::Obstacle),
            (8, EntityClass::Column),
            (9, EntityClass::Beam),
        ] {
            assert!(
                spec.fixed
                    .iter()
                    .any(|f| f.entity == id && f.class == class),
                "{} {id} is a fixed body",
                class.name()
            );
        }
        let sc = Scenario::from_toml_str(
            r#"
            robot = "pioneer3at"
            time_limit_s = 9.0
            start = { x_m = 2.0, y_m = 0.05, yaw_deg = 0.0 }
            [[velocity]]
            from_s = 0.3
            to_s = 9.0
            linear_mps = 0.5
            [rules]
            open_door = "5"
            "#,
            "test scenario",
        )
        .expect("scenario");
        let model = RobotModel::builtin(&sc.robot).expect("robot");
        let o = run_scenario(&spec, &sc, &model).expect("runs");
        assert!(o.verdict.passed, "{:?}", o.verdict);
    }
}
