//! Times the semantic map stage on the benchmark's cloud (the default building, 10 full
//! 541 x 301 scans, ~1.6 M points) and prints the per-stage medians.
//!
//! `cargo run --release -p semantic --example bench_map -- [RUNS] [--voxel M]`

use semantic::{build_semantic_map, SemanticConfig};
use std::collections::BTreeMap;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let runs: usize = args.first().and_then(|a| a.parse().ok()).unwrap_or(7);
    let mut cloud = fixtures::default_building_full_scans(10);
    if let Some(v) = args
        .iter()
        .position(|a| a == "--voxel")
        .and_then(|i| args.get(i + 1))
    {
        cloud = cloud::voxel_downsample(&cloud, v.parse()?)?;
    }
    let config = SemanticConfig::default();
    let mut totals = Vec::new();
    let mut stages: BTreeMap<String, Vec<f64>> = BTreeMap::new();
    let mut order = Vec::new();
    let mut entities = 0;
    for _ in 0..runs {
        let t = std::time::Instant::now();
        let out = build_semantic_map(&cloud, &config)?;
        totals.push(t.elapsed().as_secs_f64() * 1e3);
        entities = out.map.entities.len();
        for s in &out.timings {
            if !stages.contains_key(&s.stage) {
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
        "{} points, {} entities, {} threads: total median {:.0} ms (min {:.0})",
        cloud.len(),
        entities,
        rayon::current_num_threads(),
        median(&mut totals.clone()),
        totals.iter().copied().fold(f64::INFINITY, f64::min)
    );
    for name in order {
        let v = stages.get_mut(&name).ok_or("stage")?;
        println!("  {name:13} {:7.1} ms", median(v));
    }
    Ok(())
}
