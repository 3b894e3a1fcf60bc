//! The ASPRS classification (LAS `classification`) in PCD (field `classification`, U1) and
//! PLY (vertex property `uchar classification`): written where the cloud has one, read back
//! in every encoding, read from files written by hand with other types, and independent of
//! semsim's own `label` and `class`.

use cloud::io::{pcd, ply};
use cloud::{
    read_cloud_with_notes, EntityClass, Label, Organized, PcdEncoding, PlyEncoding, PointCloud,
};
use glam::{Quat, Vec3};
use std::path::{Path, PathBuf};

const PCD_ENCODINGS: [PcdEncoding; 3] = [
    PcdEncoding::Ascii,
    PcdEncoding::Binary,
    PcdEncoding::BinaryCompressed,
];
const PLY_ENCODINGS: [PlyEncoding; 3] = [
    PlyEncoding::Ascii,
    PlyEncoding::BinaryLittleEndian,
    PlyEncoding::BinaryBigEndian,
];

/// A 3 x 4 organised cloud with one missing return, every channel, and classification codes
/// over the whole range 0..=255.
fn full() -> PointCloud {
    let n = 12;
    let mut c = PointCloud::from_points(
        (0..n)
            .map(|i| {
                if i == 5 {
                    Vec3::NAN
                } else {
                    Vec3::new(i as f32 * 0.5, -(i as f32) / 3.0, 1.25)
                }
            })
            .collect(),
    );
    c.intensity = Some((0..n).map(|i| i as f32 * 1.5).collect());
    c.labels = Some(
        (0..n)
            .map(|i| Label {
                entity: i as u32 * 3,
                class: EntityClass::ALL[i % EntityClass::ALL.len()],
            })
            .collect(),
    );
    c.classification = Some(
        (0..n)
            .map(|i| [0u8, 1, 2, 6, 9, 17, 64, 255][i % 8])
            .collect(),
    );
    c.organized = Some(Organized { rows: 3, cols: 4 });
    c.sensor_origin = Vec3::new(0.5, 0.25, 2.0);
    c.sensor_orientation = Quat::from_rotation_z(0.4);
    c
}

/// Only points and classification.
fn bare() -> PointCloud {
    let mut c = PointCloud::from_points(vec![Vec3::X, Vec3::Y, Vec3::Z]);
    c.classification = Some(vec![2, 6, 250]);
    c
}

/// The cloud as a format without organised shape or sensor pose gives it back.
fn as_ply(c: &PointCloud) -> PointCloud {
    PointCloud {
        sensor_origin: Vec3::ZERO,
        sensor_orientation: Quat::IDENTITY,
        ..c.without_invalid()
    }
}

/// Equal, NaN points included (`PointCloud`'s `==` has NaN unequal to itself).
fn assert_same(a: &PointCloud, b: &PointCloud, what: &str) {
    let bits = |c: &PointCloud| -> Vec<[u32; 3]> {
        c.points
            .iter()
            .map(|p| p.to_array().map(f32::to_bits))
            .collect()
    };
    assert_eq!(bits(a), bits(b), "{what}: points");
    let finite = |c: &PointCloud| PointCloud {
        points: Vec::new(),
        ..c.clone()
    };
    assert_eq!(finite(a), finite(b), "{what}");
}

fn file(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).expect("write");
    path
}

/// The header up to its last line (`DATA ...` in PCD, `end_header` in PLY), not included.
fn header_of(path: &Path) -> String {
    let bytes = std::fs::read(path).expect("written");
    let last: &[u8] = if path.extension().is_some_and(|e| e == "pcd") {
        b"\nDATA "
    } else {
        b"\nend_header\n"
    };
    let end = bytes
        .windows(last.len())
        .position(|w| w == last)
        .expect("a header");
    String::from_utf8_lossy(&bytes[..=end]).into_owned()
}

