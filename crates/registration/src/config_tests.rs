//! Tests of `config`.

use super::*;

#[test]
fn method_names_parse() {
    assert_eq!("p2p".parse::<Method>(), Ok(Method::PointToPoint));
    assert_eq!("P2Plane".parse::<Method>(), Ok(Method::PointToPlane));
    assert_eq!("point_to_plane".parse::<Method>(), Ok(Method::PointToPlane));
    assert_eq!("gicp".parse::<Method>(), Ok(Method::Gicp));
    assert!("ndt".parse::<Method>().is_err());
    for m in [Method::PointToPoint, Method::PointToPlane, Method::Gicp] {
        assert_eq!(m.to_string().parse::<Method>(), Ok(m));
    }
}

#[test]
fn defaults_are_valid_and_round_trip_through_toml_and_json() {
    let c = IcpConfig::default();
    c.validate().expect("defaults valid");
    IcpConfig::point_to_point().validate().expect("p2p valid");
    let text = toml::to_string(&c).expect("toml");
    assert!(text.contains("method = \"gicp\""), "{text}");
    let back: IcpConfig = toml::from_str(&text).expect("parse");
    assert_eq!(back, c);
    let huber = IcpConfig {
        kernel: RobustKernel::Huber { k_m: 0.1 },
        nn: NnBackend::KdTree,
        ..c
    };
    let json = serde_json::to_string(&huber).expect("json");
    assert!(
        json.contains("\"kd_tree\"") && json.contains("huber"),
        "{json}"
    );
    let back: IcpConfig = serde_json::from_str(&json).expect("parse");
    assert_eq!(back, huber);
}

#[test]
fn partial_config_fills_defaults_and_unknown_fields_fail() {
    let c: IcpConfig =
        toml::from_str("method = \"point_to_plane\"\nmax_iterations = 7").expect("partial");
    assert_eq!(c.method, Method::PointToPlane);
    assert_eq!(c.max_iterations, 7);
    assert_eq!(c.nn, IcpConfig::default().nn);
    assert!(toml::from_str::<IcpConfig>("max_iteration = 7").is_err());
}

#[test]
fn absurd_values_are_rejected_by_name() {
    let with = |f: fn(&mut IcpConfig)| {
        let mut c = IcpConfig::default();
        f(&mut c);
        c
    };
    let cases: Vec<(&str, IcpConfig)> = vec![
        ("max_iterations", with(|c| c.max_iterations = 0)),
        ("max_iterations", with(|c| c.max_iterations = 10_001)),
        (
            "max_correspondence_distance_m",
            with(|c| c.max_correspondence_distance_m = f64::NAN),
        ),
        (
            "max_correspondence_distance_m",
            with(|c| c.max_correspondence_distance_m = -1.0),
        ),
        (
            "final_correspondence_distance_m",
            with(|c| c.final_correspondence_distance_m = 2.0),
        ),
        ("bucket_size_m", with(|c| c.bucket_size_m = 0.0)),
        ("source_voxel_m", with(|c| c.source_voxel_m = Some(0.0))),
        (
            "target_voxel_m",
            with(|c| c.target_voxel_m = Some(f64::INFINITY)),
        ),
        (
            "reject_worst_fraction",
            with(|c| c.reject_worst_fraction = 0.5),
        ),
        (
            "kernel.k_m",
            with(|c| c.kernel = RobustKernel::Cauchy { k_m: 0.0 }),
        ),
        ("neighbours_k", with(|c| c.neighbours_k = 2)),
        ("normal_voxel_m", with(|c| c.normal_voxel_m = -0.1)),
        ("min_fitness", with(|c| c.min_fitness = 1.5)),
        (
            "translation_epsilon_m",
            with(|c| c.translation_epsilon_m = -1e-3),
        ),
    ];
    for (name, c) in cases {
        match c.validate() {
            Err(RegistrationError::InvalidParameter(cloud::InvalidParameter {
                name: n, ..
            })) => assert_eq!(n, name),
            other => panic!("{name}: expected InvalidParameter, got {other:?}"),
        }
    }
}
