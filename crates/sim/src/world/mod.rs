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
    SharedShape,
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
    /// The one collider holding every static box when they overlap too much to be colliders
    /// of their own (see [`add_statics`]); `None` when each box is its own collider.
    #[serde(default)]
    pub(crate) static_compound: Option<ColliderHandle>,
    /// The packed [`Tag`] of each of `static_compound`'s sub-shapes, by sub-shape index.
    #[serde(default)]
    pub(crate) static_tags: Vec<u128>,
}

/// How many pairs of static boxes may have overlapping bounding boxes before the boxes are
/// merged into one compound collider. Rapier's broad phase lists every overlapping pair of
/// colliders when they are added (8 bytes each; it drops static-static pairs only afterwards),
/// so thousands of boxes at one place would cost gigabytes; a compound makes no such pairs.
/// Ordinary buildings stay far below this and keep one collider per box.
pub(crate) const STATIC_PAIR_BUDGET: usize = 100_000;

/// The axis-aligned bounds (min, max) of a box, widened by `margin`.
fn bounds(b: &BoxSpec, margin: f64) -> ([f64; 3], [f64; 3]) {
    let (s, c) = b.yaw_deg.to_radians().sin_cos();
    let h = b.half_extents_m;
    let e = [
        c.abs() * h[0] + s.abs() * h[1] + margin,
        s.abs() * h[0] + c.abs() * h[1] + margin,
        h[2] + margin,
    ];
    let m = b.center_m;
    (
        [m[0] - e[0], m[1] - e[1], m[2] - e[2]],
        [m[0] + e[0], m[1] + e[1], m[2] + e[2]],
    )
}

/// Whether more than `budget` pairs of the boxes have overlapping bounds (widened by 10 cm,
/// more than rapier's margins). Sort and sweep along x; it gives up (answering yes) after
/// `64 * budget` comparisons, so it is cheap even when every box overlaps every other.
pub(crate) fn overlaps_exceed(boxes: &[&BoxSpec], budget: usize) -> bool {
    let mut b: Vec<([f64; 3], [f64; 3])> = boxes.iter().map(|b| bounds(b, 0.1)).collect();
    b.sort_by(|p, q| p.0[0].total_cmp(&q.0[0]));
    let (mut pairs, mut checks) = (0usize, 0usize);
    for (i, (lo, hi)) in b.iter().enumerate() {
        for (lo2, hi2) in &b[i + 1..] {
            if lo2[0] > hi[0] {
                break;
            }
            checks += 1;
            if lo2[1] <= hi[1] && lo[1] <= hi2[1] && lo2[2] <= hi[2] && lo[2] <= hi2[2] {
                pairs += 1;
            }
            if pairs > budget || checks > 64 * budget {
                return true;
            }
        }
    }
    false
}

/// Makes the colliders of the static boxes: one each (tagged in its user data), or, when they
/// overlap much ([`STATIC_PAIR_BUDGET`]), one compound collider with a sub-shape per box, whose
/// tags are returned by sub-shape index.
fn add_statics(
    physics: &mut PhysicsWorld,
    statics: &[(&BoxSpec, Tag)],
    friction: f32,
) -> (Option<ColliderHandle>, Vec<u128>) {
    let fixed_groups = groups(G_STATIC, G_ROBOT | G_DOOR);
    let boxes: Vec<&BoxSpec> = statics.iter().map(|(b, _)| *b).collect();
    if !overlaps_exceed(&boxes, STATIC_PAIR_BUDGET) {
        for (b, tag) in statics {
            physics.colliders.insert(
                cuboid(b)
                    .position(pose_of(b))
                    .friction(friction)
                    .collision_groups(fixed_groups)
                    .user_data(tag.pack()),
            );
        }
        return (None, vec![]);
    }
    let parts = statics
        .iter()
        .map(|(b, _)| {
            let h = b.half_extents_m;
            (
                pose_of(b),
                SharedShape::cuboid(h[0] as f32, h[1] as f32, h[2] as f32),
            )
        })
        .collect();
    let tag = Tag {
        entity: 0,
        class: EntityClass::Wall,
        part: Part::Static,
        index: 0,
    };
    let handle = physics.colliders.insert(
        ColliderBuilder::compound(parts)
            .friction(friction)
            .collision_groups(fixed_groups)
            .user_data(tag.pack()),
    );
    let tags = statics.iter().map(|(_, t)| t.pack()).collect();
    (Some(handle), tags)
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
        // The static boxes, in the order their colliders have always been made in.
        let mut statics: Vec<(&BoxSpec, Tag)> = Vec::with_capacity(spec.static_box_count());
        for f in &spec.fixed {
            let tag = Tag {
                entity: f.entity,
                class: f.class,
                part: Part::Static,
                index: 0,
            };
            statics.push((&f.geometry, tag));
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
                statics.push((&step.geometry, tag));
            }
            if let Some(l) = &s.landing {
                let tag = Tag {
                    entity: s.entity,
                    class: EntityClass::Stairs,
                    part: Part::Landing,
                    index: s.steps.len() as u16,
                };
                statics.push((l, tag));
            }
            stairs.push(StairsInfo {
                entity: s.entity,
                steps: s.steps.len() as u16,
                has_landing: s.landing.is_some(),
            });
        }
        let (static_compound, static_tags) = add_statics(&mut physics, &statics, friction);
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
            static_compound,
            static_tags,
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

    /// The tag of sub-shape `i` of the static compound (see [`add_statics`]).
    pub(crate) fn static_tag(&self, i: u32) -> Option<Tag> {
        self.static_tags.get(i as usize).map(|t| Tag::unpack(*t))
    }

    /// Whether the static boxes are one compound collider (they overlap too much to be
    /// colliders of their own).
    pub fn statics_merged(&self) -> bool {
        self.static_compound.is_some()
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
