//! The whole semantic map stage on the default building: 10 full-resolution (541 x 301) virtual
//! scans merged with their true poses, about 1.6 million points, not downsampled.
//! `cargo bench -p semantic` (the per-stage split is printed once; `cargo run --release -p
//! semantic --example bench_map` prints medians of the split).

use criterion::{criterion_group, criterion_main, Criterion};
use semantic::{build_semantic_map, SemanticConfig};

fn semantic_map(c: &mut Criterion) {
    let cloud = fixtures::default_building_full_scans(10);
    let config = SemanticConfig::default();
    let out = build_semantic_map(&cloud, &config).expect("map");
    let split: Vec<String> = out
        .timings
        .iter()
        .map(|t| format!("{} {:.1} ms", t.stage, t.ms))
        .collect();
    eprintln!(
        "{} points ({} finite): {}",
        cloud.len(),
        cloud.valid_count(),
        split.join(", ")
    );
    let mut group = c.benchmark_group("semantic");
    group.sample_size(10);
    group.bench_function("default_building_10_full_scans", |b| {
        b.iter(|| build_semantic_map(&cloud, &config).expect("map"))
    });
    group.finish();
}

criterion_group!(benches, semantic_map);
criterion_main!(benches);