#[test]
fn pcd_keeps_the_classification_in_every_encoding() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("c.pcd");
    for cloud in [full(), full().without_invalid(), bare()] {
        for enc in PCD_ENCODINGS {
            pcd::write_pcd(&path, &cloud, enc).expect("write");
            let (back, notes) = read_cloud_with_notes(&path).expect("read");
            assert_same(&back, &cloud, &format!("{enc:?}"));
            assert!(notes.is_empty(), "{enc:?}: {notes:?}");
        }
    }
    pcd::write_pcd(&path, &full(), PcdEncoding::Binary).expect("write");
    let head = header_of(&path);
    assert!(
        head.contains("FIELDS x y z intensity label class classification\nSIZE 4 4 4 4 4 1 1\nTYPE F F F F U U U\n"),
        "{head}"
    );
}

#[test]
fn ply_keeps_the_classification_in_every_encoding() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("c.ply");
    for cloud in [full(), bare()] {
        for enc in PLY_ENCODINGS {
            ply::write_ply(&path, &cloud, enc).expect("write");
            let (back, notes) = read_cloud_with_notes(&path).expect("read");
            assert_same(&back, &as_ply(&cloud), &format!("{enc:?}"));
            assert!(notes.is_empty(), "{enc:?}: {notes:?}");
        }
    }
    ply::write_ply(&path, &full(), PlyEncoding::BinaryBigEndian).expect("write");
    let head = header_of(&path);
    assert!(
        head.ends_with("property float intensity\nproperty uint label\nproperty uchar class\nproperty uchar classification\n"),
        "{head}"
    );
}

#[test]
fn a_cloud_without_classification_writes_no_such_field() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut cloud = full().without_invalid();
    cloud.classification = None;
    for enc in PCD_ENCODINGS {
        let path = dir.path().join(format!("{}.pcd", enc.keyword()));
        pcd::write_pcd(&path, &cloud, enc).expect("write");
        assert!(!header_of(&path).contains("classification"), "{enc:?}");
        let back = pcd::read_pcd(&path).expect("read");
        assert_eq!(back.classification, None, "{enc:?}");
        assert_eq!(back.labels, cloud.labels, "{enc:?}");
    }
    for enc in PLY_ENCODINGS {
        let path = dir.path().join(format!("{}.ply", enc.keyword()));
        ply::write_ply(&path, &cloud, enc).expect("write");
        assert!(!header_of(&path).contains("classification"), "{enc:?}");
        assert_eq!(
            as_ply(&cloud),
            ply::read_ply(&path).expect("read"),
            "{enc:?}"
        );
    }
}

const PCD_HEAD: &str = "VERSION 0.7\nFIELDS x y z label classification\nSIZE 4 4 4 4 1\nTYPE F F F U U\nCOUNT 1 1 1 1 1\nWIDTH 3\nHEIGHT 1\nPOINTS 3\nDATA ascii\n";

#[test]
fn hand_written_ascii_pcd_reads_its_classification() {
    let dir = tempfile::tempdir().expect("tempdir");
    let body = "0 0 0 4 2\n1 0 0 0 6\n0 1 0 9 255\n";
    let path = file(dir.path(), "a.pcd", format!("{PCD_HEAD}{body}").as_bytes());
    let (c, notes) = read_cloud_with_notes(&path).expect("valid");
    assert_eq!(c.classification, Some(vec![2, 6, 255]));
    let entities: Vec<u32> = c.labels.expect("labels").iter().map(|l| l.entity).collect();
    assert_eq!(entities, [4, 0, 9], "label stays the entity id");
    assert!(notes.is_empty(), "{notes:?}");

    // PDAL's default: every dimension but x y z as F 8, with two decimals.
    let pdal = "VERSION 0.7\nFIELDS x y z intensity classification\nSIZE 4 4 4 8 8\nTYPE F F F F F\nCOUNT 1 1 1 1 1\nWIDTH 2\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\nDATA ascii\n0.00 0.00 0.00 12.00 2.00\n1.00 0.00 0.00 7.00 6.00\n";
    let path = file(dir.path(), "pdal.pcd", pdal.as_bytes());
    let (c, notes) = read_cloud_with_notes(&path).expect("valid");
    assert_eq!(c.classification, Some(vec![2, 6]));
    assert_eq!(c.intensity, Some(vec![12.0, 7.0]));
    assert_eq!(c.labels, None);
    assert_eq!(notes.len(), 1, "{notes:?}");
    assert!(
        notes[0].contains("field classification (TYPE F, SIZE 8) read as ASPRS classification"),
        "{notes:?}"
    );
}

