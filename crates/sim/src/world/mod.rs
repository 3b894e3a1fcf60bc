//! The physics world: rapier3d bodies, colliders and joints built from a [`WorldSpec`], every
//! collider tagged (user data) with its entity id, class and part. Single-threaded and
//! deterministic: the same inputs give bit-identical states.

mod config;
pub(crate) mod door;
pub(crate) mod robot;
pub(crate) mod tags;

pub use config::WorldConfig;

use crate::error::Result;
use crate::events::EntityRef;
use crate::model::{RobotModel, StartPose};
use crate::spec::{BoxSpec, EntityInfo, WorldSpec};
use cloud::EntityClass;
use door::{spawn_door, DoorBody};
use glam::{Quat, Vec3};
use rapier3d::prelude::{
    ColliderBuilder, ColliderHandle, PhysicsWorld, Pose, RigidBodyBuilder, RigidBodyHandle,
};
use robot::Robot;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use tags::{groups, Part, Tag, G_DOOR, G_ROBOT, G_SENSOR, G_STATIC};

/// A door's free-space sensor in the world.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(crate) struct FreeSpaceBody {
    pub entity: u32,
    pub door: Option<u32>,
    pub collider: ColliderHandle,
    /// Centre (x, y) and the wall normal (local +y), to tell the sides apart.
    pub center_xy: [f64; 2],
    pub normal_xy: [f64; 2],
}

/// A staircase in the world.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(crate) struct StairsInfo {
    pub entity: u32,
    /// Number of steps (the landing's index).
    pub steps: u16,
    pub has_landing: bool,
}

/// The simulated world: physics plus the semantic bookkeeping of every body.
#[derive(Serialize, Deserialize)]
pub struct World {
    pub(crate) physics: PhysicsWorld,
    pub(crate) ground: RigidBodyHandle,
    pub(crate) entities: BTreeMap<u32, EntityInfo>,
    pub(crate) doors: Vec<DoorBody>,
    pub(crate) free_spaces: Vec<FreeSpaceBody>,
    pub(crate) stairs: Vec<StairsInfo>,
    pub(crate) robots: Vec<Robot>,
    pub(crate) steps: u64,
    pub(crate) config: WorldConfig,
}

pub(crate) fn pose_of(b: &BoxSpec) -> Pose {
    Pose::from_parts(
        Vec3::new(
            b.center_m[0] as f32,
            b.center_m[1] as f32,
            b.center_m[2] as f32,
        ),
        Quat::from_rotation_z(b.yaw_deg.to_radians() as f32),
    )
}

pub(crate) fn cuboid(b: &BoxSpec) -> ColliderBuilder {
    let h = b.half_extents_m;
    ColliderBuilder::cuboid(h[0] as f32, h[1] as f32, h[2] as f32)
}

