//! The reliability findings: silently wrong acceptance (empty and cut-off text files, PLY data
//! beyond its declared count), foreign field types converted or skipped with notes instead of
//! refused, byte-order marks, escaped control characters, I/O messages and exit-code classes.

use cloud::io::threedtk::{read_3d, read_frames_3dtk, read_pose_3dtk};
use cloud::{
    read_cloud, read_cloud_with_notes, read_poses, BadInput, CloudError, EntityClass, PointCloud,
};
use glam::Vec3;
use std::path::PathBuf;

fn file(name: &str, bytes: &[u8]) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join(name);
    std::fs::write(&path, bytes).expect("write");
    (dir, path)
}

/// The error of reading `bytes` as `name`, checked to name the file and to be bad input.
fn err(name: &str, bytes: &[u8]) -> CloudError {
    let (_dir, path) = file(name, bytes);
    let e = read_cloud(&path).expect_err("must fail");
    assert!(e.to_string().contains(name), "names {name}: {e}");
    assert!(e.is_bad_input(), "{e}");
    e
}

fn notes_of(name: &str, bytes: &[u8]) -> (PointCloud, Vec<String>) {
    let (_dir, path) = file(name, bytes);
    let (c, notes) = read_cloud_with_notes(&path).expect("reads");
    for n in &notes {
        assert!(n.starts_with(&path.display().to_string()), "{n}");
    }
    (c, notes)
}

// ---- 3. silently wrong acceptance ----

#[test]
fn empty_xyz_and_3d_files_have_no_points() {
    for name in ["empty.xyz", "empty.txt", "empty.3d"] {
        for text in ["", "\n\n  \n", "# a comment only\n"] {
            let e = err(name, text.as_bytes());
            assert!(e.to_string().contains(": no points"), "{e}");
        }
    }
    // A shape line alone holds no point either.
    let e = err("shape.3d", b"360 x 225\n");
    assert!(e.to_string().contains("no points"), "{e}");
}

#[test]
fn threedtk_cut_inside_a_number_is_truncated() {
    // The last line lacks its newline: the file was cut (here inside "9.25").
    let e = err("cut.3d", b"1 2 3\n4 5 6\n7 8 9.2");
    assert!(matches!(e, CloudError::Truncated { .. }), "{e}");
    assert!(e.to_string().contains("line 3 ('7 8 9.2')"), "{e}");
    // A last line with fewer than 3 numbers names its line.
    let e = err("short.3d", b"1 2 3\n4 5\n");
    assert!(matches!(e, CloudError::Parse { line: 2, .. }), "{e}");
    // Complete files (CRLF, trailing blank lines) are fine.
    let (_dir, path) = file("ok.3d", b"1 2 3\r\n4 5 6\r\n\r\n");
    assert_eq!(read_3d(&path).expect("complete").len(), 2);
}

#[test]
fn ply_ascii_with_more_vertex_lines_than_declared() {
    let head = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n";
    let e = err(
        "extra.ply",
        format!("{head}end_header\n1 2 3\n4 5 6\n7 8 9\n").as_bytes(),
    );
    assert!(matches!(e, CloudError::Parse { line: 10, .. }), "{e}");
    assert!(e.to_string().contains("vertex 2"), "{e}");
    // Declared faces after the vertices are fine; one line more is not.
    let faces = format!(
        "{head}element face 1\nproperty list uchar int vertex_indices\nend_header\n1 2 3\n4 5 6\n3 0 1 1\n\n"
    );
    let (_dir, path) = file("faces.ply", faces.as_bytes());
    assert_eq!(read_cloud(&path).expect("valid").len(), 2);
    let e = err("faces_extra.ply", format!("{faces}3 0 1 1\n").as_bytes());
    assert!(e.to_string().contains("face 1"), "{e}");
}

#[test]
fn ply_binary_with_bytes_beyond_the_declared_data() {
    let head = "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
    let point: Vec<u8> = [1.0f32, 2.0, 3.0]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    let mut two = head.as_bytes().to_vec();
    two.extend(&point);
    two.extend(&point);
    let e = err("extra_bin.ply", &two);
    assert!(e.to_string().contains("12 bytes after the data"), "{e}");
    // Trailing whitespace is allowed.
    let mut one = head.as_bytes().to_vec();
    one.extend(&point);
    one.extend(b"\r\n");
    let (_dir, path) = file("newline.ply", &one);
    assert_eq!(read_cloud(&path).expect("valid").len(), 1);
}

// ---- 4. foreign field types: converted or skipped, with notes ----