#[test]
fn pcd_classification_values_that_are_no_code_skip_the_field() {
    let dir = tempfile::tempdir().expect("tempdir");
    for (ty, body, bad) in [
        (
            "U 2",
            "0 0 0 1 2\n1 0 0 2 300\n0 1 0 3 301\n",
            "300 at point 1",
        ),
        ("I 4", "0 0 0 1 -1\n1 0 0 2 6\n0 1 0 3 2\n", "-1 at point 0"),
        (
            "F 4",
            "0 0 0 1 2\n1 0 0 2 6\n0 1 0 3 2.5\n",
            "2.5 at point 2",
        ),
    ] {
        let (t, s) = ty.split_once(' ').expect("type and size");
        let head = PCD_HEAD
            .replace("SIZE 4 4 4 4 1", &format!("SIZE 4 4 4 4 {s}"))
            .replace("TYPE F F F U U", &format!("TYPE F F F U {t}"));
        let path = file(dir.path(), "bad.pcd", format!("{head}{body}").as_bytes());
        let (c, notes) = read_cloud_with_notes(&path).expect("read, not refused");
        assert_eq!(c.classification, None, "{ty}");
        assert_eq!(c.len(), 3);
        assert!(c.labels.is_some(), "{ty}: the labels are kept");
        assert!(
            notes
                .iter()
                .any(|n| n.contains("no ASPRS class") && n.contains(bad)),
            "{ty}: {notes:?}"
        );
    }
    // In range, of another integer type: converted with a note.
    let head = PCD_HEAD
        .replace("SIZE 4 4 4 4 1", "SIZE 4 4 4 4 2")
        .replace("TYPE F F F U U", "TYPE F F F U I");
    let path = file(
        dir.path(),
        "i2.pcd",
        format!("{head}0 0 0 1 0\n1 0 0 2 6\n0 1 0 3 255\n").as_bytes(),
    );
    let (c, notes) = read_cloud_with_notes(&path).expect("valid");
    assert_eq!(c.classification, Some(vec![0, 6, 255]));
    assert!(
        notes
            .iter()
            .any(|n| n.contains("(TYPE I, SIZE 2) read as ASPRS")),
        "{notes:?}"
    );
}

#[test]
fn hand_written_binary_pcd_of_other_types_reads_its_classification() {
    let dir = tempfile::tempdir().expect("tempdir");
    let head = "FIELDS x y z classification\nSIZE 4 4 4 2\nTYPE F F F U\nCOUNT 1 1 1 2\nWIDTH 3\nHEIGHT 1\nDATA binary\n";
    let mut bytes = head.as_bytes().to_vec();
    for (i, (class, other)) in [(2u16, 999u16), (6, 1), (17, 5000)].into_iter().enumerate() {
        for v in [i as f32, 0.0, 1.0] {
            bytes.extend(v.to_le_bytes());
        }
        bytes.extend(class.to_le_bytes());
        bytes.extend(other.to_le_bytes());
    }
    let path = file(dir.path(), "b.pcd", &bytes);
    let (c, notes) = read_cloud_with_notes(&path).expect("valid");
    assert_eq!(
        c.classification,
        Some(vec![2, 6, 17]),
        "the first of COUNT 2"
    );
    assert!(notes.iter().any(|n| n.contains("COUNT 2")), "{notes:?}");
    assert!(
        notes.iter().any(|n| n.contains("read as ASPRS")),
        "{notes:?}"
    );
}

