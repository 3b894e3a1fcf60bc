//! Exports that must fail, clearly: a world or robot sim would refuse, a path that cannot be
//! written (naming it, leaving no file, keeping an existing one), an unknown format name.

mod export_support;

use cloud::BadInput;
use export_support::{default_world, robot};
use interop::{export_world, write_export, ExportFormat, ExportOptions, InteropError};
use std::path::Path;

#[test]
fn a_world_that_fails_validation_is_refused_in_every_format() {
    let mut spec = default_world();
    spec.doors[0].wall = 9999;
    let mut nan = default_world();
    nan.fixed[3].geometry.half_extents_m[1] = f64::NAN;
    for format in ExportFormat::ALL {
        let err = export_world(&spec, format, &ExportOptions::default()).unwrap_err();
        assert!(matches!(err, InteropError::Sim(_)), "{err:?}");
        let msg = err.to_string();
        assert!(
            msg.contains("entity 9999") && msg.contains(&spec.doors[0].name),
            "{msg}"
        );
        assert!(err.is_bad_input());
        let err = export_world(&nan, format, &ExportOptions::default()).unwrap_err();
        let msg = err.to_string();
        assert!(msg.contains("not a finite number"), "{msg}");
    }
}

#[test]
fn a_robot_that_fails_validation_is_refused() {
    let spec = default_world();
    let (mut model, start) = robot("pioneer3at", 1.5, 0.0, 0.0);
    model.wheels.truncate(1);
    let options = ExportOptions {
        robot: Some((&model, start)),
        ..Default::default()
    };
    let err = export_world(&spec, ExportFormat::Mjcf, &options).unwrap_err();
    assert!(err.to_string().contains("needs 2 to 32 wheels"), "{err}");
    let (model, mut start) = robot("pioneer3at", 1.5, 0.0, 0.0);
    start.yaw_deg = f64::INFINITY;
    let options = ExportOptions {
        robot: Some((&model, start)),
        ..Default::default()
    };
    let err = export_world(&spec, ExportFormat::Sdf, &options).unwrap_err();
    assert!(err.to_string().contains("yaw_deg"), "{err}");
}

#[test]
fn an_unwritable_path_is_an_error_naming_it() {
    let spec = default_world();
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("no/such/folder/world.glb");
    let err = write_export(
        &missing,
        &spec,
        ExportFormat::Glb,
        &ExportOptions::default(),
    )
    .unwrap_err();
    assert!(
        err.to_string().contains(&missing.display().to_string()),
        "{err}"
    );
    assert!(!missing.exists());
    // A folder where the file should go.
    let folder = dir.path().join("taken.xml");
    std::fs::create_dir(&folder).unwrap();
    let err = write_export(
        &folder,
        &spec,
        ExportFormat::Mjcf,
        &ExportOptions::default(),
    )
    .unwrap_err();
    assert!(err.to_string().contains("taken.xml"), "{err}");
    // Nothing left behind beside it: only the folder itself.
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(left.len(), 1, "{left:?}");
}

#[test]
fn a_failed_export_keeps_the_file_it_would_have_replaced() {
    let spec = default_world();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("world.sdf");
    write_export(&path, &spec, ExportFormat::Sdf, &ExportOptions::default()).unwrap();
    let before = std::fs::read(&path).unwrap();
    let mut bad = spec.clone();
    bad.doors[0].mass_kg = -1.0;
    assert!(write_export(&path, &bad, ExportFormat::Sdf, &ExportOptions::default()).is_err());
    assert_eq!(std::fs::read(&path).unwrap(), before);
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

#[test]
fn format_names_and_extensions() {
    assert_eq!("mjcf".parse::<ExportFormat>(), Ok(ExportFormat::Mjcf));
    assert_eq!("SDF".parse::<ExportFormat>(), Ok(ExportFormat::Sdf));
    assert_eq!("gltf".parse::<ExportFormat>(), Ok(ExportFormat::Glb));
    assert_eq!("glb".parse::<ExportFormat>(), Ok(ExportFormat::Glb));
    let err = "obj".parse::<ExportFormat>().unwrap_err();
    assert!(
        err.contains("\"obj\"") && err.contains("mjcf, sdf, gltf or glb"),
        "{err}"
    );
    let ext: Vec<&str> = ExportFormat::ALL.iter().map(|f| f.extension()).collect();
    assert_eq!(ext, ["xml", "sdf", "glb"]);
    for f in ExportFormat::ALL {
        let name = format!("world.{}", f.extension());
        assert_eq!(ExportFormat::from_path(Path::new(&name)), Some(f));
        assert_eq!(f.to_string().parse::<ExportFormat>(), Ok(f));
    }
    assert_eq!(
        ExportFormat::from_path(Path::new("w.MJCF")),
        Some(ExportFormat::Mjcf)
    );
    assert_eq!(ExportFormat::from_path(Path::new("w.obj")), None);
}
