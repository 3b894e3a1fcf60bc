//! Simulation speed: simulated seconds per wall-clock second in the default building with one
//! robot at 60 Hz (events on, default rates). Run: `cargo bench -p sim --bench simulate`.
//!
//! * `pioneer_corridor_door_20s`: the Pioneer 3-AT drives down the corridor and pushes open the
//!   first north door (the ANCHORS.md reference world's workload).
//! * `inspection_default_scenario_60s`: the demo scenario (corridor, door, stairs) with the
//!   six-wheel cleated inspection robot and its arm.
//!
//! * `overlapping_boxes_30000_2s`: a world of a floor and 30,000 wall boxes all at one place
//!   (a bad map or building), built and simulated for 2 s; it also prints the process's peak
//!   memory (before the static boxes were merged into one compound collider, rapier's broad
//!   phase listed every overlapping pair: 30,000 boxes aborted at 2.3 GB).
//!
//! Criterion reports steps per second as throughput; divide by 60 for simulated s per s.

use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use sim::{BoxSpec, EntityClass, FixedBox, RobotModel, Scenario, Simulation, WorldSpec};
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

/// A floor and `n` wall boxes all at x = 5.
fn overlapping_world(n: usize) -> WorldSpec {
    let fixed = |entity: u32, class, name: String, center_m, half_extents_m| FixedBox {
        entity,
        class,
        name,
        label: String::new(),
        geometry: BoxSpec {
            center_m,
            half_extents_m,
            yaw_deg: 0.0,
        },
    };
    let mut spec = WorldSpec::default();
    spec.fixed.push(fixed(
        1,
        EntityClass::Floor,
        "floor".into(),
        [0.0, 0.0, -0.1],
        [10.0, 10.0, 0.1],
    ));
    for i in 0..n {
        spec.fixed.push(fixed(
            2 + i as u32,
            EntityClass::Wall,
            format!("w{i}"),
            [5.0, 0.0, 1.25],
            [0.1, 2.0, 1.25],
        ));
    }
    spec
}

/// The process's peak resident memory (MB), where Linux tells it.
fn peak_rss_mb() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb / 1024.0)
}

fn overlapping(c: &mut Criterion) {
    let n = 30_000;
    let spec = overlapping_world(n);
    let sc = Scenario::from_toml_str(
        "robot = \"pioneer3at\"\ntime_limit_s = 2.0\nstart = { x_m = 0.0, y_m = 0.0 }\n",
        "bench",
    )
    .expect("scenario");
    let model = RobotModel::builtin(&sc.robot).expect("model");
    let t = Instant::now();
    let mut s = Simulation::new(&spec, &sc, &model).expect("simulation");
    s.run();
    eprintln!(
        "overlapping_boxes_{n}_2s: built and simulated in {:.3} s, peak memory {} (merged: {})",
        t.elapsed().as_secs_f64(),
        peak_rss_mb().map_or("unknown".into(), |m| format!("{m:.0} MB")),
        s.world().statics_merged()
    );
    let mut group = c.benchmark_group("world");
    group.sample_size(10);
    group.bench_function("overlapping_boxes_30000_2s", |b| {
        b.iter(|| {
            let mut s = Simulation::new(&spec, &sc, &model).expect("simulation");
            s.run()
        })
    });
    group.finish();
}

criterion_group!(benches, overlapping, simulate);
criterion_main!(benches);