impl World {
    /// Builds the world of a (validated) spec.
    pub fn new(spec: &WorldSpec, config: WorldConfig) -> Result<World> {
        spec.validate()?;
        config.validate()?;
        let mut physics = PhysicsWorld::new();
        physics.gravity = Vec3::new(0.0, 0.0, -config.gravity_mps2 as f32);
        physics.integration_parameters.dt = config.dt_secs as f32;
        physics.integration_parameters.num_solver_iterations = config.solver_iterations;
        physics.integration_parameters.max_ccd_substeps = config.ccd_substeps;
        let ground = physics.bodies.insert(RigidBodyBuilder::fixed());
        let friction = config.static_friction as f32;
        let fixed_groups = groups(G_STATIC, G_ROBOT | G_DOOR);
        let add_fixed = |physics: &mut PhysicsWorld, b: &BoxSpec, tag: Tag| {
            physics.colliders.insert(
                cuboid(b)
                    .position(pose_of(b))
                    .friction(friction)
                    .collision_groups(fixed_groups)
                    .user_data(tag.pack()),
            );
        };
        for f in &spec.fixed {
            let tag = Tag {
                entity: f.entity,
                class: f.class,
                part: Part::Static,
                index: 0,
            };
            add_fixed(&mut physics, &f.geometry, tag);
        }
        let mut stairs = vec![];
        for s in &spec.stairs {
            for step in &s.steps {
                let tag = Tag {
                    entity: s.entity,
                    class: EntityClass::Stairs,
                    part: Part::Step,
                    index: step.index as u16,
                };
                add_fixed(&mut physics, &step.geometry, tag);
            }
            if let Some(l) = &s.landing {
                let tag = Tag {
                    entity: s.entity,
                    class: EntityClass::Stairs,
                    part: Part::Landing,
                    index: s.steps.len() as u16,
                };
                add_fixed(&mut physics, l, tag);
            }
            stairs.push(StairsInfo {
                entity: s.entity,
                steps: s.steps.len() as u16,
                has_landing: s.landing.is_some(),
            });
        }
        let mut free_spaces = vec![];
        for f in &spec.free_spaces {
            let tag = Tag {
                entity: f.entity,
                class: EntityClass::FreeSpaceForDoor,
                part: Part::FreeSpace,
                index: 0,
            };
            let collider = physics.colliders.insert(
                cuboid(&f.geometry)
                    .position(pose_of(&f.geometry))
                    .sensor(true)
                    .collision_groups(groups(G_SENSOR, G_ROBOT))
                    .user_data(tag.pack()),
            );
            let yaw = f.geometry.yaw_deg.to_radians();
            free_spaces.push(FreeSpaceBody {
                entity: f.entity,
                door: f.door,
                collider,
                center_xy: [f.geometry.center_m[0], f.geometry.center_m[1]],
                normal_xy: [-yaw.sin(), yaw.cos()],
            });
        }
        let doors = spec
            .doors
            .iter()
            .map(|d| spawn_door(&mut physics, ground, d, friction))
            .collect();
        let entities = spec.entities().into_iter().map(|e| (e.id, e)).collect();
        Ok(World {
            physics,
            ground,
            entities,
            doors,
            free_spaces,
            stairs,
            robots: vec![],
            steps: 0,
            config,
        })
    }

    /// Puts a robot into the world; returns its index. Its entity id is the next free id.
    pub fn add_robot(
        &mut self,
        model: &RobotModel,
        start: &StartPose,
        name: &str,
    ) -> Result<usize> {
        model.validate()?;
        start.validate()?;
        let id = self.entities.keys().next_back().copied().unwrap_or(0) + 1;
        let robot = Robot::spawn(&mut self.physics, model, start, id)?;
        self.entities.insert(
            id,
            EntityInfo {
                id,
                class: EntityClass::Robot,
                name: name.to_string(),
                label: model.name.clone(),
            },
        );
        self.robots.push(robot);
        Ok(self.robots.len() - 1)
    }

    /// Simulated time (s).
    pub fn time_s(&self) -> f64 {
        self.steps as f64 * self.config.dt_secs
    }

    /// The fixed time step (s).
    pub fn dt_secs(&self) -> f64 {
        self.config.dt_secs
    }

    /// The entity with this id.
    pub fn entity(&self, id: u32) -> Option<&EntityInfo> {
        self.entities.get(&id)
    }

    /// Every entity (robots included), by ascending id.
    pub fn entities(&self) -> impl Iterator<Item = &EntityInfo> {
        self.entities.values()
    }

    /// The number of robots.
    pub fn robot_count(&self) -> usize {
        self.robots.len()
    }

    /// Robot `i`'s entity id.
    pub fn robot_entity(&self, i: usize) -> Option<u32> {
        self.robots.get(i).map(|r| r.entity)
    }

    /// A door's current opening angle (degrees, 0 = closed), by door entity id.
    pub fn door_angle_deg(&self, entity: u32) -> Option<f64> {
        let d = self.doors.iter().find(|d| d.entity == entity)?;
        Some(d.angle_deg(&self.physics))
    }

    /// Whether a door's hinge is still intact.
    pub fn door_attached(&self, entity: u32) -> Option<bool> {
        let d = self.doors.iter().find(|d| d.entity == entity)?;
        Some(d.joint.is_some())
    }

    /// Advances the physics by one step.
    pub(crate) fn step_physics(&mut self) {
        self.physics.step();
        self.steps += 1;
    }

    /// The tag of a collider (static if it has none).
    pub(crate) fn tag(&self, c: ColliderHandle) -> Option<Tag> {
        self.physics
            .colliders
            .get(c)
            .map(|c| Tag::unpack(c.user_data))
    }
}

/// References for entity ids (unknown ids are skipped).
pub(crate) fn entity_refs(world: &World, ids: &[u32]) -> Vec<EntityRef> {
    ids.iter()
        .filter_map(|id| world.entity(*id))
        .map(EntityRef::from)
        .collect()
}
