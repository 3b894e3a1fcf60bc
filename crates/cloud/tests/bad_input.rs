//! Bad files and failing writes: each gives the right error variant, names the file, never
//! panics, and leaves no output file behind.

use cloud::io::{pcd, ply, threedtk, xyz};
use cloud::{
    read_cloud, write_cloud, write_cloud_as, CloudError, CloudFormat, Label, Organized,
    PcdEncoding, PlyEncoding, PointCloud, Result,
};
use glam::Vec3;
use std::path::{Path, PathBuf};

fn cloud(n: usize) -> PointCloud {
    let mut c = PointCloud::from_points(
        (0..n)
            .map(|i| Vec3::new(i as f32, 0.5, -(i as f32)))
            .collect(),
    );
    c.intensity = Some(vec![1.0; n]);
    c.labels = Some(vec![Label::default(); n]);
    c
}

/// Writes `bytes` as `name` in a fresh folder.
fn file(name: &str, bytes: &[u8]) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join(name);
    std::fs::write(&path, bytes).expect("write");
    (dir, path)
}

/// A file written by our own writer, then altered.
fn written(
    name: &str,
    c: &PointCloud,
    format: CloudFormat,
    edit: impl FnOnce(&mut Vec<u8>),
) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join(name);
    write_cloud_as(&path, c, format).expect("write");
    let mut bytes = std::fs::read(&path).expect("read");
    edit(&mut bytes);
    std::fs::write(&path, bytes).expect("write");
    (dir, path)
}

fn files_in(dir: &Path) -> usize {
    std::fs::read_dir(dir).expect("readable").count()
}

/// The error of reading `path`, checked to name the file; the folder must hold only that file.
fn read_err(dir: &tempfile::TempDir, path: &Path) -> CloudError {
    let e = read_cloud(path).expect_err("must fail");
    let name = path
        .file_name()
        .expect("name")
        .to_string_lossy()
        .into_owned();
    assert!(
        e.to_string().contains(&name),
        "message does not name {name}: {e}"
    );
    assert_eq!(files_in(dir.path()), 1, "nothing written beside the input");
    e
}

const BIN: CloudFormat = CloudFormat::Pcd(PcdEncoding::Binary);
const LZF: CloudFormat = CloudFormat::Pcd(PcdEncoding::BinaryCompressed);

#[test]
fn truncated_binary_pcd() {
    let (dir, path) = written("trunc.pcd", &cloud(100), BIN, |b| b.truncate(b.len() - 10));
    let e = read_err(&dir, &path);
    assert!(matches!(e, CloudError::Truncated { .. }), "{e}");
    assert!(e.to_string().contains("need 2100 bytes, found 2090"), "{e}");
}

#[test]
fn truncated_binary_compressed_pcd() {
    let (dir, path) = written("trunc_lzf.pcd", &cloud(100), LZF, |b| {
        b.truncate(b.len() - 3)
    });
    let e = read_err(&dir, &path);
    assert!(matches!(e, CloudError::Truncated { .. }), "{e}");
    assert!(
        e.to_string().contains("expected") && e.to_string().contains("found"),
        "{e}"
    );
    // A compressed size beyond the end of the file.
    let (dir, path) = written("big_lzf.pcd", &cloud(100), LZF, |b| {
        let at = b
            .windows(23)
            .position(|w| w == b"DATA binary_compressed\n")
            .expect("header")
            + 23;
        b[at..at + 4].copy_from_slice(&u32::MAX.to_le_bytes());
    });
    assert!(matches!(
        read_err(&dir, &path),
        CloudError::Truncated { .. }
    ));
}

#[test]
fn corrupt_lzf_stream_is_an_error_not_a_panic() {
    let data_start = |b: &Vec<u8>| {
        b.windows(23)
            .position(|w| w == b"DATA binary_compressed\n")
            .expect("header")
            + 23
            + 8
    };
    // A first control byte that refers back before the start of the output.
    let (dir, path) = written("bad_lzf.pcd", &cloud(300), LZF, |b| {
        let at = data_start(b);
        b[at] = 0x3f;
    });
    let e = read_err(&dir, &path);
    assert!(
        matches!(e, CloudError::Parse { .. }) && e.to_string().contains("LZF"),
        "{e}"
    );
    // Every single-byte corruption of the stream: an error or wrong values, never a panic.
    let (_dir, path) = written("fuzz.pcd", &cloud(300), LZF, |_| {});
    let good = std::fs::read(&path).expect("read");
    for at in data_start(&good)..good.len() {
        let mut bad = good.clone();
        bad[at] = bad[at].wrapping_add(0x5b);
        std::fs::write(&path, &bad).expect("write");
        let _ = pcd::read_pcd(&path);
    }
}

