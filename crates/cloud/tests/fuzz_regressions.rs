//! Every input in `tests/data/bad/` (the original findings and the minimised inputs of each
//! crash, OOM or timeout the fuzz targets in `fuzz/` found) is read the way its fuzz target
//! reads it, and must give what the targets check: a clean error that names the file, is bad
//! input and holds no control character, or a consistent cloud; never a panic or an abort.
//!
//! The extension picks the reader: `.pose`, `.frames`, `.poses` (a pose file), else the cloud
//! reader of [`cloud::read_cloud`]. Some files have their own test below as well.

use cloud::fuzzing::{
    read_cloud_bytes, read_frames_3dtk_bytes, read_pose_3dtk_bytes, read_poses_bytes,
};
use cloud::{BadInput, CloudError};
use std::path::{Path, PathBuf};

fn bad_files() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/bad");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("tests/data/bad")
        .map(|e| e.expect("entry").path())
        .collect();
    files.sort();
    files
}

/// Reads `bytes` as its fuzz target does: `Ok(())` for a consistent result, else the error.
fn read(path: &Path, bytes: &[u8]) -> Result<(), CloudError> {
    match path.extension().and_then(|e| e.to_str()) {
        Some("pose") => read_pose_3dtk_bytes(path, bytes).map(|_| ()),
        Some("frames") => read_frames_3dtk_bytes(path, bytes).map(|_| ()),
        Some("poses") => read_poses_bytes(path, bytes).map(|_| ()),
        _ => read_cloud_bytes(path, bytes).map(|(c, notes)| {
            c.validate().expect("consistent");
            for n in notes {
                assert!(!n.chars().any(char::is_control), "{n:?}");
            }
        }),
    }
}

#[test]
fn every_committed_bad_file_is_refused_cleanly() {
    let files = bad_files();
    assert!(files.len() >= 2, "{files:?}");
    for path in files {
        let bytes = std::fs::read(&path).expect("read");
        let Err(e) = read(&path, &bytes) else {
            continue;
        };
        let text = e.to_string();
        let name = path.file_name().expect("name").to_string_lossy();
        assert!(
            text.contains(&*name),
            "{name}: does not name the file: {text}"
        );
        assert!(!text.chars().any(char::is_control), "{name}: {text:?}");
        assert!(e.is_bad_input(), "{name}: {text}");
    }
}

fn error_of(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/bad")
        .join(name);
    let bytes = std::fs::read(&path).expect("read");
    read(&path, &bytes).expect_err("refused").to_string()
}

#[test]
fn ply_header_line_with_a_control_character_is_escaped() {
    let e = error_of("ply_header_control_char.ply");
    assert!(
        e.contains("unexpected header line 'e\\u{13}lement vertex 30'"),
        "{e}"
    );
}

#[test]
fn the_original_findings_give_what_the_issue_asks() {
    let e = error_of("pcd_ascii_count_4294967296.pcd");
    assert!(e.contains("expected 4294967298 values, found 3"), "{e}");
    for f in ["empty.xyz", "empty.3d"] {
        let e = error_of(f);
        assert!(e.contains(&format!("{f}: no points")), "{e}");
    }
    let e = error_of("threedtk_cut_mid_file.3d");
    assert!(
        e.contains("truncated: line 3 ('120 22') does not end with a newline"),
        "{e}"
    );
    let e = error_of("threedtk_inf.3d");
    assert!(
        e.contains("threedtk_inf.3d:2: 'inf' is not a finite number"),
        "{e}"
    );
    let e = error_of("ply_more_rows_than_declared.ply");
    assert!(
        e.contains("ply_more_rows_than_declared.ply:10: a line beyond"),
        "{e}"
    );
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/bad");
    let (c, notes) =
        cloud::read_cloud_with_notes(&dir.join("pcd_label_signed.pcd")).expect("converted");
    let entities: Vec<u32> = c.labels.expect("labels").iter().map(|l| l.entity).collect();
    assert_eq!((entities, notes.len()), (vec![7, 0], 2));
    assert_eq!(
        cloud::read_cloud(&dir.join("pcd_with_bom.pcd"))
            .expect("BOM")
            .len(),
        2
    );
}
