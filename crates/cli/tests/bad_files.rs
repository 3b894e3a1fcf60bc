//! Malformed inputs: each gives exit code 2, a message naming the file and the problem,
//! no panic, and no partial output file.

mod util;

use util::Dir;

fn convert_fails(d: &Dir, input: &str, needles: &[&str]) {
    d.run(&["convert", input, "out.ply"]).bad_input(needles);
    assert!(!d.join("out.ply").exists(), "partial output left behind");
    let stray: Vec<String> = d
        .listing(".")
        .into_iter()
        .filter(|f| f.ends_with(".tmp"))
        .collect();
    assert!(stray.is_empty(), "temporary files left: {stray:?}");
}

fn small_pcd(d: &Dir, name: &str) -> Vec<u8> {
    let xyz = d.write("src.xyz", "0 0 0\n1 2 3\n4 5 6\n7 8 9\n");
    d.run(&[
        "convert",
        xyz.to_str().expect("utf8"),
        name,
        "--encoding",
        "binary",
    ])
    .ok();
    std::fs::read(d.join(name)).expect("written")
}

#[test]
fn truncated_pcd() {
    let d = Dir::new();
    let bytes = small_pcd(&d, "whole.pcd");
    d.write("cut.pcd", &bytes[..bytes.len() - 7]);
    convert_fails(&d, "cut.pcd", &["cut.pcd", "truncated"]);
}

#[test]
fn ply_with_a_wrong_header() {
    let d = Dir::new();
    d.write(
        "bad.ply",
        "ply\nformat binary_middle_endian 1.0\nelement vertex 1\nproperty float x\nend_header\n",
    );
    d.run(&["convert", "bad.ply", "out.pcd"])
        .bad_input(&["bad.ply"]);
    d.write(
        "nomagic.ply",
        "format ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n",
    );
    d.run(&["convert", "nomagic.ply", "out.pcd"])
        .bad_input(&["nomagic.ply"]);
    assert!(!d.join("out.pcd").exists());
}

#[test]
fn threedtk_file_with_a_non_numeric_line() {
    let d = Dir::new();
    d.write("scan000.3d", "10 20 30\n11 21 31\n12 abc 32\n");
    convert_fails(&d, "scan000.3d", &["scan000.3d", "3", "abc"]);
}

#[test]
fn nan_points() {
    let d = Dir::new();
    d.write("nan.xyz", "0 0 0\n1 nan 3\n");
    convert_fails(&d, "nan.xyz", &["nan.xyz", "non-finite"]);
    d.write("inf.xyz", "0 0 0\n1 inf 3\n");
    convert_fails(&d, "inf.xyz", &["inf.xyz"]);
}

#[test]
fn unknown_extension_and_missing_file() {
    let d = Dir::new();
    d.write("a.las2", "x");
    d.run(&["convert", "a.las2", "out.pcd"])
        .bad_input(&["a.las2", "unknown point cloud format"]);
    d.run(&["convert", "nothere.pcd", "out.pcd"])
        .bad_input(&["nothere.pcd"]);
    d.write("ok.xyz", "1 2 3\n");
    d.run(&["convert", "ok.xyz", "out.foo"])
        .bad_input(&["out.foo"]);
    d.run(&["convert", "ok.xyz", "out.xyz", "--encoding", "binary"])
        .bad_input(&["--encoding"]);
}

#[test]
fn conversions_round_trip_through_every_format() {
    let d = Dir::new();
    d.write("a.xyz", "0.5 -1.25 2 7\n1 2 3 8\n-4 5.5 6 9\n");
    let mut prev = "a.xyz".to_string();
    for (next, enc) in [
        ("b.pcd", "ascii"),
        ("c.pcd", "binary-compressed"),
        ("d.ply", "binary-be"),
        ("e.ply", "ascii"),
        ("f.3d", ""),
        ("g.pcd", "binary"),
        ("h.txt", ""),
    ] {
        let mut args = vec!["convert", prev.as_str(), next];
        if !enc.is_empty() {
            args.extend(["--encoding", enc]);
        }
        let out = d.run(&args).ok();
        assert!(out.contains("3 points"), "{next}: {out}");
        prev = next.to_string();
    }
    let a = cloud::read_cloud(&d.join("a.xyz")).expect("a");
    let h = cloud::read_cloud(&d.join("h.txt")).expect("h");
    for (p, q) in a.points.iter().zip(&h.points) {
        assert!((*p - *q).length() < 1e-4, "{p} vs {q}");
    }
    let info = d.run(&["info", "g.pcd"]).ok();
    assert!(info.contains("points:    3"), "{info}");
}

#[test]
fn real_scans_convert_with_their_point_counts() {
    let Some(real) = util::real_data() else {
        return;
    };
    let d = Dir::new();
    for (file, n) in [
        ("pcl-room/room_scan1.pcd", 112_586),
        ("small-gicp/source.ply", 69_792),
    ] {
        let input = real.join(file);
        let out = d
            .run(&[
                "convert",
                input.to_str().expect("utf8"),
                "x.pcd",
                "--encoding",
                "binary-compressed",
            ])
            .ok();
        assert!(out.contains(&format!("{n} points")), "{file}: {out}");
        assert_eq!(
            cloud::read_cloud(&d.join("x.pcd")).expect("re-read").len(),
            n
        );
    }
}