#[test]
fn pcd_header_errors_are_parse_errors_with_a_line() {
    let head = "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 2\nPOINTS 5\nDATA ascii\n";
    let (dir, path) = file("points.pcd", head.as_bytes());
    let e = read_err(&dir, &path);
    assert!(matches!(e, CloudError::Parse { line: 8, .. }), "{e}");
    let no_z = head
        .replace("x y z", "x y w")
        .replace("POINTS 5", "POINTS 4");
    let (dir, path) = file("no_z.pcd", no_z.as_bytes());
    assert!(matches!(
        read_err(&dir, &path),
        CloudError::Parse { line: 2, .. }
    ));
    // POINTS 10^12 must fail on the data size, before allocating for the points.
    let huge = head
        .replace("WIDTH 2", "WIDTH 1000000000000")
        .replace("HEIGHT 2", "HEIGHT 1");
    for data in ["ascii", "binary", "binary_compressed"] {
        let text = huge
            .replace("POINTS 5", "POINTS 1000000000000")
            .replace("DATA ascii", &format!("DATA {data}"));
        let (dir, path) = file("huge.pcd", format!("{text}1 2 3\n").as_bytes());
        let e = read_err(&dir, &path);
        assert!(
            matches!(e, CloudError::Truncated { .. } | CloudError::Parse { .. }),
            "{e}"
        );
    }
}

#[test]
fn bad_values_in_pcd_data_name_the_point() {
    let head =
        "FIELDS x y z label class\nSIZE 4 4 4 4 1\nTYPE F F F U U\nWIDTH 2\nHEIGHT 1\nDATA ascii\n";
    let (dir, path) = file(
        "class.pcd",
        format!("{head}0 0 0 1 1\n0 0 0 2 200\n").as_bytes(),
    );
    let e = read_err(&dir, &path);
    assert!(
        matches!(e, CloudError::Parse { line: 8, .. }) && e.to_string().contains("point 1"),
        "{e}"
    );
    let (dir, path) = file(
        "word.pcd",
        format!("{head}0 0 0 1 1\n0 zero 0 2 1\n").as_bytes(),
    );
    let e = read_err(&dir, &path);
    assert!(
        e.to_string().contains("'zero'") && matches!(e, CloudError::Parse { line: 8, .. }),
        "{e}"
    );
    // An 8-byte label is converted (with a note), not refused; one beyond u32 is no entity.
    let wide = head.replace("SIZE 4 4 4 4 1", "SIZE 4 4 4 8 1");
    let (_dir, path) = file(
        "wide.pcd",
        format!("{wide}0 0 0 1 1\n0 0 0 4294967296 1\n").as_bytes(),
    );
    let (c, notes) = cloud::read_cloud_with_notes(&path).expect("converted");
    let entities: Vec<u32> = c.labels.expect("labels").iter().map(|l| l.entity).collect();
    assert_eq!(entities, [1, 0]);
    assert_eq!(notes.len(), 2, "{notes:?}");
    // The same unknown class in binary data.
    let mut c = cloud(4);
    c.labels = Some(vec![Label::default(); 4]);
    let (dir, path) = written("class_bin.pcd", &c, BIN, |b| {
        let last = b.len() - 1;
        b[last] = 200;
    });
    let e = read_err(&dir, &path);
    assert!(
        matches!(e, CloudError::Parse { .. })
            && e.to_string()
                .contains("point 3: unknown surface class code 200"),
        "{e}"
    );
}

#[test]
fn unorganised_pcd_with_nan_is_non_finite() {
    let text = "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 3\nHEIGHT 1\nDATA ascii\n1 2 3\nnan nan nan\n4 5 6\n";
    let (dir, path) = file("nan.pcd", text.as_bytes());
    assert!(matches!(
        read_err(&dir, &path),
        CloudError::NonFinite { index: 1, .. }
    ));
    // Organised, the same NaN point is a missing return.
    let organised = text.replace("WIDTH 3\nHEIGHT 1", "WIDTH 1\nHEIGHT 3");
    let (_dir, path) = file("nan.pcd", organised.as_bytes());
    let c = read_cloud(&path).expect("organised clouds may hold missing returns");
    assert_eq!(
        (c.organized, c.valid_count()),
        (Some(Organized { rows: 3, cols: 1 }), 2)
    );
}

