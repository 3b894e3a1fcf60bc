//! PCD I/O benchmark: binary and binary_compressed read/write of 162,841 labelled points
//! (one 541 x 301 scan). Run: `cargo bench -p cloud --bench pcd`.

use cloud::{io::pcd, EntityClass, Label, Organized, PcdEncoding, PointCloud};
use criterion::{criterion_group, criterion_main, Criterion};
use glam::Vec3;

fn scan_like() -> PointCloud {
    let (rows, cols) = (301, 541);
    let mut c = PointCloud::from_points(
        (0..rows * cols)
            .map(|i| {
                let (r, k) = ((i / cols) as f32, (i % cols) as f32);
                Vec3::new(r.sin() * 5.0 + k * 0.01, r.cos() * 5.0, k * 0.004 - 1.0)
            })
            .collect(),
    );
    c.labels = Some(
        (0..rows * cols)
            .map(|i| Label {
                entity: (i % 40) as u32,
                class: EntityClass::Wall,
            })
            .collect(),
    );
    c.organized = Some(Organized { rows, cols });
    c
}

fn pcd_io(c: &mut Criterion) {
    let cloud = scan_like();
    let dir = tempfile::tempdir().expect("tempdir");
    let mut group = c.benchmark_group("pcd_162841_points");
    group.sample_size(20);
    for (name, enc) in [
        ("binary", PcdEncoding::Binary),
        ("binary_compressed", PcdEncoding::BinaryCompressed),
    ] {
        let path = dir.path().join(format!("{name}.pcd"));
        group.bench_function(format!("write_{name}"), |b| {
            b.iter(|| pcd::write_pcd(&path, &cloud, enc).expect("write"))
        });
        group.bench_function(format!("read_{name}"), |b| {
            b.iter(|| pcd::read_pcd(&path).expect("read"))
        });
    }
    group.finish();
}

criterion_group!(benches, pcd_io);
criterion_main!(benches);
