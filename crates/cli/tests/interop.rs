//! The interop commands through the real binary: `convert` between every format pair that
//! writes (PCD, PLY, XYZ, 3DTK, E57, LAS, LAZ), `info` on each, `export` in each format,
//! truncated E57/LAS/LAZ/MCAP files refused (exit 2, the file named, nothing written), and a
//! multi-scan E57 written by pye57 (libE57Format) registered as a sequence.

mod util;

use std::path::{Path, PathBuf};
use util::Dir;

fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

/// A small scan folder of the default building (`n` scans along the corridor).
fn scans(d: &Dir, n: usize) -> PathBuf {
    let cfg = d.small_config();
    let building = d.write(
        "b.toml",
        include_str!("../../scanner/data/default_building.toml"),
    );
    let poses: Vec<String> = (0..n).map(|k| format!("{},0,0", 2 + k)).collect();
    let mut args = vec![
        "scan",
        "--building",
        s(&building),
        "--out",
        "scans",
        "--config",
        s(&cfg),
    ];
    for p in &poses {
        args.extend(["--pose", p.as_str()]);
    }
    d.run(&args).ok();
    d.join("scans")
}

/// The finite points of a cloud file, read by the cloud crate.
fn points(path: &Path) -> Vec<glam::Vec3> {
    cloud::read_cloud(path)
        .unwrap_or_else(|e| panic!("{e}"))
        .without_invalid()
        .points
}

#[test]
fn convert_round_trips_through_every_writable_format() {
    let d = Dir::new();
    let folder = scans(&d, 1);
    let original = points(&folder.join("scan000.pcd"));
    assert!(original.len() > 1000);
    // Each format and how closely it keeps positions: 3DTK stores centimetres as text with
    // 3 decimals (1e-5 m), XYZ 6 decimals, LAS/LAZ integers at the writer's scale, the others
    // f32/f64 exactly.
    for (ext, tolerance_m) in [
        ("ply", 0.0),
        ("xyz", 2e-6),
        ("3d", 2e-5),
        ("e57", 1e-6),
        ("las", 1.5e-4),
        ("laz", 1.5e-4),
    ] {
        let there = d.join(&format!("c.{ext}"));
        let back = d.join(&format!("back_{ext}.pcd"));
        d.run(&["convert", s(&folder.join("scan000.pcd")), s(&there)])
            .ok();
        let info = d.run(&["info", s(&there)]).ok();
        assert!(
            info.contains(&format!("points:    {}", original.len())),
            "{ext}: {info}"
        );
        d.run(&["convert", s(&there), s(&back)]).ok();
        let returned = points(&back);
        assert_eq!(returned.len(), original.len(), "{ext}: point count");
        let worst = original
            .iter()
            .zip(&returned)
            .map(|(a, b)| (*a - *b).abs().max_element())
            .fold(0.0f32, f32::max);
        assert!(
            worst <= tolerance_m + 1e-6,
            "{ext}: worst coordinate difference {worst} m > {tolerance_m}"
        );
    }
}

#[test]
fn export_writes_mjcf_sdf_and_glb_with_entities_and_the_robot() {
    let d = Dir::new();
    for (format, file) in [("mjcf", "w.xml"), ("sdf", "w.sdf"), ("gltf", "w.glb")] {
        let out = d
            .run(&[
                "export",
                "--building",
                "default",
                "--format",
                format,
                "--robot",
                "pioneer3at",
                "--out",
                file,
            ])
            .ok();
        assert!(
            out.contains("doors") && out.contains("robot pioneer3at"),
            "{out}"
        );
        let bytes = std::fs::read(d.join(file)).expect("written");
        match format {
            "gltf" => {
                assert_eq!(&bytes[..4], b"glTF", "GLB magic");
                let version = u32::from_le_bytes([bytes[4], bytes[5], bytes[6], bytes[7]]);
                let length = u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]);
                assert_eq!((version, length as usize), (2, bytes.len()));
            }
            _ => {
                let text = String::from_utf8(bytes).expect("XML text");
                let root = if format == "mjcf" { "<mujoco" } else { "<sdf" };
                assert!(text.contains(root), "{format}: no {root}");
                assert!(text.contains("door"), "{format}: no door");
            }
        }
    }
    assert_eq!(d.listing("."), ["w.glb", "w.sdf", "w.xml"]);
}

