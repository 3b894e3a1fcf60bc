//! Statistical outlier removal of one full 541 x 301 scan of the default building (the ideal
//! laser's 162,841 rays less its missing returns, and the realistic laser's), as `read_scans`
//! runs it on every scan it reads.
//! Run: `cargo bench -p pipeline --bench outliers`.

use criterion::{criterion_group, criterion_main, Criterion};
use pipeline::{remove_outliers, OutlierConfig};
use scanner::{Building, BuildingGeometry, LaserConfig, Realism, ScanPose, VirtualLaser};

fn outliers(c: &mut Criterion) {
    let building = Building::default_building().expect("default building");
    let geometry = BuildingGeometry::new(&building);
    let pose = ScanPose {
        x_m: 6.5,
        y_m: 0.0,
        yaw_deg: 0.0,
    };
    let config = OutlierConfig::default();
    let mut group = c.benchmark_group("outliers");
    group.sample_size(20);
    for (name, realism) in [("ideal", Realism::off()), ("real", Realism::real())] {
        let laser = VirtualLaser::new(LaserConfig {
            realism,
            ..Default::default()
        })
        .expect("laser");
        let scan = laser.scan(&geometry, &pose, 0).without_invalid();
        let name = format!("corridor_{name}_{}k_points", scan.len() / 1000);
        group.bench_function(name, |b| b.iter(|| remove_outliers(&scan, &config)));
    }
    group.finish();
}

criterion_group!(benches, outliers);
criterion_main!(benches);
