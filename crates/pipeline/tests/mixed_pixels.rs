//! Mixed-pixel removal against ground truth: the realistic laser's organised scans of the
//! default building, whose mixed pixels are the unknown-labelled returns off every surface
//! (people left out), and the same scans with mixed pixels off.

use cloud::PointCloud;
use glam::Vec3;
use pipeline::{find_mixed_pixels, MixedPixelConfig};
use scanner::{Building, BuildingGeometry, LaserConfig, MixedPixels, Realism, VirtualLaser};

/// What the filter found among the returns of the realistic laser's scans.
#[derive(Debug, Default)]
struct Counts {
    /// Unknown-labelled returns farther than five times the 1 cm noise from every surface
    /// (mixed pixels), and how many of them were found.
    off_surface: usize,
    off_surface_found: usize,
    /// Returns on the building's surfaces, and how many of them were found.
    surface: usize,
    surface_found: usize,
}

/// Distance from a world point to the nearest surface of the building.
fn clearance_m(geometry: &BuildingGeometry, p: Vec3) -> f32 {
    (1..=geometry.entities().len() as u32)
        .map(|e| geometry.distance_to_entity(p, e))
        .fold(f32::INFINITY, f32::min)
}

/// The realistic laser (level mount, so that the pose is the truth; nobody walking) through
/// every other survey pose of the default building, its scans organised with their no-echo
/// readings dropped (as `read_scans` hands them to the filter).
fn counts(mixed: MixedPixels) -> Counts {
    let building = Building::default_building().expect("default");
    let geometry = BuildingGeometry::new(&building);
    let mut realism = Realism::real();
    realism.people.count = 0;
    realism.mount = scanner::Mount::off();
    realism.mixed = mixed.clone();
    let laser = LaserConfig {
        realism,
        ..LaserConfig::default()
    };
    let virtual_laser = VirtualLaser::new(laser.clone()).expect("valid laser");
    let mut c = Counts::default();
    for pose in fixtures::survey_poses(&building, &geometry)
        .iter()
        .step_by(2)
    {
        let s: PointCloud = pipeline::drop_no_echo(&virtual_laser.scan(&geometry, pose, 0)).0;
        assert!(s.organized.is_some(), "the scan keeps its grid");
        let world_from_scan = pose.world_from_scan(laser.mount_height_m);
        let found: std::collections::HashSet<usize> =
            find_mixed_pixels(&s, &MixedPixelConfig::default())
                .into_iter()
                .collect();
        let labels = s.labels.as_ref().expect("labelled");
        for (i, (p, l)) in s.points.iter().zip(labels).enumerate() {
            if !p.is_finite() {
                continue;
            }
            let hit = usize::from(found.contains(&i));
            if l.entity != 0 {
                c.surface += 1;
                c.surface_found += hit;
                continue;
            }
            let w = world_from_scan.transform_point3(p.as_dvec3()).as_vec3();
            if clearance_m(&geometry, w) > 0.05 {
                c.off_surface += 1;
                c.off_surface_found += hit;
            }
        }
    }
    eprintln!("realistic laser, mixed pixels {mixed:?}: {c:?}");
    c
}

/// The least share of the mixed pixels found that the test pins: 209 of 244 (86 %) were when
/// it was written; the bound is a floor under that, not a target. (The statistical outlier
/// removal finds 22 % of them, `tests/outliers.rs`: it cannot tell a streak along an edge from
/// a cable.)
const MIXED_PIXELS_FOUND: f64 = 0.75;

/// The most surface returns found, per million: 321 and 353 (with and without mixed pixels)
/// were, single samples between two surfaces that continue neither (a step's tread seen at
/// grazing incidence between two risers, the last sample round a corner).
const SURFACE_FOUND_PPM: usize = 500;

#[test]
fn mixed_pixels_of_the_realistic_laser_are_found_and_its_surfaces_kept() {
    let c = counts(MixedPixels::real());
    assert!(c.off_surface > 100, "{c:?}");
    let share = c.off_surface_found as f64 / c.off_surface as f64;
    assert!(share >= MIXED_PIXELS_FOUND, "{share}: {c:?}");
    assert!(
        c.surface_found * 1_000_000 <= SURFACE_FOUND_PPM * c.surface,
        "{c:?}"
    );
}

#[test]
fn without_mixed_pixels_the_filter_finds_next_to_nothing() {
    let c = counts(MixedPixels::off());
    assert!(c.surface > 100_000, "{c:?}");
    assert!(
        c.surface_found * 1_000_000 <= SURFACE_FOUND_PPM * c.surface,
        "{c:?}"
    );
}