#[test]
fn export_refuses_bad_worlds_and_options_and_writes_nothing() {
    let d = Dir::new();
    let map = d.write("broken_map.json", "{\"format\": \"semsim-semantic-map\", ");
    d.run(&[
        "export",
        "--map",
        s(&map),
        "--format",
        "sdf",
        "--out",
        "w.sdf",
    ])
    .bad_input(&["broken_map.json"]);
    d.run(&[
        "export",
        "--building",
        "default",
        "--format",
        "obj",
        "--out",
        "w.obj",
    ])
    .bad_input(&["obj"]);
    d.run(&[
        "export",
        "--building",
        "default",
        "--format",
        "mjcf",
        "--robot",
        "pioneer3at",
        "--start",
        "1,nan",
        "--out",
        "w.xml",
    ])
    .bad_input(&["--start"]);
    d.run(&[
        "export",
        "--building",
        "default",
        "--format",
        "mjcf",
        "--robot",
        "no_such_robot.urdf",
        "--out",
        "w.xml",
    ])
    .bad_input(&["no_such_robot.urdf"]);
    assert_eq!(d.listing("."), ["broken_map.json"]);
}

#[test]
fn truncated_e57_las_laz_and_mcap_exit_2_naming_the_file_and_write_nothing() {
    let d = Dir::new();
    let folder = scans(&d, 1);
    let mut broken = Vec::new();
    for ext in ["e57", "las", "laz"] {
        let whole = d.join(&format!("whole.{ext}"));
        d.run(&["convert", s(&folder.join("scan000.pcd")), s(&whole)])
            .ok();
        let bytes = std::fs::read(&whole).expect("written");
        broken.push(d.write(&format!("cut.{ext}"), &bytes[..bytes.len() / 2]));
        let mut flipped = bytes.clone();
        for b in flipped.iter_mut().skip(8).step_by(97) {
            *b ^= 0x5a;
        }
        broken.push(d.write(&format!("flipped.{ext}"), flipped));
    }
    // An MCAP file: the magic, then bytes that are no record.
    let mut mcap = b"\x89MCAP0\r\n".to_vec();
    mcap.extend((0..200u32).map(|i| (i * 37 % 251) as u8));
    broken.push(d.write("garbage.mcap", mcap));
    for file in &broken {
        let name = file
            .file_name()
            .expect("name")
            .to_string_lossy()
            .into_owned();
        d.run(&["info", s(file)]).bad_input(&[&name]);
        d.run(&["convert", s(file), "out.pcd"]).bad_input(&[&name]);
        assert!(!d.join("out.pcd").exists(), "{name}: partial output");
    }
}

#[test]
fn a_multi_scan_e57_written_by_pye57_registers_as_a_sequence_with_its_poses_as_odometry() {
    let Some(python) = fixtures::oracles::python() else {
        return;
    };
    let d = Dir::new();
    let folder = scans(&d, 3);
    let odometry = cloud::read_poses(&folder.join("odometry.txt")).expect("odometry");
    let mut args = vec![s(&fixtures::oracles::script("scans_to_e57.py")).to_string()];
    args.push(s(&d.join("site.e57")).to_string());
    for pose in &odometry {
        let xyz = d.join(&format!("{}.xyz", pose.name));
        d.run(&[
            "convert",
            s(&folder.join(format!("{}.pcd", pose.name))),
            s(&xyz),
        ])
        .ok();
        let m = pose.world_from_scan.matrix3;
        let t = pose.world_from_scan.translation;
        let rows = [
            [m.x_axis.x, m.y_axis.x, m.z_axis.x, t.x],
            [m.x_axis.y, m.y_axis.y, m.z_axis.y, t.y],
            [m.x_axis.z, m.y_axis.z, m.z_axis.z, t.z],
            [0.0, 0.0, 0.0, 1.0],
        ];
        let numbers: Vec<String> = rows.iter().flatten().map(|v| format!("{v:.17}")).collect();
        args.extend([pose.name.clone(), s(&xyz).to_string(), numbers.join(",")]);
    }
    fixtures::oracles::run_ok(std::process::Command::new(python).args(&args));
    let info = d.run(&["info", "site.e57"]).ok();
    assert!(
        info.contains("scans:     3") && info.contains("scan002"),
        "{info}"
    );
    // The E57's poses are the odometry; the folder's poses.txt is the truth, matched by name.
    let truth = folder.join("poses.txt");
    d.run(&[
        "register",
        "--sequence",
        "site.e57",
        "--truth",
        s(&truth),
        "--out",
        "reg",
    ])
    .ok();
    let rows: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(d.join("reg/registration.json")).expect("report"),
    )
    .expect("json");
    let rows = rows.as_array().expect("rows");
    assert_eq!(rows.len(), 3);
    for row in rows {
        let error_m = row["error_m"].as_f64().expect("an error against the truth");
        assert!(error_m < 0.05, "{row}");
    }
}
