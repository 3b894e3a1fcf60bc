//! glTF 2.0 binary (GLB): the world for viewers, one node per entity.
//!
//! * **Frame**: glTF's, +Y up: semsim's (x, y, z) is glTF's (x, z, -y) (a rotation, so the
//!   floor plan's x stays x and "up" is +Y). Every position, mesh and translation is converted;
//!   the root node `semsim world` has no transform.
//! * **Entities**: a node each, named `<class> <id>` (`wall 12`, `stairs 30`), with one mesh of
//!   all its boxes (a staircase's steps and landing together), 4 vertices a face with the
//!   face's normal, triangle lists, u16 indices (u32 past 65535 vertices); its `extras` are
//!   `{"entity": id, "class": "wall", "name": "walls[4]", "label": "...", "relations":
//!   [{"type": "connected_via_joint", "other": 12, "role": "subject"}]}` (`role` says whether
//!   this entity is the relation's `a`, the subject, or its `b`, the object).
//! * **Materials**: one per class, coloured as semsim's renders (`baseColorFactor` in linear
//!   RGB); door free spaces translucent (`alphaMode` BLEND).
//! * **Doors**: the node's origin (`translation`) is the hinge point (at the leaf centre's
//!   height) and its mesh the closed leaf relative to it; the hinge axis is the node's local
//!   +Y (up), so rotating the node about its +Y by `opening_sign` x the opening angle swings the
//!   door (three.js: `node.rotation.y = sign * angle`). The node starts rotated by the initial
//!   opening; its `extras.hinge` holds `axis`, `opening_sign` (+1 counter-clockwise seen from
//!   above, -1 clockwise), `min_deg`, `max_deg` and `initial_deg`.
//! * **Robot** (when given): node `robot <id>` at the chassis centre (rotated by its heading),
//!   its chassis box, children `robot <id> wheel <i>` (cylinders; spin about the node's local
//!   Z, which is semsim's -y: the axle) and the arm's chain of link nodes.

mod mesh;

use super::parts::{
    by_entity, element_name, hinge_point, leaf_offset, linear_rgb, relations, static_boxes,
};
use super::robot::{arm_axis, RobotLayout};
use cloud::EntityClass;
use mesh::{glb, to_gltf, Buffer, Mesh, Placement};
use semantic::Relation;
use serde_json::{json, Map, Value};
use sim::WorldSpec;
use std::collections::HashMap;

/// Segments around a wheel.
const WHEEL_SEGMENTS: u32 = 24;
/// The opacity of door free spaces.
const FREE_SPACE_ALPHA: f64 = 0.3;

/// The document being built.
#[derive(Default)]
struct Doc {
    buffer: Buffer,
    meshes: Vec<Value>,
    nodes: Vec<Value>,
    materials: Vec<Value>,
    material_of: HashMap<EntityClass, usize>,
    relations: HashMap<u32, Vec<Value>>,
}

impl Doc {
    fn material(&mut self, class: EntityClass) -> usize {
        if let Some(m) = self.material_of.get(&class) {
            return *m;
        }
        let [r, g, b] = linear_rgb(semantic::class_color(class));
        let mut m = json!({
            "name": class.name(),
            "pbrMetallicRoughness": {
                "baseColorFactor": [r, g, b, 1.0],
                "metallicFactor": 0.0,
                "roughnessFactor": 0.9,
            },
        });
        if class == EntityClass::FreeSpaceForDoor {
            m["pbrMetallicRoughness"]["baseColorFactor"][3] = json!(FREE_SPACE_ALPHA);
            m["alphaMode"] = json!("BLEND");
            m["doubleSided"] = json!(true);
        }
        self.materials.push(m);
        self.material_of.insert(class, self.materials.len() - 1);
        self.materials.len() - 1
    }

    /// Adds a mesh of one material; returns its index.
    fn mesh(&mut self, name: &str, mesh: &Mesh, class: EntityClass) -> usize {
        let material = self.material(class);
        let primitive = self.buffer.primitive(mesh, material);
        self.meshes
            .push(json!({ "name": name, "primitives": [primitive] }));
        self.meshes.len() - 1
    }

    /// Adds a node; returns its index.
    fn node(&mut self, node: Value) -> usize {
        self.nodes.push(node);
        self.nodes.len() - 1
    }

