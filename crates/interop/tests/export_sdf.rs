//! SDF 1.9 exports, read by SDFormat's own parser (`target/oracles/bin/sdf_check`, built
//! against libsdformat 12 by `tools/oracles/setup.sh`): no errors, every door a revolute
//! joint with its limits, the robot's wheels and arm joints.

mod export_support;

use export_support::{default_world, export, map_world, robot};
use interop::{ExportFormat, ExportOptions};
use sim::WorldSpec;
use std::collections::{BTreeSet, HashMap};
use std::path::Path;
use std::process::Command;

/// A joint as sdf_check prints it: `joint <model>/<name> <type> lower=<rad> upper=<rad>`.
#[derive(Debug)]
struct Joint {
    kind: String,
    lower: f64,
    upper: f64,
}

/// sdf_check's report: models (links, joints) and joints by `model/name`.
struct Report {
    text: String,
    models: HashMap<String, (usize, usize)>,
    joints: HashMap<String, Joint>,
}

fn sdf_check(path: &Path) -> Option<Report> {
    let program = fixtures::oracles::program("sdf_check")?;
    let text = fixtures::oracles::run_ok(Command::new(program).arg(path));
    assert!(!text.contains("error:"), "{text}");
    let mut models = HashMap::new();
    let mut joints = HashMap::new();
    for line in text.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        let value = |w: &str, key: &str| -> f64 {
            w.strip_prefix(key)
                .and_then(|v| v.parse().ok())
                .unwrap_or_else(|| panic!("{line}"))
        };
        match words.as_slice() {
            ["model", name, links, count] => {
                models.insert(
                    name.to_string(),
                    (
                        value(links, "links=") as usize,
                        value(count, "joints=") as usize,
                    ),
                );
            }
            ["joint", name, kind, lower, upper] => {
                joints.insert(
                    name.to_string(),
                    Joint {
                        kind: kind.to_string(),
                        lower: value(lower, "lower="),
                        upper: value(upper, "upper="),
                    },
                );
            }
            _ => {}
        }
    }
    Some(Report {
        text,
        models,
        joints,
    })
}

/// sdf_check prints 17 significant digits: what SDFormat read equals the spec within 1e-6.
fn close(printed: f64, exact: f64) -> bool {
    (printed - exact).abs() <= 1e-6
}

fn check_doors(spec: &WorldSpec, r: &Report) {
    for d in &spec.doors {
        let name = format!("door_{}/hinge", d.entity);
        let j = r
            .joints
            .get(&name)
            .unwrap_or_else(|| panic!("no joint {name}:\n{}", r.text));
        assert_eq!(j.kind, "revolute", "{name}");
        assert!(close(j.lower, d.min_deg.to_radians()), "{name}: {j:?}");
        assert!(close(j.upper, d.max_deg.to_radians()), "{name}: {j:?}");
        assert_eq!(r.models[&format!("door_{}", d.entity)], (1, 1));
    }
}

/// Distinct static entities (fixed boxes and staircases).
fn static_entities(spec: &WorldSpec) -> usize {
    let mut ids: BTreeSet<u32> = spec.fixed.iter().map(|f| f.entity).collect();
    ids.extend(spec.stairs.iter().map(|s| s.entity));
    ids.len()
}

#[test]
fn the_default_world_and_a_pioneer_load_in_sdformat() {
    let spec = default_world();
    let (model, start) = robot("pioneer3at", 1.5, 0.0, 0.0);
    let options = ExportOptions {
        robot: Some((&model, start)),
        ..Default::default()
    };
    let dir = tempfile::tempdir().unwrap();
    let path = export(dir.path(), "world", &spec, ExportFormat::Sdf, &options);
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("<sdf version=\"1.9\">"), "{text}");
    // The initial openings are the world state's joint angles.
    for d in spec.doors.iter().filter(|d| d.initial_deg != 0.0) {
        let angle = format!("<angle axis=\"0\">{}</angle>", d.initial_deg.to_radians());
        assert!(text.contains(&angle), "{angle} missing");
    }
    let Some(r) = sdf_check(&path) else {
        return;
    };
    // The building, a model per door and the robot.
    assert!(
        r.text
            .contains(&format!("world semsim models={}", spec.doors.len() + 2)),
        "{}",
        r.text
    );
    assert_eq!(
        r.models["building"],
        (static_entities(&spec) + spec.free_spaces.len(), 0),
        "{}",
        r.text
    );
    check_doors(&spec, &r);
    let id = spec.entities().iter().map(|e| e.id).max().unwrap() + 1;
    let robot = format!("robot_{id}");
    assert_eq!(r.models[&robot], (5, 4), "{}", r.text);
    for i in 0..4 {
        let j = &r.joints[&format!("{robot}/wheel_{i}_axle")];
        assert_eq!(j.kind, "continuous");
    }
}

#[test]
fn a_semantic_map_world_and_the_inspection_robot_load_in_sdformat() {
    let (spec, relations) = map_world();
    assert!(spec.doors[0].initial_deg > 0.0);
    let (model, start) = robot("inspection", 3.0, -1.0, 90.0);
    let options = ExportOptions {
        robot: Some((&model, start)),
        relations: &relations,
    };
    let dir = tempfile::tempdir().unwrap();
    let path = export(dir.path(), "map", &spec, ExportFormat::Sdf, &options);
    let Some(r) = sdf_check(&path) else {
        return;
    };
    check_doors(&spec, &r);
    let id = spec.entities().iter().map(|e| e.id).max().unwrap() + 1;
    let robot = format!("robot_{id}");
    // Chassis, 6 wheels, 3 arm links; 6 wheel joints and 3 arm joints.
    assert_eq!(r.models[&robot], (10, 9), "{}", r.text);
    let arm = model.arm.as_ref().unwrap();
    for l in &arm.links {
        let j = &r.joints[&format!("{robot}/arm_{}_joint", l.name)];
        assert_eq!(j.kind, "revolute");
        assert!(close(j.lower, l.min_deg.to_radians()), "{j:?}");
        assert!(close(j.upper, l.max_deg.to_radians()), "{j:?}");
    }
}
