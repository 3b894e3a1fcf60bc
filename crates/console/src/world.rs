//! The world a console shows and simulates: a [`WorldSpec`] (from a building or a semantic
//! map) with the semantic net's relations, served as a GLB (interop's glTF export, with the
//! robot at its start) and as a JSON list of entities for the page's hover labels.

use crate::error::Result;
use cloud::EntityClass;
use semantic::{Relation, RelationType, SemanticMap};
use serde::Serialize;
use sim::{RobotModel, StartPose, WorldSpec};
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// The world of a console session.
#[derive(Debug, Clone, PartialEq)]
pub struct ConsoleWorld {
    /// What is simulated.
    pub spec: WorldSpec,
    /// The semantic map's relations between entity ids (none for a building).
    pub relations: Vec<Relation>,
}

impl ConsoleWorld {
    /// The world of a building description (ground truth; no relations besides the ones the
    /// world implies).
    pub fn from_building(building: &scanner::Building) -> Result<ConsoleWorld> {
        Ok(ConsoleWorld {
            spec: WorldSpec::from_building(building)?,
            relations: vec![],
        })
    }

    /// The world of a semantic map, with its relations.
    pub fn from_semantic_map(map: &SemanticMap) -> Result<ConsoleWorld> {
        Ok(ConsoleWorld {
            spec: WorldSpec::from_semantic_map(map)?,
            relations: map.relations.clone(),
        })
    }

    /// The world of a semantic map file (`semantic_map.json`); errors name the file.
    pub fn from_semantic_map_file(path: &Path) -> Result<ConsoleWorld> {
        let map = SemanticMap::load(path)?;
        let spec = WorldSpec::from_semantic_map(&map)
            .map_err(|e| e.in_source(&path.display().to_string()))?;
        Ok(ConsoleWorld {
            spec,
            relations: map.relations,
        })
    }

    /// The map's relations and the ones the world implies (a door `connected_via_joint` to
    /// its wall, a free space `available_inside` its wall, a door `available_inside` its free
    /// space), each once, ordered.
    pub fn all_relations(&self) -> Vec<Relation> {
        let mut set: BTreeSet<Relation> = self.relations.iter().copied().collect();
        for d in &self.spec.doors {
            set.insert(Relation {
                kind: RelationType::ConnectedViaJoint,
                a: d.entity,
                b: d.wall,
            });
        }
        for f in &self.spec.free_spaces {
            if let Some(w) = f.wall {
                set.insert(Relation {
                    kind: RelationType::AvailableInside,
                    a: f.entity,
                    b: w,
                });
            }
            if let Some(d) = f.door {
                set.insert(Relation {
                    kind: RelationType::AvailableInside,
                    a: d,
                    b: f.entity,
                });
            }
        }
        set.into_iter().collect()
    }

    /// The robot's entity id in a simulation of this world: the one after the largest.
    pub fn robot_entity(&self) -> u32 {
        self.spec.entities().iter().map(|e| e.id).max().unwrap_or(0) + 1
    }

    /// The world and the robot at `start` as GLB bytes (interop's export).
    pub fn glb(&self, robot: &RobotModel, start: StartPose) -> Result<Vec<u8>> {
        let options = interop::ExportOptions {
            robot: Some((robot, start)),
            relations: &self.relations,
        };
        Ok(interop::export_world(
            &self.spec,
            interop::ExportFormat::Glb,
            &options,
        )?)
    }

    /// `/api/world.json`: every entity (id, class, name, label, relations) and the robot.
    pub fn entities_json(&self, robot_name: &str, robot_model: &str) -> String {
        let mut relations: BTreeMap<u32, Vec<RelationJson>> = BTreeMap::new();
        for r in self.all_relations() {
            for (this, other, role) in [(r.a, r.b, "subject"), (r.b, r.a, "object")] {
                relations.entry(this).or_default().push(RelationJson {
                    kind: r.kind.name(),
                    other,
                    role,
                });
            }
        }
        let mut entities: Vec<EntityJson> = self
            .spec
            .entities()
            .into_iter()
            .map(|e| EntityJson {
                relations: relations.remove(&e.id).unwrap_or_default(),
                id: e.id,
                class: e.class.name(),
                name: e.name,
                label: e.label,
            })
            .collect();
        let robot = self.robot_entity();
        entities.push(EntityJson {
            id: robot,
            class: EntityClass::Robot.name(),
            name: robot_name.to_string(),
            label: robot_model.to_string(),
            relations: vec![],
        });
        let doc = WorldJson {
            name: &self.spec.name,
            robot,
            entities,
        };
        serde_json::to_string(&doc).unwrap_or_else(|_| "{}".into())
    }
}

#[derive(Serialize)]
struct RelationJson {
    #[serde(rename = "type")]
    kind: &'static str,
    other: u32,
    role: &'static str,
}

#[derive(Serialize)]
struct EntityJson {
    id: u32,
    class: &'static str,
    name: String,
    label: String,
    relations: Vec<RelationJson>,
}

#[derive(Serialize)]
struct WorldJson<'a> {
    name: &'a str,
    robot: u32,
    entities: Vec<EntityJson>,
}
