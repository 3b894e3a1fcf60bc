//! Simulation speed: simulated seconds per wall-clock second in the default building with one
//! robot at 60 Hz (events on, default rates). Run: `cargo bench -p sim --bench simulate`.
//!
//! * `pioneer_corridor_door_20s`: the Pioneer 3-AT drives down the corridor and pushes open the
//!   first north door (the ANCHORS.md reference world's workload).
//! * `inspection_default_scenario_60s`: the demo scenario (corridor, door, stairs) with the
//!   six-wheel cleated inspection robot and its arm.
//!
//! Criterion reports steps per second as throughput; divide by 60 for simulated s per s.

use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use sim::{RobotModel, Scenario, Simulation, WorldSpec};
use std::time::Instant;

const PIONEER: &str = r#"
robot = "pioneer3at"
time_limit_s = 20.0
start = { x_m = 1.5, y_m = 0.0, yaw_deg = 0.0 }
[[waypoints]]
x_m = 2.45
y_m = 0.0
[[waypoints]]
x_m = 2.45
y_m = 3.0
[[waypoints]]
x_m = 4.0
y_m = 3.5
"#;

fn simulate(c: &mut Criterion) {
    let building = scanner::Building::default_building().expect("default building");
    let spec = WorldSpec::from_building(&building).expect("world spec");
    let cases = [
        (
            "pioneer_corridor_door_20s",
            Scenario::from_toml_str(PIONEER, "bench").expect("scenario"),
        ),
        (
            "inspection_default_scenario_60s",
            Scenario::default_scenario().expect("scenario"),
        ),
    ];
    let mut group = c.benchmark_group("simulate");
    group.sample_size(10);
    for (name, sc) in &cases {
        let model = RobotModel::builtin(&sc.robot).expect("model");
        let steps = (sc.time_limit_s * 60.0).round() as u64;
        group.throughput(Throughput::Elements(steps));
        group.bench_function(*name, |b| {
            b.iter_batched(
                || Simulation::new(&spec, sc, &model).expect("simulation"),
                |mut s| s.run(),
                BatchSize::LargeInput,
            )
        });
        // A plain figure for the report: simulated seconds per wall-clock second (best of 5).
        let best = (0..5)
            .map(|_| {
                let mut s = Simulation::new(&spec, sc, &model).expect("simulation");
                let t = Instant::now();
                s.run();
                t.elapsed().as_secs_f64()
            })
            .fold(f64::INFINITY, f64::min);
        eprintln!(
            "{name}: {:.0} simulated s per wall s ({:.1} us per step, best of 5)",
            sc.time_limit_s / best,
            best / steps as f64 * 1e6
        );
    }
    group.finish();
}

criterion_group!(benches, simulate);
criterion_main!(benches);
