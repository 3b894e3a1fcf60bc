//! GLB exports: the Khronos glTF validator finds no error and no warning, and the file read
//! back (with `gltf-json`) has a node per entity carrying its id, class and relations, door
//! nodes at their hinges, and meshes whose bounds are the entities' boxes.

mod export_support;

use export_support::{default_world, export, gltf_bounds, map_world, robot, to_gltf};
use gltf_json::mesh::Semantic;
use gltf_json::validation::Checked;
use gltf_json::Root;
use interop::{export_world, ExportFormat, ExportOptions};
use serde_json::Value;
use sim::{BoxSpec, WorldSpec};
use std::path::Path;
use std::process::Command;

/// Runs the validator; asserts 0 errors and 0 warnings (infos and hints are fine).
fn validate(path: &Path) {
    let Some(_) = fixtures::oracles::node_package("gltf-validator") else {
        return;
    };
    let out = fixtures::oracles::run_ok(
        Command::new("node")
            .arg(fixtures::oracles::script("validate_gltf.mjs"))
            .arg(path),
    );
    let report: Value = serde_json::from_str(&out).unwrap_or_else(|e| panic!("{e}: {out}"));
    assert_eq!(report["issues"]["numErrors"], 0, "{report:#}");
    assert_eq!(report["issues"]["numWarnings"], 0, "{report:#}");
    assert_eq!(report["mimeType"], "model/gltf-binary");
}

/// The JSON chunk of a GLB, parsed.
fn parse(glb: &[u8]) -> Root {
    assert_eq!(&glb[0..4], b"glTF");
    assert_eq!(u32::from_le_bytes(glb[4..8].try_into().unwrap()), 2);
    assert_eq!(
        u32::from_le_bytes(glb[8..12].try_into().unwrap()) as usize,
        glb.len()
    );
    let len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    assert_eq!(&glb[16..20], b"JSON");
    Root::from_slice(&glb[20..20 + len]).unwrap()
}

fn extras(node: &gltf_json::Node) -> Value {
    let raw = node.extras.as_ref().expect("node without extras");
    serde_json::from_str(raw.get()).unwrap()
}

/// The node whose extras name entity `id`.
fn node_of(root: &Root, id: u32) -> (&gltf_json::Node, Value) {
    root.nodes
        .iter()
        .filter(|n| n.extras.is_some())
        .map(|n| (n, extras(n)))
        .find(|(_, e)| e["entity"] == id && e.get("wheel").is_none() && e.get("arm_link").is_none())
        .unwrap_or_else(|| panic!("no node for entity {id}"))
}