#[test]
fn pcd_signed_label_is_converted_with_notes() {
    let head = "FIELDS x y z label\nSIZE 4 4 4 4\nTYPE F F F I\nWIDTH 3\nHEIGHT 1\n";
    let ascii = format!("{head}DATA ascii\n0 0 0 7\n1 1 1 -1\n2 2 2 0\n");
    let mut binary = format!("{head}DATA binary\n").into_bytes();
    for (k, l) in [7i32, -1, 0].iter().enumerate() {
        [k as f32; 3]
            .iter()
            .for_each(|v| binary.extend(v.to_le_bytes()));
        binary.extend(l.to_le_bytes());
    }
    for (name, bytes) in [("ascii.pcd", ascii.into_bytes()), ("binary.pcd", binary)] {
        let (c, notes) = notes_of(name, &bytes);
        let labels = c.labels.expect("labels");
        let entities: Vec<u32> = labels.iter().map(|l| l.entity).collect();
        assert_eq!(entities, [7, 0, 0], "{name}");
        assert!(labels.iter().all(|l| l.class == EntityClass::Unknown));
        assert_eq!(notes.len(), 2, "{notes:?}");
        assert!(
            notes[0].contains("field label (TYPE I, SIZE 4) read as entity ids"),
            "{notes:?}"
        );
        assert!(
            notes[1].contains("1 point(s)") && notes[1].contains("-1 at point 1"),
            "{notes:?}"
        );
    }
}

#[test]
fn pcd_foreign_types_and_fields_are_converted_or_skipped_with_notes() {
    // class as I4 with valid codes: converted; x y z as I2: read as metres; rgb and a
    // COUNT 3 normal: skipped; padding: silently.
    let text = "FIELDS x y z _ rgb normal class\nSIZE 2 2 2 1 4 4 4\nTYPE I I I U F F I\nCOUNT 1 1 1 1 1 3 1\nWIDTH 2\nHEIGHT 1\nDATA ascii\n1 2 3 0 0.5 0 0 1 3\n-1 -2 -3 0 0.5 0 0 1 1\n";
    let (c, notes) = notes_of("foreign.pcd", text.as_bytes());
    assert_eq!(
        c.points,
        [Vec3::new(1.0, 2.0, 3.0), Vec3::new(-1.0, -2.0, -3.0)]
    );
    let classes: Vec<EntityClass> = c.labels.expect("labels").iter().map(|l| l.class).collect();
    assert_eq!(classes, [EntityClass::Wall, EntityClass::Floor]);
    let all = notes.join("\n");
    assert!(
        all.contains("field x (TYPE I, SIZE 2) read as metres"),
        "{all}"
    );
    assert!(
        all.contains("field(s) rgb, normal not used by semsim (skipped)"),
        "{all}"
    );
    assert!(
        all.contains("field class (TYPE I, SIZE 4) read as class codes"),
        "{all}"
    );
    assert!(!all.contains(" _"), "{all}");
    // A class field of another type with values that are no class codes: skipped, and with
    // no label field there are no labels at all.
    let text = "FIELDS x y z class\nSIZE 4 4 4 4\nTYPE F F F F\nWIDTH 2\nHEIGHT 1\nDATA ascii\n0 0 0 1\n0 0 0 42.5\n";
    let (c, notes) = notes_of("float_class.pcd", text.as_bytes());
    assert_eq!(c.labels, None);
    assert!(
        notes.join("\n").contains("e.g. 42.5 at point 1): skipped"),
        "{notes:?}"
    );
    // A class of semsim's own type (U1) with an unknown code stays an error.
    let text =
        "FIELDS x y z class\nSIZE 4 4 4 1\nTYPE F F F U\nWIDTH 1\nHEIGHT 1\nDATA ascii\n0 0 0 42\n";
    let e = err("own_class.pcd", text.as_bytes());
    assert!(
        e.to_string().contains("unknown surface class code 42"),
        "{e}"
    );
}

#[test]
fn ply_signed_label_and_foreign_class_are_converted_with_notes() {
    let text = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty int label\nproperty float class\nend_header\n0 0 0 255 -5 3\n1 1 1 0 9 1\n";
    let (c, notes) = notes_of("labels.ply", text.as_bytes());
    let labels = c.labels.expect("labels");
    assert_eq!(labels.iter().map(|l| l.entity).collect::<Vec<_>>(), [0, 9]);
    assert_eq!(
        labels.iter().map(|l| l.class).collect::<Vec<_>>(),
        [EntityClass::Wall, EntityClass::Floor]
    );
    let all = notes.join("\n");
    assert!(all.contains("vertex property(ies) red not used"), "{all}");
    assert!(
        all.contains("vertex property label (int) read as entity ids"),
        "{all}"
    );
    assert!(all.contains("-5 at point 0: read as no entity"), "{all}");
    assert!(
        all.contains("vertex property class (float) read as class codes"),
        "{all}"
    );
}

#[test]
fn semsims_own_files_read_without_notes() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut c = PointCloud::from_points(vec![Vec3::ONE; 3]);
    c.intensity = Some(vec![0.5; 3]);
    c.labels = Some(vec![cloud::Label::default(); 3]);
    for name in ["a.pcd", "a.ply", "a.xyz", "a.3d"] {
        let path = dir.path().join(name);
        cloud::write_cloud(&path, &c).expect("write");
        let (_, notes) = read_cloud_with_notes(&path).expect("read");
        assert!(notes.is_empty(), "{name}: {notes:?}");
    }
}

// ---- 5. messages ----

