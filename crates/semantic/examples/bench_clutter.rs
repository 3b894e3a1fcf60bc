//! Times the semantic map stage on cluttered buildings of ~1.6 M points each, and prints the
//! per-stage medians (Markdown) and the entity counts:
//!
//! - the garage of the clutter tests (`tests/data/garage.toml`: a downstand beam, a beam over
//!   pillars, parked cars, shelves, a table, crates, a store room), scanned with the ideal laser
//!   at full resolution (541 x 301 rays) from ten poses of a 5 m grid;
//! - a generated `garage` style building (seed 3: two staircases, parked cars, pillars, beams),
//!   scanned with the realistic laser (`real` preset) at full resolution along its
//!   `scan --survey` poses, as many as make 1.6 M points, merged at the true poses.
//!
//! `cargo run --release -p semantic --example bench_clutter -- [RUNS]` (see
//! `bench/semantic_clutter.sh`, which runs it on two cores and records the result).

use glam::Vec3;
use scanner::{
    generate_building, survey_poses, Building, BuildingGeometry, GeneratorConfig, LaserConfig,
    Realism, ScanPose, Style, SurveyConfig, VirtualLaser,
};
use semantic::{build_semantic_map, EntityClass, SemanticConfig};
use std::collections::BTreeMap;
use std::path::Path;

/// Points the benchmark's clouds reach (the figure).
const TARGET_POINTS: usize = 1_600_000;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let runs: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(7);
    let (poses, cloud) = clutter_garage()?;
    time_map(
        &format!("cluttered garage (ideal laser): {poses} scans"),
        &cloud,
        runs,
    )?;
    println!();
    let (poses, cloud) = style_garage()?;
    time_map(
        &format!("generated `garage` style, seed 3 (realistic laser): {poses} survey scans"),
        &cloud,
        runs,
    )?;
    Ok(())
}

/// The clutter tests' garage from ten poses of a 5 m grid, ideal laser.
fn clutter_garage() -> Result<(usize, cloud::PointCloud), Box<dyn std::error::Error>> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/garage.toml");
    let b = Building::load(&path)?;
    let g = BuildingGeometry::new(&b);
    let mut poses = Vec::new();
    for y in [2.0, 7.0, 12.0] {
        for x in [2.5, 7.5, 13.5, 17.0, 21.5] {
            let clear = [0.0f32, 0.5].iter().all(|&d| {
                g.entity_containing(Vec3::new(x as f32 + d, y as f32, 0.5))
                    .is_none()
            });
            if clear {
                poses.push(ScanPose {
                    x_m: x,
                    y_m: y,
                    yaw_deg: 0.0,
                });
            }
        }
    }
    // Ten scans: ~1.6 M points.
    poses.truncate(10);
    let cloud = fixtures::scan_building(&b, &poses, &LaserConfig::default(), 0.0);
    Ok((poses.len(), cloud))
}

/// A generated garage-style building along its survey poses, realistic laser, up to
/// [`TARGET_POINTS`].
fn style_garage() -> Result<(usize, cloud::PointCloud), Box<dyn std::error::Error>> {
    let b = generate_building(
        3,
        &GeneratorConfig {
            style: Style::Garage,
            ..GeneratorConfig::default()
        },
    )?;
    let laser = LaserConfig {
        realism: Realism::real(),
        ..LaserConfig::default()
    };
    let g = BuildingGeometry::new(&b);
    let laser = VirtualLaser::new(laser)?;
    let poses = survey_poses(&b, &SurveyConfig::default())?;
    let mut cloud = cloud::PointCloud::from_points(Vec::new());
    let mut used = 0;
    // (a scan's labels are left out, as a real scan has none)
    for (k, pose) in poses.iter().enumerate() {
        if cloud.len() >= TARGET_POINTS {
            break;
        }
        let mut scan = laser.scan(&g, pose, k as u64).without_invalid();
        // The sensor's no-echo readings are dropped, as the scan readers drop them.
        if let Some(no_echo) = laser.config().realism.no_echo_range_m {
            let (origin, far) = (scan.sensor_origin, no_echo as f32 - 0.01);
            scan.points.retain(|p| p.distance(origin) < far);
        }
        scan.transform(&pose.world_from_scan(laser.config().mount_height_m));
        cloud.points.extend(scan.points);
        used += 1;
    }
    Ok((used, cloud))
}

/// Maps `cloud` `runs` times and prints the per-stage medians.
fn time_map(
    name: &str,
    cloud: &cloud::PointCloud,
    runs: usize,
) -> Result<(), Box<dyn std::error::Error>> {
    let config = SemanticConfig::default();
    let mut totals = Vec::new();
    let mut stages: BTreeMap<String, Vec<f64>> = BTreeMap::new();
    let mut order = Vec::new();
    let mut counts = Vec::new();
    for _ in 0..runs {
        let t = std::time::Instant::now();
        let out = build_semantic_map(cloud, &config)?;
        totals.push(t.elapsed().as_secs_f64() * 1e3);
        counts = [
            EntityClass::Wall,
            EntityClass::Stairs,
            EntityClass::Obstacle,
            EntityClass::Column,
            EntityClass::Beam,
        ]
        .iter()
        .map(|&c| format!("{} {}", c.name(), out.map.of_class(c).count()))
        .collect();
        for s in &out.timings {
            if !order.contains(&s.stage) {
                order.push(s.stage.clone());
            }
            stages.entry(s.stage.clone()).or_default().push(s.ms);
        }
    }
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    println!(
        "{name}, {} points, {} threads, {runs} runs; entities: {}",
        cloud.len(),
        rayon::current_num_threads(),
        counts.join(", ")
    );
    println!();
    println!("| stage | median ms |");
    println!("|---|---:|");
    for s in &order {
        if let Some(v) = stages.get_mut(s) {
            println!("| {s} | {:.1} |", median(v));
        }
    }
    println!("| **total** | **{:.1}** |", median(&mut totals));
    Ok(())
}