    /// An entity's `extras`.
    fn extras(&self, id: u32, class: EntityClass, name: &str, label: &str) -> Map<String, Value> {
        let mut e = Map::new();
        e.insert("entity".into(), json!(id));
        e.insert("class".into(), json!(class.name()));
        e.insert("name".into(), json!(name));
        if !label.is_empty() {
            e.insert("label".into(), json!(label));
        }
        let rel = self.relations.get(&id).cloned().unwrap_or_default();
        e.insert("relations".into(), Value::Array(rel));
        e
    }
}

/// A rotation about glTF's axis `axis` (unit) by `angle` radians, as `[x, y, z, w]`.
fn rotation(axis: [f64; 3], angle: f64) -> [f64; 4] {
    let (s, c) = (angle / 2.0).sin_cos();
    [axis[0] * s, axis[1] * s, axis[2] * s, c]
}

/// The GLB of a (validated) world and robot.
pub(crate) fn write(spec: &WorldSpec, robot: Option<&RobotLayout>, given: &[Relation]) -> Vec<u8> {
    let mut doc = Doc::default();
    for r in relations(spec, given) {
        for (this, other, role) in [(r.a, r.b, "subject"), (r.b, r.a, "object")] {
            doc.relations.entry(this).or_default().push(json!({
                "type": r.kind.name(),
                "other": other,
                "role": role,
            }));
        }
    }
    let root = doc.node(json!({ "name": "semsim world" }));
    let mut children = vec![];
    let boxes = static_boxes(spec);
    for group in by_entity(&boxes) {
        let Some(first) = group.first() else {
            continue;
        };
        let mut m = Mesh::default();
        for b in &group {
            let g = b.geometry;
            let at = Placement {
                origin_m: g.center_m,
                yaw_rad: g.yaw_deg.to_radians(),
            };
            m.add_box(&at, g.half_extents_m);
        }
        let name = node_name(first.class, first.entity);
        let mesh = doc.mesh(&name, &m, first.class);
        let extras = doc.extras(first.entity, first.class, first.entity_name, first.label);
        children.push(doc.node(json!({ "name": name, "mesh": mesh, "extras": extras })));
    }
    for d in &spec.doors {
        let mut m = Mesh::default();
        let at = Placement {
            origin_m: leaf_offset(d),
            yaw_rad: d.leaf.yaw_deg.to_radians(),
        };
        m.add_box(&at, d.leaf.half_extents_m);
        let name = node_name(EntityClass::Door, d.entity);
        let mesh = doc.mesh(&name, &m, EntityClass::Door);
        let mut extras = doc.extras(d.entity, EntityClass::Door, &d.name, &d.label);
        let sign = d.opens.sign();
        extras.insert(
            "hinge".into(),
            json!({
                "axis": [0.0, 1.0, 0.0],
                "opening_sign": sign,
                "min_deg": d.min_deg,
                "max_deg": d.max_deg,
                "initial_deg": d.initial_deg,
                "wall": d.wall,
            }),
        );
        let mut node = json!({
            "name": name,
            "mesh": mesh,
            "translation": to_gltf(hinge_point(d)),
            "extras": extras,
        });
        if d.initial_deg != 0.0 {
            node["rotation"] = json!(rotation(
                [0.0, 1.0, 0.0],
                (sign * d.initial_deg).to_radians()
            ));
        }
        children.push(doc.node(node));
    }
    for f in &spec.free_spaces {
        let mut m = Mesh::default();
        let g = &f.geometry;
        let at = Placement {
            origin_m: g.center_m,
            yaw_rad: g.yaw_deg.to_radians(),
        };
        m.add_box(&at, g.half_extents_m);
        let class = EntityClass::FreeSpaceForDoor;
        let name = node_name(class, f.entity);
        let mesh = doc.mesh(&name, &m, class);
        let mut extras = doc.extras(f.entity, class, &f.name, "");
        extras.insert("door".into(), json!(f.door));
        extras.insert("wall".into(), json!(f.wall));
        children.push(doc.node(json!({ "name": name, "mesh": mesh, "extras": extras })));
    }
    if let Some(r) = robot {
        children.push(robot_nodes(&mut doc, r));
    }
    if !children.is_empty() {
        doc.nodes[root]["children"] = json!(children);
    }
    let mut gltf = json!({
        "asset": { "version": "2.0", "generator": "semsim interop (world export)" },
        "scene": 0,
        "scenes": [{ "name": spec.name, "nodes": [root] }],
        "nodes": doc.nodes,
        "extras": {
            "frame": "glTF +Y up: semsim (x, y, z) = glTF (x, -z, y)",
            "world": spec.name,
        },
    });
    if !doc.meshes.is_empty() {
        gltf["meshes"] = json!(doc.meshes);
        gltf["materials"] = json!(doc.materials);
        gltf["accessors"] = json!(doc.buffer.accessors);
        gltf["bufferViews"] = json!(doc.buffer.views);
        gltf["buffers"] = json!([{ "byteLength": padded(doc.buffer.bytes.len()) }]);
    }
    let text = serde_json::to_vec(&gltf).unwrap_or_default();
    glb(&text, &doc.buffer.bytes)
}

