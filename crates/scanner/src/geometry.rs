//! The building as solid geometry: every element becomes one or more boxes rotated about z
//! (a ramp's slab also pitched about its own y axis), each carrying the ground-truth label of
//! its entity; a BVH (parry3d `Compound`) answers rays.

use crate::building::{Building, Hinge, Material, Ramp, Swing, Wall};
use cloud::{EntityClass, Label};
use glam::{Quat, Vec3};
use parry3d::math::Pose;
use parry3d::query::Ray;
use parry3d::shape::{CompositeShapeRef, Compound, SharedShape};
use serde::Serialize;

/// One box of the building: centre, half extents along its own axes, yaw about z, pitch,
/// label. Its rotation is `Rz(yaw_rad) * Ry(-pitch_rad)`: yawed, then its own +x end raised by
/// `pitch_rad` (only ramps are pitched; every other box has `pitch_rad == 0`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BoxPart {
    /// Centre in world coordinates (metres).
    pub center_m: Vec3,
    /// Half extents along the box's own axes.
    pub half_extents_m: Vec3,
    /// Rotation about z (radians).
    pub yaw_rad: f32,
    /// How far the box's own +x end is raised (radians, about its own y axis after the yaw);
    /// non-zero only for ramps.
    pub pitch_rad: f32,
    /// The ground-truth label of every point on this box.
    pub label: Label,
    /// What its surface is made of.
    pub material: Material,
}

/// A semantic entity of the building (ground truth): id, class and a name for people.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TruthEntity {
    /// Entity id, as stored in point labels (never 0).
    pub id: u32,
    /// Its class.
    pub class: EntityClass,
    /// A name, e.g. `walls[2]` or `walls[2].doors[0].leaf`.
    pub name: String,
}

/// The building as labelled boxes with a ray-cast acceleration structure.
pub struct BuildingGeometry {
    parts: Vec<BoxPart>,
    entities: Vec<TruthEntity>,
    compound: Compound,
}

impl BuildingGeometry {
    /// Builds the geometry of a (validated) building.
    pub fn new(b: &Building) -> BuildingGeometry {
        let mut g = Builder::default();
        let f = &b.floor;
        let (min, max) = (f.min_m, f.max_m);
        let floor = g.entity(EntityClass::Floor, "floor".into());
        g.aabb(
            floor,
            [min[0], min[1], -f.thickness_m],
            [max[0], max[1], 0.0],
        );
        let c = &b.ceiling;
        let ceiling = g.entity(EntityClass::Ceiling, "ceiling".into());
        g.aabb(
            ceiling,
            [min[0], min[1], c.height_m],
            [max[0], max[1], c.height_m + c.thickness_m],
        );
        for (i, w) in b.walls.iter().enumerate() {
            add_wall(&mut g, w, b.wall_height_m(w), i);
        }
        for (i, s) in b.stairs.iter().enumerate() {
            let id = g.entity(EntityClass::Stairs, format!("stairs[{i}]"));
            let yaw = s.direction_deg.to_radians();
            let dir = [yaw.cos(), yaw.sin()];
            for k in 0..s.steps {
                let top = s.base_m + (k + 1) as f64 * s.rise_m;
                let along = (k as f64 + 0.5) * s.run_m;
                let c = [
                    s.start_m[0] + dir[0] * along,
                    s.start_m[1] + dir[1] * along,
                    top / 2.0,
                ];
                g.oriented(id, c, [s.run_m / 2.0, s.width_m / 2.0, top / 2.0], yaw);
            }
            if s.landing_m > 0.0 {
                let top = s.base_m + s.steps as f64 * s.rise_m;
                let along = s.steps as f64 * s.run_m + s.landing_m / 2.0;
                let c = [
                    s.start_m[0] + dir[0] * along,
                    s.start_m[1] + dir[1] * along,
                    top / 2.0,
                ];
                g.oriented(id, c, [s.landing_m / 2.0, s.width_m / 2.0, top / 2.0], yaw);
            }
        }
        for (i, f) in b.boxes.iter().enumerate() {
            let id = g.entity(f.class, format!("boxes[{i}]"));
            let h = [f.size_m[0] / 2.0, f.size_m[1] / 2.0, f.size_m[2] / 2.0];
            g.material = f.material;
            g.oriented(id, f.center_m, h, f.yaw_deg.to_radians());
            g.material = Material::Matte;
        }
        for (i, r) in b.ramps.iter().enumerate() {
            add_ramp(&mut g, r, i);
        }
        g.finish()
    }

    /// The boxes, in build order.
    pub fn parts(&self) -> &[BoxPart] {
        &self.parts
    }

    /// The entities, by ascending id.
    pub fn entities(&self) -> &[TruthEntity] {
        &self.entities
    }

