//! The semantic net (paper, Fig. 2 and 1.3.2): the identified walls, openings, leaves, stairs,
//! floor and ceiling become entities with ids, oriented boxes and rules, and the relations
//! between them are computed from their geometry:
//!
//! - walls: `parallel` / `orthogonal` (directions within `relation_angle_deg`), `equal_height`
//!   (bottoms and tops within `equal_height_m`);
//! - `ceiling above floor`, `floor under ceiling`; `stairs above floor`, `floor under stairs`,
//!   `stairs available_inside floor`;
//! - per opening: `free_space_for_door available_inside wall`, `wall_above_door
//!   available_inside wall`, `wall_above_door above free_space_for_door` (and `under`), and
//!   for a leaf: `door available_inside free_space_for_door`, `door connected_via_joint wall`,
//!   `wall_above_door above door` (and `under`);
//! - obstacles, columns and beams (added after the labelling, see [`obstacles`]):
//!   `available_inside floor`, `above floor` (a beam: `under ceiling`), `near` a door's free
//!   space within `near_m`.

mod entities;
mod obstacles;

pub(crate) use obstacles::add_obstacles;

use crate::doors::{Leaf, Opening};
use crate::error::Result;
use crate::floor_ceiling::Levels;
use crate::map::{Entity, Relation, RelationType, SemanticMap};
use crate::points::undirected_angle_deg;
use crate::stairs::DetectedStairs;
use crate::walls::WallFit;
use cloud::check_range;
use glam::DMat4;
use serde::{Deserialize, Serialize};

/// Configuration of the semantic net's relations.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct NetConfig {
    /// Walls within this angle are parallel (or, from 90 degrees, orthogonal).
    pub relation_angle_deg: f64,
    /// Walls whose bottoms and tops agree within this are of equal height.
    pub equal_height_m: f64,
    /// An obstacle whose footprint lies within this of a door's free space is `near` it: the
    /// manoeuvring space accessibility codes keep clear in front of a door is 1.5 m deep
    /// (DIN 18040-1, ADA 404.2.4 ~1.5 m), so an obstacle within 1 m of the opening intrudes.
    pub near_m: f64,
}

impl Default for NetConfig {
    fn default() -> Self {
        NetConfig {
            relation_angle_deg: 3.0,
            equal_height_m: 0.05,
            near_m: 1.0,
        }
    }
}

impl NetConfig {
    pub(crate) fn validate(&self) -> Result<()> {
        check_range(
            "net.relation_angle_deg",
            self.relation_angle_deg,
            0.0,
            45.0,
            "within 0..45 deg",
        )?;
        check_range(
            "net.equal_height_m",
            self.equal_height_m,
            0.0,
            10.0,
            "within 0..10 m",
        )?;
        check_range("net.near_m", self.near_m, 0.0, 100.0, "within 0..100 m")?;
        Ok(())
    }
}

/// Everything the identification stages found.
pub(crate) struct Detections {
    pub levels: Levels,
    /// Where the floor was seen (rectangles in a frame turned by `slab_yaw`).
    pub floor_footprint: Option<crate::floor_ceiling::FloorFootprint>,
    /// The ceiling's extent: (min, max) in a frame turned by `slab_yaw`.
    pub ceiling_extent: Option<([f64; 2], [f64; 2])>,
    pub slab_yaw: f64,
    pub slab_thickness: f64,
    pub walls: Vec<WallFit>,
    pub openings: Vec<Opening>,
    pub leaves: Vec<Option<Leaf>>,
    pub stairs: Vec<DetectedStairs>,
    pub leaf_thickness: f64,
}

/// The entity ids given to each detection (0 = none).
#[derive(Default)]
pub(crate) struct Ids {
    pub floor: u32,
    pub ceiling: u32,
    pub walls: Vec<u32>,
    /// Per opening: free space, lintel, door.
    pub openings: Vec<(u32, u32, u32)>,
    pub stairs: Vec<u32>,
}

/// Builds the map's entities and relations (support counts are filled in by the labelling).
/// Ids are given in this order: floor, ceiling, walls, per opening its free space, lintel and
/// leaf, staircases.
pub(crate) fn assemble(d: &Detections, c: &NetConfig) -> (SemanticMap, Ids) {
    let mut net = Net::new(d);
    // Floor and ceiling slabs, over the extent of their points.
    net.add_slabs();
    // Walls, with their solid parts beside the openings.
    net.add_walls();
    // Per opening: its free space, lintel and leaf, related to each other and the wall.
    net.add_openings();
    // Staircases, on the floor.
    net.add_stairs();
    // The ceiling above the floor.
    net.relate_slabs();
    // Walls to walls: parallel, orthogonal, equal height.
    net.relate_walls(c);
    (net.map, net.ids)
}

/// The map being built, the ids given so far and the next id.
struct Net<'a> {
    d: &'a Detections,
    map: SemanticMap,
    ids: Ids,
    next: u32,
}

impl<'a> Net<'a> {
    fn new(d: &'a Detections) -> Net<'a> {
        let map = SemanticMap {
            input_from_map: DMat4::from(d.levels.map_from_input.inverse())
                .transpose()
                .to_cols_array(),
            ..SemanticMap::default()
        };
        Net {
            d,
            map,
            ids: Ids::default(),
            next: 1,
        }
    }

    /// Adds `e` with the next id, and returns the id.
    fn add(&mut self, e: Entity) -> u32 {
        let id = self.next;
        self.next += 1;
        self.map.entities.push(Entity { id, ..e });
        id
    }

    /// Adds the relation "`a` `kind` `b`".
    fn relate(&mut self, kind: RelationType, a: u32, b: u32) {
        self.map.relations.push(Relation { kind, a, b });
    }

    /// `ceiling above floor`, `floor under ceiling`.
    fn relate_slabs(&mut self) {
        let (floor, ceiling) = (self.ids.floor, self.ids.ceiling);
        if floor != 0 && ceiling != 0 {
            self.relate(RelationType::Above, ceiling, floor);
            self.relate(RelationType::Under, floor, ceiling);
        }
    }

    /// Every pair of walls: `parallel` or `orthogonal` (directions within
    /// `relation_angle_deg`), `equal_height` (bottoms and tops within `equal_height_m`).
    fn relate_walls(&mut self, c: &NetConfig) {
        let walls = &self.d.walls;
        for (i, wi) in walls.iter().enumerate() {
            for (j, wj) in walls.iter().enumerate().skip(i + 1) {
                let (a, b) = (self.ids.walls[i], self.ids.walls[j]);
                let angle = undirected_angle_deg(wi.line.dir, wj.line.dir);
                if angle <= c.relation_angle_deg {
                    self.relate(RelationType::Parallel, a, b);
                } else if angle >= 90.0 - c.relation_angle_deg {
                    self.relate(RelationType::Orthogonal, a, b);
                }
                if (wi.z_range.0 - wj.z_range.0).abs() <= c.equal_height_m
                    && (wi.z_range.1 - wj.z_range.1).abs() <= c.equal_height_m
                {
                    self.relate(RelationType::EqualHeight, a, b);
                }
            }
        }
    }
}