const PLY_HEAD: &str = "ply\nformat ascii 1.0\ncomment by hand\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nproperty uchar classification\nproperty uchar class\nend_header\n";

#[test]
fn hand_written_ascii_ply_reads_its_classification() {
    let dir = tempfile::tempdir().expect("tempdir");
    let body = "0 0 0 2 1\n1 0 0 6 0\n0 1 0 255 3\n";
    let path = file(dir.path(), "a.ply", format!("{PLY_HEAD}{body}").as_bytes());
    let (c, notes) = read_cloud_with_notes(&path).expect("valid");
    assert_eq!(c.classification, Some(vec![2, 6, 255]));
    let classes: Vec<u8> = c
        .labels
        .expect("labels")
        .iter()
        .map(|l| l.class.code())
        .collect();
    assert_eq!(classes, [1, 0, 3], "class stays semsim's entity class");
    assert!(notes.is_empty(), "{notes:?}");

    let int = PLY_HEAD.replace("uchar classification", "int classification");
    let path = file(dir.path(), "int.ply", format!("{int}{body}").as_bytes());
    let (c, notes) = read_cloud_with_notes(&path).expect("valid");
    assert_eq!(c.classification, Some(vec![2, 6, 255]));
    assert!(
        notes.iter().any(
            |n| n.contains("vertex property classification (int) read as ASPRS classification")
        ),
        "{notes:?}"
    );

    let path = file(
        dir.path(),
        "bad.ply",
        format!("{int}0 0 0 2 1\n1 0 0 -6 0\n0 1 0 256 3\n").as_bytes(),
    );
    let (c, notes) = read_cloud_with_notes(&path).expect("read, not refused");
    assert_eq!(c.classification, None);
    assert_eq!(c.len(), 3);
    assert!(
        notes
            .iter()
            .any(|n| n.contains("holds 2 value(s) that are no ASPRS class")
                && n.contains("-6 at point 1")),
        "{notes:?}"
    );

    let list = PLY_HEAD.replace("uchar classification", "list uchar uchar classification");
    let path = file(
        dir.path(),
        "list.ply",
        format!("{list}0 0 0 1 2 1\n1 0 0 1 6 0\n0 1 0 1 9 3\n").as_bytes(),
    );
    let (c, notes) = read_cloud_with_notes(&path).expect("valid");
    assert_eq!(c.classification, None, "a list is no classification");
    assert!(
        notes.iter().any(|n| n.contains("classification not used")),
        "{notes:?}"
    );
}

#[test]
fn binary_ply_of_other_types_reads_its_classification() {
    let dir = tempfile::tempdir().expect("tempdir");
    for big in [false, true] {
        let enc = if big {
            "binary_big_endian"
        } else {
            "binary_little_endian"
        };
        let mut bytes = format!("ply\nformat {enc} 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nproperty ushort classification\nend_header\n").into_bytes();
        for (i, class) in [9u16, 64].into_iter().enumerate() {
            for v in [i as f32, 2.0, 3.0] {
                bytes.extend(if big {
                    v.to_be_bytes()
                } else {
                    v.to_le_bytes()
                });
            }
            bytes.extend(if big {
                class.to_be_bytes()
            } else {
                class.to_le_bytes()
            });
        }
        let path = file(dir.path(), "b.ply", &bytes);
        let (c, notes) = read_cloud_with_notes(&path).expect("valid");
        assert_eq!(c.classification, Some(vec![9, 64]), "{enc}");
        assert_eq!(c.points[1], Vec3::new(1.0, 2.0, 3.0), "{enc}");
        assert!(
            notes.iter().any(|n| n.contains("(ushort) read as ASPRS")),
            "{enc}: {notes:?}"
        );
    }
}