    /// The nearest hit of a ray within `max_toi` (in units of `dir`'s length): time of impact and label.
    pub fn cast_ray(&self, origin: Vec3, dir: Vec3, max_toi: f32) -> Option<(f32, Label)> {
        let ray = Ray::new(origin, dir);
        let (part, toi) = CompositeShapeRef(&self.compound).cast_local_ray(&ray, max_toi, true)?;
        Some((toi, self.parts.get(part as usize)?.label))
    }

    /// The nearest hit like [`Self::cast_ray`], with the surface's outward unit normal and the
    /// index of the box hit (into [`Self::parts`]: its label and material). With `solid` false
    /// a ray starting inside a box hits that box's far side (a beam going on through glass).
    pub fn cast_ray_with_normal(
        &self,
        origin: Vec3,
        dir: Vec3,
        max_toi: f32,
        solid: bool,
    ) -> Option<(f32, Vec3, usize)> {
        let ray = Ray::new(origin, dir);
        let (part, toi) = CompositeShapeRef(&self.compound).cast_local_ray(&ray, max_toi, solid)?;
        // The normal of the box's face nearest the hit, in the box's own frame (much cheaper
        // than the BVH's normal query).
        let p = self.parts.get(part as usize)?;
        let rotation = p.rotation();
        let local = rotation.inverse() * (origin + dir * toi - p.center_m);
        let depth = p.half_extents_m - local.abs();
        let axis = if depth.x <= depth.y && depth.x <= depth.z {
            Vec3::X
        } else if depth.y <= depth.z {
            Vec3::Y
        } else {
            Vec3::Z
        };
        let normal = rotation * (axis * local.dot(axis).signum());
        Some((toi, normal, part as usize))
    }

    /// The entity whose solid contains `point`, if any (e.g. a scan pose inside a wall).
    pub fn entity_containing(&self, point: Vec3) -> Option<&TruthEntity> {
        let i = self
            .compound
            .shapes()
            .iter()
            .position(|(p, s)| s.contains_point(p, point))?;
        let id = self.parts.get(i)?.label.entity;
        self.entities.get(id as usize - 1)
    }

    /// Distance from `point` to the nearest box of entity `entity` (infinite if it has none).
    pub fn distance_to_entity(&self, point: Vec3, entity: u32) -> f32 {
        self.parts
            .iter()
            .zip(self.compound.shapes())
            .filter(|(p, _)| p.label.entity == entity)
            .map(|(_, (pose, shape))| shape.distance_to_point(pose, point, true))
            .fold(f32::INFINITY, f32::min)
    }
}

/// A ramp: one slab pitched so that its top runs from the foot on the floor to the head at
/// `rise_m`. Class `ramp`: it is walked and driven on like the floor, and it is neither an
/// obstacle nor a staircase.
fn add_ramp(g: &mut Builder, r: &Ramp, i: usize) {
    let id = g.entity(EntityClass::Ramp, format!("ramps[{i}]"));
    let pitch = r.pitch_rad();
    let dir = r.direction();
    let slope_len = r.length_m.hypot(r.rise_m);
    // The middle of the top face, then half the thickness down along the top's normal.
    let (sp, cp) = pitch.sin_cos();
    let normal = [-sp * dir[0], -sp * dir[1], cp];
    let half_t = r.thickness_m / 2.0;
    let top_mid = [
        r.start_m[0] + dir[0] * r.length_m / 2.0,
        r.start_m[1] + dir[1] * r.length_m / 2.0,
        r.rise_m / 2.0,
    ];
    let center = [
        top_mid[0] - normal[0] * half_t,
        top_mid[1] - normal[1] * half_t,
        top_mid[2] - normal[2] * half_t,
    ];
    let label = g.label(id);
    g.parts.push(BoxPart {
        center_m: Vec3::new(center[0] as f32, center[1] as f32, center[2] as f32),
        half_extents_m: Vec3::new(
            (slope_len / 2.0) as f32,
            (r.width_m / 2.0) as f32,
            half_t as f32,
        ),
        yaw_rad: r.direction_deg.to_radians() as f32,
        pitch_rad: pitch as f32,
        label,
        material: Material::Matte,
    });
}

impl BoxPart {
    /// The box's rotation: yaw about z, then its own +x end raised by the pitch.
    pub fn rotation(&self) -> Quat {
        Quat::from_rotation_z(self.yaw_rad) * Quat::from_rotation_y(-self.pitch_rad)
    }
}