/// The POSITION accessor's bounds of a node's mesh.
fn mesh_bounds(root: &Root, node: &gltf_json::Node) -> ([f64; 3], [f64; 3]) {
    let mesh = root.get(node.mesh.expect("node without mesh")).unwrap();
    let prim = &mesh.primitives[0];
    let acc = root
        .get(prim.attributes[&Checked::Valid(Semantic::Positions)])
        .unwrap();
    let v = |x: &Option<Value>| -> [f64; 3] {
        let a = x.as_ref().expect("POSITION without min/max");
        [0, 1, 2].map(|k| a[k].as_f64().unwrap())
    };
    (v(&acc.min), v(&acc.max))
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Rotates `v` by the unit quaternion `q` = [x, y, z, w].
fn rotate(q: [f64; 4], v: [f64; 3]) -> [f64; 3] {
    let u = [q[0], q[1], q[2]];
    let t = cross(u, v).map(|c| 2.0 * c);
    add(add(v, t.map(|c| q[3] * c)), cross(u, t))
}

fn assert_near(a: [f64; 3], b: [f64; 3], tol: f64, what: &str) {
    for k in 0..3 {
        assert!((a[k] - b[k]).abs() <= tol, "{what}: {a:?} vs {b:?}");
    }
}

/// Every entity has its node, named `<class> <id>`, with its class and name in the extras and
/// a mesh bounding its boxes; doors sit at their hinges.
fn check_entities(spec: &WorldSpec, root: &Root) {
    for e in spec.entities() {
        let (node, ex) = node_of(root, e.id);
        assert_eq!(ex["class"], e.class.name(), "{ex}");
        assert_eq!(ex["name"], e.name.as_str(), "{ex}");
        assert_eq!(
            node.name.as_deref(),
            Some(format!("{} {}", e.class.name(), e.id).as_str())
        );
        assert!(ex["relations"].is_array(), "{ex}");
        let boxes: Vec<&BoxSpec> = spec
            .fixed
            .iter()
            .filter(|f| f.entity == e.id)
            .map(|f| &f.geometry)
            .chain(
                spec.stairs
                    .iter()
                    .filter(|s| s.entity == e.id)
                    .flat_map(|s| {
                        s.steps
                            .iter()
                            .map(|st| &st.geometry)
                            .chain(s.landing.as_ref())
                    }),
            )
            .chain(
                spec.free_spaces
                    .iter()
                    .filter(|f| f.entity == e.id)
                    .map(|f| &f.geometry),
            )
            .collect();
        let (lo, hi) = mesh_bounds(root, node);
        if let Some(d) = spec.doors.iter().find(|d| d.entity == e.id) {
            let hinge = [d.hinge_m[0], d.hinge_m[1], d.leaf.center_m[2]];
            let t = node
                .translation
                .expect("a door node has a translation")
                .map(f64::from);
            assert_near(t, to_gltf(hinge), 1e-5, "door translation");
            let (elo, ehi) = gltf_bounds(&[&d.leaf], hinge);
            assert_near(lo, elo, 1e-4, "leaf bounds (min)");
            assert_near(hi, ehi, 1e-4, "leaf bounds (max)");
            assert_eq!(ex["hinge"]["opening_sign"], d.opens.sign(), "{ex}");
            assert_eq!(ex["hinge"]["axis"], serde_json::json!([0.0, 1.0, 0.0]));
            // The node is turned about +Y by the initial opening.
            let q = node.rotation.map(|r| r.0).unwrap_or([0.0, 0.0, 0.0, 1.0]);
            let angle = 2.0 * (q[1] as f64).atan2(q[3] as f64);
            let expected = (d.opens.sign() * d.initial_deg).to_radians();
            assert!((angle - expected).abs() < 1e-6, "{angle} vs {expected}");
            // So the node puts the leaf where sim's initially opened door has it: the closed
            // leaf's centre turned about the hinge by the opening, in the opening sense.
            let local = [0, 1, 2].map(|k| (lo[k] + hi[k]) / 2.0);
            let placed = add(t, rotate(q.map(f64::from), local));
            let (s, c) = expected.sin_cos();
            let r = [d.leaf.center_m[0] - hinge[0], d.leaf.center_m[1] - hinge[1]];
            let opened = [
                hinge[0] + c * r[0] - s * r[1],
                hinge[1] + s * r[0] + c * r[1],
                d.leaf.center_m[2],
            ];
            assert_near(placed, to_gltf(opened), 1e-4, "opened leaf centre");
        } else {
            assert!(!boxes.is_empty(), "entity {} has no boxes", e.id);
            assert!(node.translation.is_none());
            let (elo, ehi) = gltf_bounds(&boxes, [0.0; 3]);
            assert_near(lo, elo, 1e-4, &format!("{} bounds (min)", e.name));
            assert_near(hi, ehi, 1e-4, &format!("{} bounds (max)", e.name));
        }
    }
}

#[test]
fn the_default_world_and_a_pioneer_as_glb() {
    let spec = default_world();
    let (model, start) = robot("pioneer3at", 1.5, 0.0, 30.0);
    let options = ExportOptions {
        robot: Some((&model, start)),
        ..Default::default()
    };
    let dir = tempfile::tempdir().unwrap();
    let path = export(dir.path(), "world", &spec, ExportFormat::Glb, &options);
    validate(&path);
    let bytes = std::fs::read(&path).unwrap();
    let root = parse(&bytes);
    check_entities(&spec, &root);
    // One material per class, the free spaces' translucent.
    let names: Vec<&str> = root
        .materials
        .iter()
        .filter_map(|m| m.name.as_deref())
        .collect();
    for class in [
        "floor",
        "wall",
        "door",
        "stairs",
        "furniture",
        "free_space_for_door",
        "robot",
    ] {
        assert_eq!(
            names.iter().filter(|n| **n == class).count(),
            1,
            "{names:?}"
        );
    }
    // The robot: at its chassis centre, turned by its heading, with 4 wheel nodes.
    let id = spec.entities().iter().map(|e| e.id).max().unwrap() + 1;
    let (node, ex) = node_of(&root, id);
    assert_eq!(ex["class"], "robot");
    let z = model.chassis_height_m() + 0.002;
    let t = node.translation.unwrap().map(f64::from);
    assert_near(t, to_gltf([1.5, 0.0, z]), 1e-6, "robot translation");
    assert_eq!(node.children.as_ref().map(Vec::len), Some(4));
    // A door's relations: hinged to its wall, inside its free space.
    let d = &spec.doors[0];
    let (_, ex) = node_of(&root, d.entity);
    let rel = ex["relations"].as_array().unwrap();
    assert!(
        rel.iter()
            .any(|r| r["type"] == "connected_via_joint" && r["other"] == d.wall),
        "{ex}"
    );
}

#[test]
fn a_semantic_map_world_keeps_its_relations() {
    let (spec, relations) = map_world();
    let options = ExportOptions {
        relations: &relations,
        ..Default::default()
    };
    let bytes = export_world(&spec, ExportFormat::Glb, &options).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("map.glb");
    std::fs::write(&path, &bytes).unwrap();
    validate(&path);
    let root = parse(&bytes);
    check_entities(&spec, &root);
    let has = |id: u32, kind: &str, other: u32, role: &str| {
        let (_, ex) = node_of(&root, id);
        ex["relations"]
            .as_array()
            .unwrap()
            .iter()
            .any(|r| r["type"] == kind && r["other"] == other && r["role"] == role)
    };
    // From the map: the ceiling above the floor; and the door's.
    assert!(has(2, "above", 1, "subject"));
    assert!(has(1, "above", 2, "object"));
    assert!(has(5, "connected_via_joint", 3, "subject"));
    assert!(has(3, "connected_via_joint", 5, "object"));
    assert!(has(6, "available_inside", 3, "subject"));
    assert!(has(6, "available_inside", 5, "object"));
    // Each relation once, though the world implies the door's too.
    let (_, ex) = node_of(&root, 5);
    let joints = ex["relations"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|r| r["type"] == "connected_via_joint")
        .count();
    assert_eq!(joints, 1, "{ex}");
    // The free space is translucent.
    let (fs, _) = node_of(&root, 6);
    let mesh = root.get(fs.mesh.unwrap()).unwrap();
    let material = root.get(mesh.primitives[0].material.unwrap()).unwrap();
    assert_eq!(
        material.alpha_mode,
        Checked::Valid(gltf_json::material::AlphaMode::Blend)
    );
}

#[test]
fn an_empty_world_is_a_valid_glb_without_a_buffer() {
    let spec = WorldSpec::default();
    let bytes = export_world(&spec, ExportFormat::Glb, &ExportOptions::default()).unwrap();
    let root = parse(&bytes);
    assert!(root.buffers.is_empty() && root.meshes.is_empty());
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("empty.glb");
    std::fs::write(&path, &bytes).unwrap();
    validate(&path);
}
