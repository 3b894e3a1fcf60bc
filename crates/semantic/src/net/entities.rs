//! The entities of the semantic net: the slabs, walls, openings (free space, lintel, leaf)
//! and staircases as oriented boxes with their class's geometry, confidence and rules.

use super::Net;
use crate::map::{
    DoorInfo, Entity, FloorInfo, HingeEdge, OpeningInfo, OrientedBox, RelationType, StairsInfo,
    SwingSide, WallInfo,
};
use cloud::EntityClass;
use glam::DVec2;

/// A wall's solid part beside an opening must be longer than this to get a box.
const MIN_SOLID_M: f64 = 0.01;
/// An opening gets a lintel entity where the wall rises more than this above it.
const MIN_LINTEL_M: f64 = 0.02;
/// A wall seen from one side only (thickness assumed) has its confidence scaled by this.
const ONE_FACE_CONFIDENCE: f64 = 0.85;

fn xy(v: DVec2) -> [f64; 2] {
    v.to_array()
}

/// An entity without id, support or class section.
fn blank(class: EntityClass, geometry: OrientedBox, confidence: f64, rules: Vec<String>) -> Entity {
    Entity {
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
        obstacle: None,
        floor: None,
    }
}

impl Net<'_> {
    /// The box of a floor or ceiling slab: footprint `ext` (min, max in the frame turned by
    /// `slab_yaw`), its top at `z_top`.
    fn slab(&self, ext: ([f64; 2], [f64; 2]), z_top: f64) -> OrientedBox {
        let d = self.d;
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
    }

    /// The floor and the ceiling, where both their height and their extent were found.
    pub(super) fn add_slabs(&mut self) {
        let d = self.d;
        let footprint = d.floor_footprint.as_ref();
        if let (Some((z, n)), Some((f, ext))) = (
            d.levels.floor,
            footprint.and_then(|f| f.extent().map(|e| (f, e))),
        ) {
            let coverage = if f.seen_cells > 0 {
                (f.covered_cells as f64 / f.seen_cells as f64).min(1.0)
            } else {
                0.0
            };
            let rules = vec![
                format!(
                    "lowest horizontal peak of the z histogram: {n} points at z {z:.3} m (tilt levelled: {:.2} deg)",
                    d.levels.tilt_deg
                ),
                format!(
                    "seen floor: {} parts covering {:.0} % of the {:.1} m2 seen (cells of {:.2} m, gaps closed)",
                    f.parts.len(),
                    100.0 * coverage,
                    f.seen_cells as f64 * f.cell_m * f.cell_m,
                    f.cell_m
                ),
            ];
            let mut floor = blank(EntityClass::Floor, self.slab(ext, z), 1.0, rules);
            floor.floor = Some(FloorInfo {
                parts: f.parts.iter().map(|&p| self.slab(p, z)).collect(),
                coverage,
            });
            self.ids.floor = self.add(floor);
        }
        if let (Some((z, n)), Some(ext)) = (d.levels.ceiling, d.ceiling_extent) {
            let rules = vec![format!(
                "highest horizontal peak of the z histogram: {n} points at z {z:.3} m"
            )];
            let mut b = self.slab(ext, z + d.slab_thickness);
            b.center_m[2] = z + d.slab_thickness / 2.0;
            self.ids.ceiling = self.add(blank(EntityClass::Ceiling, b, 1.0, rules));
        }
    }

    /// The walls, each with its solid boxes: the wall minus its openings.
    pub(super) fn add_walls(&mut self) {
        let d = self.d;
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
                if a - s > MIN_SOLID_M {
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
                w.coverage * if w.measured { 1.0 } else { ONE_FACE_CONFIDENCE },
                w.rules.clone(),
            );
            e.wall = Some(WallInfo {
                segment_m: [xy(w.start()), xy(w.end())],
                thickness_m: w.thickness,
                thickness_measured: w.measured,
                z_range_m: z,
                solid_boxes: solid,
            });
            let id = self.add(e);
            self.ids.walls.push(id);
        }
    }

    /// Per opening: the free space for door, the lintel (where the wall rises above the
    /// opening) and the leaf (where one was found), and their relations.
    pub(super) fn add_openings(&mut self) {
        let d = self.d;
        for (o, leaf) in d.openings.iter().zip(&d.leaves) {
            let w = &d.walls[o.wall];
            let wall_id = self.ids.walls[o.wall];
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
            let free_id = self.add(free);
            let mut lintel_id = 0;
            if w.z_range.1 - o.top_z > MIN_LINTEL_M {
                lintel_id = self.add(blank(
                    EntityClass::WallAboveDoor,
                    OrientedBox::along(a, b, w.thickness, [o.top_z, w.z_range.1]),
                    o.confidence,
                    vec![format!(
                        "wall face above the opening from z {:.2} m: the lintel",
                        o.top_z
                    )],
                ));
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
                door_id = self.add(e);
            }
            self.ids.openings.push((free_id, lintel_id, door_id));
            self.relate(RelationType::AvailableInside, free_id, wall_id);
            if lintel_id != 0 {
                self.relate(RelationType::AvailableInside, lintel_id, wall_id);
                self.relate(RelationType::Above, lintel_id, free_id);
                self.relate(RelationType::Under, free_id, lintel_id);
            }
            if door_id != 0 {
                self.relate(RelationType::AvailableInside, door_id, free_id);
                self.relate(RelationType::ConnectedViaJoint, door_id, wall_id);
                if lintel_id != 0 {
                    self.relate(RelationType::Above, lintel_id, door_id);
                    self.relate(RelationType::Under, door_id, lintel_id);
                }
            }
        }
    }

    /// The staircases, each a box per step and the landing, and their relations to the floor.
    pub(super) fn add_stairs(&mut self) {
        let d = self.d;
        let floor_z = d.levels.floor_ref_m;
        for s in &d.stairs {
            let step_box = |k: u32| {
                let (a, b) = s.step_range(k);
                let top = floor_z + s.base + s.rise * k.min(s.steps) as f64;
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
                    [floor_z, floor_z + s.base + s.rise * s.steps as f64],
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
                start_m: [s.start.x, s.start.y, floor_z + s.base],
                landing_m: s.landing,
                steps,
                landing,
            });
            let id = self.add(e);
            self.ids.stairs.push(id);
            let floor = self.ids.floor;
            if floor != 0 {
                self.relate(RelationType::AvailableInside, id, floor);
                self.relate(RelationType::Above, id, floor);
                self.relate(RelationType::Under, floor, id);
            }
        }
    }
}