fn add_wall(g: &mut Builder, w: &Wall, height: f64, i: usize) {
    let len = w.length_m();
    let u = [
        (w.end_m[0] - w.start_m[0]) / len,
        (w.end_m[1] - w.start_m[1]) / len,
    ];
    let yaw = u[1].atan2(u[0]);
    let at = |s: f64| [w.start_m[0] + u[0] * s, w.start_m[1] + u[1] * s];
    let half_t = w.thickness_m / 2.0;
    let wall = g.entity(EntityClass::Wall, format!("walls[{i}]"));
    g.material = w.material;
    let mut doors: Vec<_> = w.doors.iter().enumerate().collect();
    doors.sort_by(|a, b| a.1.offset_m.total_cmp(&b.1.offset_m));
    let piece = |g: &mut Builder, id: u32, s0: f64, s1: f64, z0: f64, z1: f64| {
        if s1 - s0 > 1e-4 && z1 - z0 > 1e-4 {
            let m = at((s0 + s1) / 2.0);
            g.oriented(
                id,
                [m[0], m[1], (z0 + z1) / 2.0],
                [(s1 - s0) / 2.0, half_t, (z1 - z0) / 2.0],
                yaw,
            );
        }
    };
    let mut s = 0.0;
    for &(_, d) in &doors {
        piece(g, wall, s, d.offset_m, 0.0, height);
        s = d.offset_m + d.width_m;
    }
    piece(g, wall, s, len, 0.0, height);
    for (j, d) in doors {
        if d.height_m < height - 1e-4 {
            let lintel = g.entity(
                EntityClass::WallAboveDoor,
                format!("walls[{i}].doors[{j}].lintel"),
            );
            piece(
                g,
                lintel,
                d.offset_m,
                d.offset_m + d.width_m,
                d.height_m,
                height,
            );
        }
        let Some(leaf) = &d.leaf else { continue };
        let id = g.entity(EntityClass::Door, format!("walls[{i}].doors[{j}].leaf"));
        let (hinge_s, closed_yaw, sign) = match (leaf.hinge, leaf.swing) {
            (Hinge::Start, Swing::Left) => (d.offset_m, yaw, 1.0),
            (Hinge::Start, Swing::Right) => (d.offset_m, yaw, -1.0),
            (Hinge::End, Swing::Left) => (d.offset_m + d.width_m, yaw + std::f64::consts::PI, -1.0),
            (Hinge::End, Swing::Right) => (d.offset_m + d.width_m, yaw + std::f64::consts::PI, 1.0),
        };
        let leaf_yaw = closed_yaw + sign * leaf.open_deg.to_radians();
        let leaf_len = (d.width_m - 0.01).max(0.01);
        let h = at(hinge_s);
        let mid = [
            h[0] + leaf_yaw.cos() * leaf_len / 2.0,
            h[1] + leaf_yaw.sin() * leaf_len / 2.0,
        ];
        let leaf_h = (d.height_m - 0.01).max(0.01);
        g.material = leaf.material;
        g.oriented(
            id,
            [mid[0], mid[1], 0.005 + leaf_h / 2.0],
            [leaf_len / 2.0, leaf.thickness_m / 2.0, leaf_h / 2.0],
            leaf_yaw,
        );
        g.material = w.material;
    }
    g.material = Material::Matte;
}

#[derive(Default)]
struct Builder {
    parts: Vec<BoxPart>,
    entities: Vec<TruthEntity>,
    /// The material of the boxes added next.
    material: Material,
}

impl Builder {
    fn entity(&mut self, class: EntityClass, name: String) -> u32 {
        let id = self.entities.len() as u32 + 1;
        self.entities.push(TruthEntity { id, class, name });
        id
    }

    fn label(&self, id: u32) -> Label {
        let class = self
            .entities
            .get(id as usize - 1)
            .map(|e| e.class)
            .unwrap_or_default();
        Label { entity: id, class }
    }

    fn aabb(&mut self, id: u32, lo: [f64; 3], hi: [f64; 3]) {
        let c = [
            (lo[0] + hi[0]) / 2.0,
            (lo[1] + hi[1]) / 2.0,
            (lo[2] + hi[2]) / 2.0,
        ];
        let h = [
            (hi[0] - lo[0]) / 2.0,
            (hi[1] - lo[1]) / 2.0,
            (hi[2] - lo[2]) / 2.0,
        ];
        self.oriented(id, c, h, 0.0);
    }

    fn oriented(&mut self, id: u32, center: [f64; 3], half: [f64; 3], yaw: f64) {
        let label = self.label(id);
        self.parts.push(BoxPart {
            center_m: Vec3::new(center[0] as f32, center[1] as f32, center[2] as f32),
            half_extents_m: Vec3::new(half[0] as f32, half[1] as f32, half[2] as f32),
            yaw_rad: yaw as f32,
            pitch_rad: 0.0,
            label,
            material: self.material,
        });
    }

    fn finish(self) -> BuildingGeometry {
        let shapes = self
            .parts
            .iter()
            .map(|p| {
                let pose = Pose::from_parts(p.center_m, p.rotation());
                (
                    pose,
                    SharedShape::cuboid(p.half_extents_m.x, p.half_extents_m.y, p.half_extents_m.z),
                )
            })
            .collect();
        BuildingGeometry {
            parts: self.parts,
            entities: self.entities,
            compound: Compound::new(shapes),
        }
    }
}
