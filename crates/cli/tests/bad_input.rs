//! The bad-input regression suite: the real binary over the committed bad inputs in
//! `tests/data/bad/` (each named after what it pins) and over outputs that would clash with
//! inputs. Every case asserts the exit code, that the message names the file or option and the
//! true problem, that nothing panics or aborts, and that no partial or overwritten file is left.

mod util;

use std::path::{Path, PathBuf};
use util::Dir;

/// A committed bad input, copied into the test's folder (so nothing in the repository is touched).
fn bad(d: &Dir, name: &str) -> PathBuf {
    let src = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/bad")
        .join(name);
    let dst = d.join(name);
    std::fs::copy(&src, &dst).unwrap_or_else(|e| panic!("{}: {e}", src.display()));
    dst
}

fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

/// No file but `keep` in the folder (no partial output, no temporary file).
fn only(d: &Dir, keep: &[&str]) {
    let extra: Vec<String> = d
        .listing(".")
        .into_iter()
        .filter(|f| !keep.contains(&f.as_str()))
        .collect();
    assert!(extra.is_empty(), "files left behind: {extra:?}");
}

/// A tiny scan folder of the default building (two scans, a small laser).
fn scan_folder(d: &Dir, name: &str) -> PathBuf {
    let cfg = d.small_config();
    d.scan_default_building(name, &["2,0,0", "3,0,0"], &cfg)
        .ok();
    d.join(name)
}

#[test]
fn pcd_ascii_count_of_4294967296_is_bad_input_not_an_abort() {
    let d = Dir::new();
    let f = bad(&d, "pcd_ascii_count_4294967296.pcd");
    for cmd in [vec!["info", s(&f)], vec!["convert", s(&f), "out.ply"]] {
        let r = d.run(&cmd);
        r.bad_input(&["pcd_ascii_count_4294967296.pcd"]);
        assert!(!r.stderr().contains("memory allocation"), "{}", r.stderr());
    }
    only(&d, &["pcd_ascii_count_4294967296.pcd"]);
}

#[test]
fn empty_xyz_and_3d_files_are_refused() {
    let d = Dir::new();
    for f in ["empty.xyz", "empty.3d"] {
        let p = bad(&d, f);
        d.run(&["info", s(&p)]).bad_input(&[f, "no points"]);
    }
}

#[test]
fn a_3d_file_cut_mid_line_and_a_ply_with_extra_rows_are_refused() {
    let d = Dir::new();
    let cut = bad(&d, "threedtk_cut_mid_file.3d");
    d.run(&["info", s(&cut)])
        .bad_input(&["threedtk_cut_mid_file.3d"]);
    let ply = bad(&d, "ply_more_rows_than_declared.ply");
    d.run(&["info", s(&ply)])
        .bad_input(&["ply_more_rows_than_declared.ply"]);
}

#[test]
fn a_signed_label_field_is_converted_with_a_note_and_a_bom_is_accepted() {
    let d = Dir::new();
    let signed = bad(&d, "pcd_label_signed.pcd");
    let r = d.run(&["info", s(&signed)]);
    let out = r.ok();
    assert!(out.contains("points:    2"), "{out}");
    assert!(
        r.stderr().contains("note:") && r.stderr().contains("label"),
        "{}",
        r.stderr()
    );
    let bom = bad(&d, "pcd_with_bom.pcd");
    assert!(d.run(&["info", s(&bom)]).ok().contains("points:    2"));
}

#[test]
fn a_non_finite_3dtk_line_is_reported_as_written_with_its_line() {
    let d = Dir::new();
    let f = bad(&d, "threedtk_inf.3d");
    let r = d.run(&["info", s(&f)]);
    r.bad_input(&["threedtk_inf.3d", "2"]);
    assert!(!r.stderr().contains("NaN"), "{}", r.stderr());
}

#[test]
fn a_building_with_a_1e30_m_box_is_not_valid() {
    let d = Dir::new();
    let f = bad(&d, "building_box_1e30.toml");
    d.run(&["building", "check", s(&f)])
        .bad_input(&["building_box_1e30.toml", "boxes[0]"]);
}

#[test]
fn nul_bytes_from_a_file_are_never_echoed_to_the_terminal() {
    let d = Dir::new();
    let f = bad(&d, "building_with_nul.toml");
    let r = d.run(&["building", "check", s(&f)]);
    r.bad_input(&["building_with_nul.toml"]);
    assert!(!r.stderr().contains('\0'), "raw NUL in {:?}", r.stderr());
}

#[test]
fn a_config_section_of_another_stage_is_checked_by_every_command() {
    let d = Dir::new();
    let cfg = bad(&d, "config_max_iterations_0.toml");
    d.scan_default_building("scans", &["2,0,0"], &cfg)
        .bad_input(&["config_max_iterations_0.toml", "max_iterations"]);
    assert!(
        !d.join("scans").exists(),
        "scan ran with a bad configuration"
    );
}

#[test]
fn a_heading_of_1e300_degrees_is_refused() {
    let d = Dir::new();
    let b = d.default_building();
    d.run(&[
        "scan",
        "--building",
        s(&b),
        "--pose",
        "2,0,1e300",
        "--out",
        "scans",
    ])
    .bad_input(&["pose 0", "yaw"]);
    let written = d.join("scans");
    assert!(!written.exists() || std::fs::read_dir(&written).map(|r| r.count()).unwrap_or(0) == 0);
}