fn padded(n: usize) -> usize {
    n.div_ceil(4) * 4
}

/// `<class> <id>` (`wall 12`).
fn node_name(class: EntityClass, id: u32) -> String {
    format!("{} {id}", class.name())
}

/// The robot's node tree; returns its root node.
fn robot_nodes(doc: &mut Doc, r: &RobotLayout) -> usize {
    let m = r.model;
    let class = EntityClass::Robot;
    let mut chassis = Mesh::default();
    let at = Placement {
        origin_m: [0.0; 3],
        yaw_rad: 0.0,
    };
    chassis.add_box(&at, r.chassis_half_m());
    let name = node_name(class, r.entity);
    let mesh = doc.mesh(&r.chassis_name(), &chassis, class);
    let mut children = vec![];
    for (i, w) in m.wheels.iter().enumerate() {
        let mut wheel = Mesh::default();
        wheel.add_wheel(w.radius_m, w.width_m, WHEEL_SEGMENTS);
        let mesh = doc.mesh(&r.wheel_name(i), &wheel, class);
        children.push(doc.node(json!({
            "name": format!("{name} wheel {i}"),
            "mesh": mesh,
            "translation": to_gltf(w.position_m),
            "extras": { "entity": r.entity, "class": class.name(), "wheel": i,
                        "radius_m": w.radius_m, "driven": w.driven },
        })));
    }
    if let Some(arm) = &m.arm {
        let mut chain = vec![];
        let mut anchor = arm.mount_m;
        for (i, l) in arm.links.iter().enumerate() {
            let mut bar = Mesh::default();
            let at = Placement {
                origin_m: [l.length_m / 2.0, 0.0, 0.0],
                yaw_rad: 0.0,
            };
            bar.add_box(
                &at,
                [l.length_m / 2.0, l.thickness_m / 2.0, l.thickness_m / 2.0],
            );
            let mesh = doc.mesh(&r.link_name(i), &bar, class);
            let axis = to_gltf(arm_axis(l.axis));
            chain.push(json!({
                "name": format!("{name} arm {}", l.name),
                "mesh": mesh,
                "translation": to_gltf(anchor),
                "rotation": rotation(axis, l.angle_deg.to_radians()),
                "extras": { "entity": r.entity, "class": class.name(), "arm_link": i,
                            "joint_axis": axis, "angle_deg": l.angle_deg,
                            "min_deg": l.min_deg, "max_deg": l.max_deg },
            }));
            anchor = [l.length_m, 0.0, 0.0];
        }
        // Nest the chain: each link is the previous one's child.
        let mut child: Option<usize> = None;
        for mut node in chain.into_iter().rev() {
            if let Some(c) = child {
                node["children"] = json!([c]);
            }
            child = Some(doc.node(node));
        }
        children.extend(child);
    }
    let mut node = json!({
        "name": name,
        "mesh": mesh,
        "translation": to_gltf(r.position_m),
        "extras": { "entity": r.entity, "class": class.name(), "name": element_name(class, r.entity),
                    "model": m.name },
        "children": children,
    });
    if r.yaw_rad != 0.0 {
        node["rotation"] = json!(rotation([0.0, 1.0, 0.0], r.yaw_rad));
    }
    doc.node(node)
}