#[test]
fn ply_with_a_wrong_header() {
    let (dir, path) = file(
        "magic.ply",
        b"PLY\nformat ascii 1.0\nelement vertex 0\nend_header\n",
    );
    assert!(matches!(
        read_err(&dir, &path),
        CloudError::Parse { line: 1, .. }
    ));
    let (dir, path) = file("nox.ply", b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float y\nproperty float z\nend_header\n1 2\n");
    assert!(matches!(
        read_err(&dir, &path),
        CloudError::Parse { line: 3, .. }
    ));
    let (dir, path) = file(
        "noend.ply",
        b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n",
    );
    assert!(matches!(
        read_err(&dir, &path),
        CloudError::Parse { line: 5, .. }
    ));
    let le = CloudFormat::Ply(PlyEncoding::BinaryLittleEndian);
    let (dir, path) = written("trunc.ply", &cloud(10), le, |b| b.truncate(b.len() - 1));
    let e = read_err(&dir, &path);
    assert!(
        matches!(e, CloudError::Truncated { .. })
            && e.to_string().contains("need 210 bytes, found 209"),
        "{e}"
    );
    let ascii = CloudFormat::Ply(PlyEncoding::Ascii);
    let (dir, path) = written("short.ply", &cloud(10), ascii, |b| b.truncate(b.len() - 12));
    assert!(matches!(
        read_err(&dir, &path),
        CloudError::Truncated { .. } | CloudError::Parse { .. }
    ));
}

#[test]
fn threedtk_with_a_non_numeric_line() {
    let (dir, path) = file("scan000.3d", b"1 2 3\n4 5 6\n7 eight 9\n");
    let e = read_err(&dir, &path);
    assert!(
        matches!(e, CloudError::Parse { line: 3, .. }) && e.to_string().contains("'eight'"),
        "{e}"
    );
    let (dir, path) = file("scan000.pose", b"0 0 0\n0 x 0\n");
    let e = threedtk::read_pose_3dtk(&path).expect_err("bad pose");
    assert!(matches!(e, CloudError::Parse { line: 2, .. }), "{e}");
    assert_eq!(files_in(dir.path()), 1);
    let (_dir, path) = file(
        "scan000.frames",
        b"1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 2\n1 0 0 0 0 1 0 0 0 0 2 0 0 0 0 1 2\n",
    );
    let e = threedtk::read_frames_3dtk(&path).expect_err("not a rotation");
    assert!(matches!(e, CloudError::Parse { line: 2, .. }), "{e}");
}

#[test]
fn xyz_with_nan_is_non_finite() {
    let (dir, path) = file("nan.xyz", b"1 2 3\n4 nan 6\n");
    assert!(matches!(
        read_err(&dir, &path),
        CloudError::NonFinite { index: 1, .. }
    ));
}

#[test]
fn unknown_extension() {
    let (dir, path) = file("cloud.las", b"1 2 3\n");
    assert!(matches!(
        read_err(&dir, &path),
        CloudError::UnknownFormat { .. }
    ));
    let out = dir.path().join("out.obj");
    assert!(matches!(
        write_cloud(&out, &cloud(3)),
        Err(CloudError::UnknownFormat { .. })
    ));
    assert_eq!(files_in(dir.path()), 1);
}

fn every_format() -> Vec<(&'static str, CloudFormat)> {
    let mut v: Vec<_> = [
        PcdEncoding::Ascii,
        PcdEncoding::Binary,
        PcdEncoding::BinaryCompressed,
    ]
    .map(|e| ("pcd", CloudFormat::Pcd(e)))
    .to_vec();
    v.extend(
        [
            PlyEncoding::Ascii,
            PlyEncoding::BinaryLittleEndian,
            PlyEncoding::BinaryBigEndian,
        ]
        .map(|e| ("ply", CloudFormat::Ply(e))),
    );
    v.extend([("xyz", CloudFormat::Xyz), ("3d", CloudFormat::ThreeDtk)]);
    v
}

#[test]
fn failing_writes_leave_no_file() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut mismatched = cloud(5);
    mismatched.labels = Some(vec![Label::default(); 4]);
    let mut nan = cloud(5);
    nan.points[2] = Vec3::NAN;
    for (ext, format) in every_format() {
        let missing = dir.path().join("no such folder").join(format!("c.{ext}"));
        let e = write_cloud_as(&missing, &cloud(5), format).expect_err("no folder");
        assert!(
            matches!(e, CloudError::Io { .. }) && e.to_string().contains("c."),
            "{e}"
        );
        let path = dir.path().join(format!("c.{ext}"));
        let e = write_cloud_as(&path, &mismatched, format).expect_err("mismatch");
        assert!(matches!(e, CloudError::Inconsistent(_)), "{format:?}: {e}");
        let e = write_cloud_as(&path, &nan, format).expect_err("NaN in an unorganised cloud");
        assert!(
            matches!(e, CloudError::NonFinite { index: 2, .. }),
            "{format:?}: {e}"
        );
        assert_eq!(files_in(dir.path()), 0, "{format:?} left a file");
    }
    // The format functions check the cloud themselves too.
    let path = dir.path().join("direct");
    let direct: [&dyn Fn() -> Result<()>; 4] = [
        &|| pcd::write_pcd(&path, &mismatched, PcdEncoding::Binary),
        &|| ply::write_ply(&path, &mismatched, PlyEncoding::Ascii),
        &|| xyz::write_xyz(&path, &mismatched),
        &|| threedtk::write_3d(&path, &mismatched),
    ];
    for write in direct {
        assert!(matches!(write(), Err(CloudError::Inconsistent(_))));
    }
    assert_eq!(files_in(dir.path()), 0);
}