#[test]
fn register_sequence_never_replaces_the_folders_ground_truth() {
    let d = Dir::new();
    let dir = scan_folder(&d, "scans");
    let truth = std::fs::read(dir.join("poses.txt")).expect("truth written");
    d.run(&["register", "--sequence", "scans", "--out", "scans"])
        .bad_input(&["poses.txt", "would replace the input"]);
    assert_eq!(
        std::fs::read(dir.join("poses.txt")).expect("still there"),
        truth
    );
    assert!(!dir.join("map.pcd").exists() && !dir.join("registration.json").exists());
}

#[test]
fn convert_onto_its_own_input_is_refused() {
    let d = Dir::new();
    let f = d.write("a.xyz", "0 0 0\n1 1 1\n");
    d.run(&["convert", "a.xyz", "./a.xyz"])
        .bad_input(&["a.xyz", "would replace the input"]);
    assert_eq!(std::fs::read_to_string(f).expect("kept"), "0 0 0\n1 1 1\n");
}

#[test]
fn a_3dtk_folder_with_one_pose_file_missing_is_refused() {
    let d = Dir::new();
    std::fs::create_dir(d.join("seq")).expect("mkdir");
    for k in 0..3 {
        d.write(
            &format!("seq/scan00{k}.3d"),
            "100 200 300\n110 210 310\n120 220 330\n",
        );
        if k != 1 {
            d.write(&format!("seq/scan00{k}.pose"), "0 0 0\n0 0 0\n");
        }
    }
    d.run(&["register", "--sequence", "seq", "--out", "out"])
        .bad_input(&["scan001.3d", "scan001.pose"]);
    assert!(!d.join("out").exists());
}

#[test]
fn pose_names_with_the_file_extension_place_their_scans() {
    let d = Dir::new();
    d.write("a.xyz", "0 0 0\n");
    d.write("b.xyz", "1 1 1\n");
    // Three poses for two clouds: only matching by name can place them, and the names carry
    // the extension. (Before, this was "3 poses for 2 clouds, and not every cloud's file stem
    // names a pose".) The two-point cloud then fails later, in the map stage, for its own reason.
    d.write(
        "poses.txt",
        "a.xyz 1 0 0 5  0 1 0 0  0 0 1 0  0 0 0 1\n\
         b.xyz 1 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1\n\
         c.xyz 1 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1\n",
    );
    let r = d.run(&[
        "map",
        "a.xyz",
        "b.xyz",
        "--poses",
        "poses.txt",
        "--out",
        "m",
    ]);
    assert!(!r.stderr().contains("file stem"), "{}", r.stderr());
    assert!(!r.stderr().contains("panicked"), "{}", r.stderr());
}

#[test]
fn paths_that_cannot_be_used_are_bad_input() {
    let d = Dir::new();
    d.write("a.xyz", "0 0 0\n1 1 1\n");
    std::fs::create_dir(d.join("folder.xyz")).expect("mkdir");
    d.write("file", "x");
    // An input that is a folder.
    d.run(&["info", "folder.xyz"]).bad_input(&["folder.xyz"]);
    // An output whose parent is a file, and an output folder that is a file.
    d.run(&["convert", "a.xyz", "file/out.ply"])
        .bad_input(&["file/out.ply"]);
    d.run(&["simulate", "--out", "file"]).bad_input(&["file"]);
    // A missing output folder.
    d.run(&["convert", "a.xyz", "missing/out.ply"])
        .bad_input(&["missing/out.ply"]);
    // The OS's text once, not twice.
    let r = d.run(&["info", "nothing.xyz"]);
    r.bad_input(&["nothing.xyz"]);
    assert_eq!(
        r.stderr().matches("os error 2").count(),
        1,
        "{}",
        r.stderr()
    );
}

#[test]
fn a_scenario_out_of_range_names_its_file() {
    let d = Dir::new();
    let f = bad(&d, "scenario_time_limit_1e300.toml");
    d.run(&["simulate", "--scenario", s(&f), "--out", "sim"])
        .bad_input(&["scenario_time_limit_1e300.toml", "time_limit_s"]);
    assert!(!d.join("sim").exists());
}

#[test]
fn run_checks_its_scenario_before_leaving_any_stage_behind() {
    let d = Dir::new();
    scan_folder(&d, "scans");
    let f = bad(&d, "scenario_door_nowhere.toml");
    let r = d.run(&["run", "scans", "--scenario", s(&f), "--out", "out"]);
    r.bad_input(&["door@90,90"]);
    assert!(!d.join("out/registration").exists() && !d.join("out/map").exists());
}

#[test]
fn a_plot_path_that_cannot_be_written_is_bad_input() {
    let d = Dir::new();
    let dir = scan_folder(&d, "scans");
    let a = dir.join("scan000.pcd");
    let b = dir.join("scan001.pcd");
    d.run(&["register", s(&a), s(&b), "--plot", "rmse.gif"])
        .bad_input(&["rmse.gif"]);
    d.run(&["register", s(&a), s(&b), "--plot", "missing/rmse.svg"])
        .bad_input(&["missing"]);
}

#[test]
fn an_impossible_device_choice_says_what_is_wrong_without_nan() {
    let d = Dir::new();
    let dir = scan_folder(&d, "scans");
    let r = d.run(&[
        "register",
        s(&dir.join("scan000.pcd")),
        s(&dir.join("scan001.pcd")),
        "--method",
        "gicp",
        "--device",
        "gpu",
    ]);
    r.bad_input(&["device = gpu", "GICP"]);
    assert!(!r.stderr().contains("NaN"), "{}", r.stderr());
}
