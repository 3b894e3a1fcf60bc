//! Virtual laser benchmark: one full 541 x 301 scan (162,841 rays) of the default building,
//! by the ideal laser and by the realistic one (`Realism::real()`: noise, dropouts, glass,
//! mixed pixels with their extra footprint rays, walking people, a tilted mount).
//! Run: `cargo bench -p scanner --bench scan`.

use criterion::{criterion_group, criterion_main, Criterion};
use scanner::{Building, BuildingGeometry, LaserConfig, Realism, ScanPose, VirtualLaser};

fn scan(c: &mut Criterion) {
    let building = Building::default_building().expect("default building");
    let geometry = BuildingGeometry::new(&building);
    let laser = VirtualLaser::new(LaserConfig::default()).expect("default laser");
    let real = VirtualLaser::new(LaserConfig {
        realism: Realism::real(),
        ..Default::default()
    })
    .expect("real laser");
    let mut group = c.benchmark_group("virtual_laser");
    group.sample_size(20);
    for (name, pose) in [
        (
            "corridor_541x301",
            ScanPose {
                x_m: 6.5,
                y_m: 0.0,
                yaw_deg: 0.0,
            },
        ),
        (
            "stair_room_541x301",
            ScanPose {
                x_m: 17.5,
                y_m: 2.5,
                yaw_deg: 0.0,
            },
        ),
    ] {
        group.bench_function(name, |b| b.iter(|| laser.scan(&geometry, &pose, 0)));
        group.bench_function(format!("{name}_real"), |b| {
            b.iter(|| real.scan(&geometry, &pose, 0))
        });
    }
    group.bench_function("build_geometry", |b| {
        b.iter(|| BuildingGeometry::new(&building))
    });
    group.finish();
}

criterion_group!(benches, scan);
criterion_main!(benches);
