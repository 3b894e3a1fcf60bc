//! TEMP one-off measurement (removed before hand-back).
use sim::{BoxSpec, FixedBox, RobotModel, Scenario, WorldSpec};

#[test]
#[ignore]
fn measure_overlapping_boxes() {
    let n: usize = std::env::var("N")
        .map(|v| v.parse().unwrap())
        .unwrap_or(30_000);
    let mut spec = WorldSpec::default();
    spec.fixed.push(FixedBox {
        entity: 1,
        class: sim::EntityClass::Floor,
        name: "floor".into(),
        label: String::new(),
        geometry: BoxSpec {
            center_m: [0.0, 0.0, -0.1],
            half_extents_m: [10.0, 10.0, 0.1],
            yaw_deg: 0.0,
        },
    });
    for i in 0..n {
        spec.fixed.push(FixedBox {
            entity: 2 + i as u32,
            class: sim::EntityClass::Wall,
            name: format!("w{i}"),
            label: String::new(),
            geometry: BoxSpec {
                center_m: [5.0, 0.0, 1.25],
                half_extents_m: [0.1, 2.0, 1.25],
                yaw_deg: 0.0,
            },
        });
    }
    let sc = Scenario::from_toml_str(
        r#"
        robot = "pioneer3at"
        time_limit_s = 2.0
        start = { x_m = 0.0, y_m = 0.0, yaw_deg = 0.0 }
        "#,
        "m",
    )
    .unwrap();
    let model = RobotModel::builtin(&sc.robot).unwrap();
    let t = std::time::Instant::now();
    let o = sim::run_scenario(&spec, &sc, &model).unwrap();
    eprintln!("n={n} events={} time={:?}", o.events.len(), t.elapsed());
}