#[test]
fn a_byte_order_mark_is_accepted_everywhere() {
    const BOM: &str = "\u{feff}";
    let cases: [(&str, String); 4] = [
        ("bom.pcd", format!("{BOM}# c\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\nHEIGHT 1\nDATA ascii\n1 2 3\n")),
        ("bom.ply", format!("{BOM}ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 3\n")),
        ("bom.xyz", format!("{BOM}1 2 3\n")),
        ("bom.3d", format!("{BOM}1 2 3\n")),
    ];
    for (name, text) in cases {
        let (_dir, path) = file(name, text.as_bytes());
        assert_eq!(read_cloud(&path).expect(name).len(), 1);
    }
    let (_dir, path) = file("scan000.pose", format!("{BOM}0 0 0\n0 0 0\n").as_bytes());
    read_pose_3dtk(&path).expect("pose");
    let (_dir, path) = file(
        "scan000.frames",
        format!("{BOM}1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 2\n").as_bytes(),
    );
    read_frames_3dtk(&path).expect("frames");
    let (_dir, path) = file(
        "poses.txt",
        format!("{BOM}# c\ns 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n").as_bytes(),
    );
    assert_eq!(read_poses(&path).expect("poses").len(), 1);
}

#[test]
fn control_characters_from_a_file_are_escaped_in_messages() {
    let e = err("nul.pcd", b"\0\x1b[31mred\nDATA ascii\n").to_string();
    assert!(
        e.contains("unknown header keyword '\\u{0}\\u{1b}[31mred'"),
        "{e}"
    );
    assert!(!e.chars().any(|c| c.is_control()), "{e:?}");
    let e = err("esc.xyz", b"1 2 \x1b]0;title\x07\n").to_string();
    assert!(!e.chars().any(|c| c.is_control()), "{e:?}");
    assert!(e.contains("\\u{1b}]0;title\\u{7}"), "{e}");
    let e = err(
        "bad.ply",
        b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\0\nend_header\n",
    )
    .to_string();
    assert!(!e.chars().any(|c| c.is_control()), "{e:?}");
    // Long tokens are shortened.
    let long = format!("1 2 {}\n", "x".repeat(10_000));
    let e = err("long.xyz", long.as_bytes()).to_string();
    assert!(e.len() < 300, "{}", e.len());
}

#[test]
fn threedtk_infinity_names_the_line_and_the_text_as_written() {
    let e = err("inf.3d", b"1 2 3\ninf 0 0\n");
    assert!(matches!(e, CloudError::Parse { line: 2, .. }), "{e}");
    assert!(
        e.to_string().contains("'inf' is not a finite number"),
        "{e}"
    );
    let e = err("nan.3d", b"1 2 3\n0 NaN 0\n");
    assert!(e.to_string().contains(":2: 'NaN'"), "{e}");
}

/// The message as anyhow's `{:#}` prints it: the error, then each source after `: `.
fn chain(e: &(dyn std::error::Error + 'static)) -> String {
    let mut text = e.to_string();
    let mut cur = e.source();
    while let Some(s) = cur {
        text = format!("{text}: {s}");
        cur = s.source();
    }
    text
}

#[test]
fn the_os_error_text_appears_once_in_the_chain() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("missing.pcd");
    let e = read_cloud(&path).expect_err("missing");
    let text = chain(&e);
    assert_eq!(text.matches("os error 2").count(), 1, "{text}");
    assert!(
        text.contains("missing.pcd: No such file or directory"),
        "{text}"
    );
    assert_eq!(text, e.to_string(), "complete with Display alone");
}

// ---- 6. paths and exit codes ----

#[test]
fn unusable_paths_are_bad_input() {
    let dir = tempfile::tempdir().expect("tempdir");
    let missing = dir.path().join("missing.xyz");
    assert!(read_cloud(&missing).expect_err("missing").is_bad_input());
    // A folder named like a cloud.
    let folder = dir.path().join("scans.pcd");
    std::fs::create_dir(&folder).expect("mkdir");
    let e = read_cloud(&folder).expect_err("folder");
    assert_eq!(
        e.to_string(),
        format!("{}: is a folder, not a file", folder.display())
    );
    assert!(e.is_bad_input());
    for e in [
        read_poses(&folder).map(|_| ()).expect_err("folder"),
        read_pose_3dtk(&folder).map(|_| ()).expect_err("folder"),
        read_frames_3dtk(&folder).map(|_| ()).expect_err("folder"),
    ] {
        assert!(e.to_string().ends_with("is a folder, not a file"), "{e}");
    }
    // A path through a file.
    let (_d, plain) = file("plain.xyz", b"1 2 3\n");
    let e = read_cloud(&plain.join("x.xyz")).expect_err("not a folder");
    assert!(e.is_bad_input(), "{e}");
    // Writing into a folder that does not exist.
    let e = cloud::write_cloud(&dir.path().join("no/such/out.pcd"), &PointCloud::default())
        .expect_err("no folder");
    assert!(e.is_bad_input(), "{e}");
}
