//! Times the semantic map stage on a cluttered building: the garage of the clutter tests
//! (`tests/data/garage.toml`: a downstand beam, a beam over pillars, parked cars, shelves, a
//! table, crates, a store room), scanned at full resolution (541 x 301 rays) from ten poses of a
//! 5 m grid, ~1.6 M points, and prints the per-stage medians (Markdown) and the entity counts.
//!
//! `cargo run --release -p semantic --example bench_clutter -- [RUNS]` (see
//! `bench/semantic_clutter.sh`, which runs it on two cores and records the result).

use glam::Vec3;
use scanner::{Building, BuildingGeometry, LaserConfig, ScanPose};
use semantic::{build_semantic_map, EntityClass, SemanticConfig};
use std::collections::BTreeMap;
use std::path::Path;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let runs: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(7);
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
    let laser = LaserConfig::default();
    let cloud = fixtures::scan_building(&b, &poses, &laser, 0.0);
    let config = SemanticConfig::default();
    let mut totals = Vec::new();
    let mut stages: BTreeMap<String, Vec<f64>> = BTreeMap::new();
    let mut order = Vec::new();
    let mut counts = Vec::new();
    for _ in 0..runs {
        let t = std::time::Instant::now();
        let out = build_semantic_map(&cloud, &config)?;
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
        "cluttered garage: {} scans, {} points, {} threads, {runs} runs; entities: {}",
        poses.len(),
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
