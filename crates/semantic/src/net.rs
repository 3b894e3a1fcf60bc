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
//!   `wall_above_door above door` (and `under`).

use crate::doors::Leaf;
use crate::error::{check_range, Result};
use crate::floor_ceiling::Levels;
use crate::map::{
    DoorInfo, Entity, EntityClass, HingeEdge, OpeningInfo, OrientedBox, Relation, RelationType,
    SemanticMap, StairsInfo, SwingSide, WallInfo,
};
use crate::openings::Opening;
use crate::points::undirected_angle_deg;
use crate::stairs::Staircase;
use crate::walls::WallFit;
use glam::{DMat4, DVec2};
use serde::{Deserialize, Serialize};

/// Configuration of the semantic net's relations.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct NetConfig {
    /// Walls within this angle are parallel (or, from 90 degrees, orthogonal).
    pub relation_angle_deg: f64,
    /// Walls whose bottoms and tops agree within this are of equal height.
    pub equal_height_m: f64,
}

impl Default for NetConfig {
    fn default() -> Self {
        NetConfig {
            relation_angle_deg: 3.0,
            equal_height_m: 0.05,
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
        )
    }
}

/// Everything the identification stages found.
pub(crate) struct Detections {
    pub levels: Levels,
    /// Floor and ceiling footprints: (min, max) in a frame turned by `slab_yaw`.
    pub floor_extent: Option<([f64; 2], [f64; 2])>,
    pub ceiling_extent: Option<([f64; 2], [f64; 2])>,
    pub slab_yaw: f64,
    pub slab_thickness: f64,
    pub walls: Vec<WallFit>,
    pub openings: Vec<Opening>,
    pub leaves: Vec<Option<Leaf>>,
    pub stairs: Vec<Staircase>,
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

fn xy(v: DVec2) -> [f64; 2] {
    v.to_array()
}

/// Builds the map's entities and relations (support counts are filled in by the labelling).
pub(crate) fn assemble(d: &Detections, c: &NetConfig) -> (SemanticMap, Ids) {
    let mut map = SemanticMap {
        input_from_map: DMat4::from(d.levels.map_from_input.inverse())
            .transpose()
            .to_cols_array(),
        ..SemanticMap::default()
    };
    let mut ids = Ids::default();
    let mut next = 1u32;
    let mut add = |map: &mut SemanticMap, e: Entity| -> u32 {
        let id = next;
        next += 1;
        map.entities.push(Entity { id, ..e });
        id
    };
    let blank =
        |class: EntityClass, geometry: OrientedBox, confidence: f64, rules: Vec<String>| Entity {
            id: 0,
            class,
            geometry,
            support_points: 0,
            confidence: confidence.clamp(0.0, 1.0),
            rules,
            wall: None,
            door: None,
            opening: None,
            stairs: None,
        };
    let slab = |ext: ([f64; 2], [f64; 2]), z_top: f64| {
        let (lo, hi) = ext;
        let (s, co) = d.slab_yaw.sin_cos();
        let (u, v) = ((lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0);
        OrientedBox {
            center_m: [
                co * u - s * v,
                s * u + co * v,
                z_top - d.slab_thickness / 2.0,
            ],
            size_m: [hi[0] - lo[0], hi[1] - lo[1], d.slab_thickness],
            yaw_deg: d.slab_yaw.to_degrees(),
        }
    };
    if let (Some((z, n)), Some(ext)) = (d.levels.floor, d.floor_extent) {
        let rules = vec![format!(
            "lowest horizontal peak of the z histogram: {n} points at z {z:.3} m (tilt levelled: {:.2} deg)",
            d.levels.tilt_deg
        )];
        ids.floor = add(
            &mut map,
            blank(EntityClass::Floor, slab(ext, z), 1.0, rules),
        );
    }
    if let (Some((z, n)), Some(ext)) = (d.levels.ceiling, d.ceiling_extent) {
        let rules = vec![format!(
            "highest horizontal peak of the z histogram: {n} points at z {z:.3} m"
        )];
        let mut b = slab(ext, z + d.slab_thickness);
        b.center_m[2] = z + d.slab_thickness / 2.0;
        ids.ceiling = add(&mut map, blank(EntityClass::Ceiling, b, 1.0, rules));
    }
    for (wi, w) in d.walls.iter().enumerate() {
        let z = [w.z_range.0, w.z_range.1];
        let mut cuts: Vec<(f64, f64)> = d
            .openings
            .iter()
            .filter(|o| o.wall == wi)
            .map(|o| (o.s0, o.s1))
            .collect();
        cuts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut solid = Vec::new();
        let mut s = 0.0;
        for (a, b) in cuts.iter().copied().chain([(w.length, w.length)]) {
            if a - s > 0.01 {
                solid.push(OrientedBox::along(
                    xy(w.line.at(s)),
                    xy(w.line.at(a)),
                    w.thickness,
                    z,
                ));
            }
            s = s.max(b);
        }
        let mut e = blank(
            EntityClass::Wall,
            OrientedBox::along(xy(w.start()), xy(w.end()), w.thickness, z),
            w.coverage * if w.measured { 1.0 } else { 0.85 },
            w.rules.clone(),
        );
        e.wall = Some(WallInfo {
            segment_m: [xy(w.start()), xy(w.end())],
            thickness_m: w.thickness,
            thickness_measured: w.measured,
            z_range_m: z,
            solid_boxes: solid,
        });
        ids.walls.push(add(&mut map, e));
    }
    for (o, leaf) in d.openings.iter().zip(&d.leaves) {
        let w = &d.walls[o.wall];
        let wall_id = ids.walls[o.wall];
        let (a, b) = (xy(w.line.at(o.s0)), xy(w.line.at(o.s1)));
        let floor_z = w.z_range.0;
        let mut free = blank(
            EntityClass::FreeSpaceForDoor,
            OrientedBox::along(a, b, w.thickness, [floor_z, o.top_z]),
            o.confidence,
            o.rules.clone(),
        );
        free.opening = Some(OpeningInfo {
            offset_m: o.s0,
            width_m: o.s1 - o.s0,
            height_m: o.top_z - floor_z,
        });
        let free_id = add(&mut map, free);
        let mut lintel_id = 0;
        if w.z_range.1 - o.top_z > 0.02 {
            lintel_id = add(
                &mut map,
                blank(
                    EntityClass::WallAboveDoor,
                    OrientedBox::along(a, b, w.thickness, [o.top_z, w.z_range.1]),
                    o.confidence,
                    vec![format!(
                        "wall face above the opening from z {:.2} m: the lintel",
                        o.top_z
                    )],
                ),
            );
        }
        let mut door_id = 0;
        if let Some(l) = leaf {
            let hinge = if l.hinge_start { a } else { b };
            let mut e = blank(
                EntityClass::Door,
                OrientedBox::along(a, b, d.leaf_thickness, [floor_z, o.top_z]),
                l.coverage,
                l.rules.clone(),
            );
            e.door = Some(DoorInfo {
                hinge_m: [hinge[0], hinge[1], floor_z],
                hinge_axis: [0.0, 0.0, 1.0],
                hinge_edge: if l.hinge_start {
                    HingeEdge::Start
                } else {
                    HingeEdge::End
                },
                swing: if l.swing_left {
                    SwingSide::Left
                } else {
                    SwingSide::Right
                },
                observed_open_deg: l.open_deg,
            });
            door_id = add(&mut map, e);
        }
        ids.openings.push((free_id, lintel_id, door_id));
        let rel = &mut map.relations;
        let mut push = |kind, a, b| rel.push(Relation { kind, a, b });
        push(RelationType::AvailableInside, free_id, wall_id);
        if lintel_id != 0 {
            push(RelationType::AvailableInside, lintel_id, wall_id);
            push(RelationType::Above, lintel_id, free_id);
            push(RelationType::Under, free_id, lintel_id);
        }
        if door_id != 0 {
            push(RelationType::AvailableInside, door_id, free_id);
            push(RelationType::ConnectedViaJoint, door_id, wall_id);
            if lintel_id != 0 {
                push(RelationType::Above, lintel_id, door_id);
                push(RelationType::Under, door_id, lintel_id);
            }
        }
    }
    let floor_z = d.levels.floor_ref_m;
    for s in &d.stairs {
        let step_box = |k: u32| {
            let (a, b) = s.step_range(k);
            let top = floor_z + s.rise * k.min(s.steps) as f64;
            OrientedBox::along(
                xy(s.start + s.dir * a),
                xy(s.start + s.dir * b),
                s.width,
                [floor_z, top],
            )
        };
        let steps: Vec<OrientedBox> = (1..=s.steps).map(step_box).collect();
        let landing = (s.landing > 0.0).then(|| step_box(s.steps + 1));
        let total = s.steps as f64 * s.run + s.landing;
        let mut e = blank(
            EntityClass::Stairs,
            OrientedBox::along(
                xy(s.start),
                xy(s.start + s.dir * total),
                s.width,
                [floor_z, floor_z + s.rise * s.steps as f64],
            ),
            s.confidence,
            s.rules.clone(),
        );
        e.stairs = Some(StairsInfo {
            step_count: s.steps,
            rise_m: s.rise,
            run_m: s.run,
            width_m: s.width,
            direction_deg: s.dir.y.atan2(s.dir.x).to_degrees(),
            start_m: [s.start.x, s.start.y, floor_z],
            landing_m: s.landing,
            steps,
            landing,
        });
        let id = add(&mut map, e);
        ids.stairs.push(id);
        if ids.floor != 0 {
            map.relations.push(Relation {
                kind: RelationType::AvailableInside,
                a: id,
                b: ids.floor,
            });
            map.relations.push(Relation {
                kind: RelationType::Above,
                a: id,
                b: ids.floor,
            });
            map.relations.push(Relation {
                kind: RelationType::Under,
                a: ids.floor,
                b: id,
            });
        }
    }
    if ids.floor != 0 && ids.ceiling != 0 {
        map.relations.push(Relation {
            kind: RelationType::Above,
            a: ids.ceiling,
            b: ids.floor,
        });
        map.relations.push(Relation {
            kind: RelationType::Under,
            a: ids.floor,
            b: ids.ceiling,
        });
    }
    for (i, wi) in d.walls.iter().enumerate() {
        for (j, wj) in d.walls.iter().enumerate().skip(i + 1) {
            let (a, b) = (ids.walls[i], ids.walls[j]);
            let angle = undirected_angle_deg(wi.line.dir, wj.line.dir);
            if angle <= c.relation_angle_deg {
                map.relations.push(Relation {
                    kind: RelationType::Parallel,
                    a,
                    b,
                });
            } else if angle >= 90.0 - c.relation_angle_deg {
                map.relations.push(Relation {
                    kind: RelationType::Orthogonal,
                    a,
                    b,
                });
            }
            if (wi.z_range.0 - wj.z_range.0).abs() <= c.equal_height_m
                && (wi.z_range.1 - wj.z_range.1).abs() <= c.equal_height_m
            {
                map.relations.push(Relation {
                    kind: RelationType::EqualHeight,
                    a,
                    b,
                });
            }
        }
    }
    (map, ids)
}
