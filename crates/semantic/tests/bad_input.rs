//! Bad input: clear typed errors or an honest (empty) map, never a panic or a giant allocation.

use cloud::{Label, PointCloud};
use glam::Vec3;
use semantic::{build_semantic_map, EntityClass, SemanticConfig, SemanticError};

fn grid(n: usize, step: f32, f: impl Fn(f32, f32) -> Vec3) -> Vec<Vec3> {
    let mut v = Vec::new();
    for i in 0..n {
        for j in 0..n {
            v.push(f(i as f32 * step, j as f32 * step));
        }
    }
    v
}

#[test]
fn empty_and_all_nan_clouds_are_typed_errors() {
    let c = SemanticConfig::default();
    let err = build_semantic_map(&PointCloud::from_points(Vec::new()), &c).expect_err("empty");
    assert!(
        matches!(err, SemanticError::EmptyCloud { total: 0 }),
        "{err}"
    );
    let err = build_semantic_map(&PointCloud::from_points(vec![Vec3::NAN; 100]), &c)
        .expect_err("all NaN");
    assert!(
        matches!(err, SemanticError::EmptyCloud { total: 100 }),
        "{err}"
    );
    let inf = vec![
        Vec3::new(f32::INFINITY, 0.0, 0.0),
        Vec3::new(0.0, f32::NEG_INFINITY, 1.0),
    ];
    assert!(matches!(
        build_semantic_map(&PointCloud::from_points(inf), &c),
        Err(SemanticError::EmptyCloud { .. })
    ));
}

#[test]
fn a_single_plane_gives_a_floor_and_no_walls() {
    let plane = grid(200, 0.05, |x, y| Vec3::new(x, y, 0.3));
    let out = build_semantic_map(&PointCloud::from_points(plane), &SemanticConfig::default())
        .expect("a map");
    assert_eq!(out.map.of_class(EntityClass::Floor).count(), 1);
    assert_eq!(out.map.of_class(EntityClass::Wall).count(), 0);
    assert_eq!(out.map.of_class(EntityClass::Ceiling).count(), 0);
    assert!((out.floor_z_m.expect("floor") - 0.3).abs() < 0.01);
    assert!(out.labels.iter().all(|l| l.class == EntityClass::Floor));
    // A single vertical plane: no floor, no ceiling; whatever is found, no panic.
    let wall = grid(200, 0.02, |x, z| Vec3::new(x, 0.0, z));
    let out = build_semantic_map(&PointCloud::from_points(wall), &SemanticConfig::default())
        .expect("a map");
    assert_eq!(out.map.of_class(EntityClass::Floor).count(), 0);
}

#[test]
fn a_cloud_10_km_wide_is_refused_without_allocating_the_image() {
    // Points spread evenly over 10 km: the robust extent is still 10 km.
    let wide: Vec<Vec3> = (0..20_000)
        .map(|i| {
            Vec3::new(
                (i % 200) as f32 * 50.0,
                (i / 200) as f32 * 100.0,
                (i % 7) as f32 * 0.4,
            )
        })
        .collect();
    let err = build_semantic_map(&PointCloud::from_points(wide), &SemanticConfig::default())
        .expect_err("too wide");
    let text = err.to_string();
    match err {
        SemanticError::ImageTooLarge {
            width_px,
            height_px,
            max_pixels,
            width_m,
            ..
        } => {
            assert!(width_px * height_px > max_pixels);
            assert!(width_m > 9_000.0);
            assert!(text.contains("resolution_m"), "{text}");
        }
        other => panic!("unexpected {other}"),
    }
}

#[test]
fn a_room_with_stray_far_points_and_nans_still_maps() {
    // A 6 x 4 x 2.6 m room, one stray point 10 km away and missing returns mixed in.
    let mut pts = Vec::new();
    let step = 0.04f32;
    for i in 0..=150 {
        for j in 0..=100 {
            let (x, y) = (i as f32 * step, j as f32 * step);
            pts.push(Vec3::new(x, y, 0.0));
            pts.push(Vec3::new(x, y, 2.6));
        }
    }
    for k in 0..=65 {
        let z = k as f32 * step;
        for i in 0..=150 {
            pts.push(Vec3::new(i as f32 * step, 0.0, z));
            pts.push(Vec3::new(i as f32 * step, 4.0, z));
        }
        for j in 0..=100 {
            pts.push(Vec3::new(0.0, j as f32 * step, z));
            pts.push(Vec3::new(6.0, j as f32 * step, z));
        }
    }
    pts.push(Vec3::new(10_000.0, 10_000.0, 1.0));
    for i in (0..pts.len()).step_by(97) {
        pts[i] = Vec3::NAN;
    }
    let mut cloud = PointCloud::from_points(pts);
    cloud.labels = Some(vec![Label::default(); cloud.len()]);
    let out = build_semantic_map(&cloud, &SemanticConfig::default()).expect("a map");
    assert_eq!(out.map.of_class(EntityClass::Wall).count(), 4);
    assert_eq!(out.labels.len(), cloud.len());
    for (p, l) in cloud.points.iter().zip(&out.labels) {
        if !p.is_finite() || p.x > 100.0 {
            assert_eq!(*l, Label::default(), "a missing or stray point got a label");
        }
    }
    let walls: Vec<_> = out
        .map
        .of_class(EntityClass::Wall)
        .filter_map(|e| e.wall.as_ref())
        .collect();
    for w in walls {
        let len = glam::DVec2::from_array(w.segment_m[0])
            .distance(glam::DVec2::from_array(w.segment_m[1]));
        assert!(
            (len - 4.0).abs() < 0.1 || (len - 6.0).abs() < 0.1,
            "wall length {len}"
        );
    }
}

#[test]
fn invalid_configurations_are_named() {
    let cloud = PointCloud::from_points(grid(10, 0.1, |x, y| Vec3::new(x, y, 0.0)));
    let mut c = SemanticConfig::default();
    c.projection.resolution_m = 0.0;
    let err = build_semantic_map(&cloud, &c).expect_err("zero resolution");
    assert!(
        matches!(
            &err,
            SemanticError::InvalidParameter(p) if p.name == "projection.resolution_m"
        ),
        "{err}"
    );
    let mut c = SemanticConfig::default();
    c.walls.face_tolerance_m = f64::NAN;
    assert!(matches!(
        build_semantic_map(&cloud, &c),
        Err(SemanticError::InvalidParameter(p)) if p.name == "walls.face_tolerance_m"
    ));
    // Unknown keys in a configuration file are rejected by serde.
    let text = r#"{"projection": {"resolution_m": 0.05, "bogus": 1}}"#;
    assert!(serde_json::from_str::<SemanticConfig>(text).is_err());
    let c: SemanticConfig =
        serde_json::from_str(r#"{"hough": {"threshold_votes": 20}}"#).expect("partial config");
    assert_eq!(c.hough.threshold_votes, 20);
    assert_eq!(c.projection, semantic::ProjectionConfig::default());
}
