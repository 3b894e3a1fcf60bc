//! Round trips through `write_cloud` / `read_cloud` between every pair of formats (PCD, PLY,
//! XYZ, 3DTK, E57, LAS, LAZ), each pair followed by LAS again, and what each format keeps.
//!
//! Per format, what comes back of a cloud written and read again:
//! - PCD, PLY, E57 (f32, or f64 of the f32) and XYZ (shortest decimal of the f32): exact.
//! - 3DTK: centimetres with 4 decimals, converted to metres: within 1e-6 m (plus f32 rounding).
//! - LAS/LAZ: 0.1 mm integers: within 5e-5 m; intensity rounded to u16 (the test uses whole
//!   numbers, so exact), classification kept (written 0 where the cloud had none).
//!
//! Intensity survives every format; the ASPRS classification survives LAS/LAZ, PCD (field
//! `classification`, `U 1`) and PLY (vertex property `uchar classification`; these two write
//! it only where the cloud has one), so LAS -> PCD -> LAS and LAS -> PLY -> LAS keep every
//! point's class; XYZ, 3DTK and E57 drop it.

mod scans_support;

use cloud::{Organized, PointCloud};
use glam::Vec3;
use interop::{is_sequence_file, read_cloud, read_scans, write_cloud, InteropError, ReadOptions};
use std::path::Path;

const FORMATS: [&str; 7] = ["pcd", "ply", "xyz", "3d", "e57", "las", "laz"];

/// The position error a format may add (metres) for coordinates within ±8 m.
fn tolerance(ext: &str) -> f32 {
    match ext {
        "3d" => 1e-6 + 1e-6,
        "las" | "laz" => 5e-5 + 1e-6,
        _ => 0.0,
    }
}

fn keeps_class(ext: &str) -> bool {
    matches!(ext, "las" | "laz" | "pcd" | "ply")
}

/// The classification a cloud with `class` has after a trip through format `ext`: kept where
/// the format keeps it, dropped where not; LAS/LAZ always have one (0 where the cloud had none),
/// PCD and PLY only where the cloud had one.
fn through(ext: &str, class: Option<Vec<u8>>, n: usize) -> Option<Vec<u8>> {
    match ext {
        "las" | "laz" => Some(class.unwrap_or_else(|| vec![0; n])),
        _ if keeps_class(ext) => class,
        _ => None,
    }
}

fn sample() -> PointCloud {
    let mut c = PointCloud::from_points(
        (0..60)
            .map(|i| {
                let t = i as f32 * 0.37;
                Vec3::new(
                    t.cos() * 7.5,
                    t.sin() * 6.25 - 1.0,
                    (i % 7) as f32 * 0.3125 - 0.9,
                )
            })
            .collect(),
    );
    c.intensity = Some((0..60).map(|i| (i * 17 % 1000) as f32).collect());
    c.classification = Some((0..60).map(|i| [1u8, 2, 6, 9][i % 4]).collect());
    c
}

fn read(path: &Path) -> PointCloud {
    let (c, _) = read_cloud(path, &ReadOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    c
}

#[test]
fn every_pair_of_formats_round_trips() {
    let dir = tempfile::tempdir().unwrap();
    let original = sample();
    for a in FORMATS {
        let first = dir.path().join(format!("first.{a}"));
        write_cloud(&first, &original).unwrap_or_else(|e| panic!("{a}: {e}"));
        let via_a = read(&first);
        for b in FORMATS {
            let second = dir.path().join(format!("second_{a}.{b}"));
            write_cloud(&second, &via_a).unwrap_or_else(|e| panic!("{a} -> {b}: {e}"));
            let back = read(&second);
            let what = format!("{a} -> {b}");
            assert_eq!(back.len(), original.len(), "{what}");
            let tol = tolerance(a) + tolerance(b);
            for (p, q) in back.points.iter().zip(&original.points) {
                let d = (*p - *q).abs().max_element();
                assert!(d <= tol, "{what}: {p:?} vs {q:?} ({d} > {tol})");
            }
            assert_eq!(back.intensity, original.intensity, "{what}: intensity");
            let n = original.len();
            let class = through(b, through(a, original.classification.clone(), n), n);
            if keeps_class(a) && keeps_class(b) {
                assert_eq!(class, original.classification, "{what}");
            }
            assert_eq!(back.classification, class, "{what}: classification");
            assert!(back.organized.is_none(), "{what}");
            // And on to LAS: e.g. LAS -> PCD -> LAS and LAS -> PLY -> LAS keep the classes.
            let third = dir.path().join(format!("third_{a}_{b}.las"));
            write_cloud(&third, &back).unwrap_or_else(|e| panic!("{what} -> las: {e}"));
            let las = read(&third);
            assert_eq!(
                las.classification,
                through("las", class, n),
                "{what} -> las: classification"
            );
        }
    }
}

/// LAS -> PCD -> LAS and LAS -> PLY -> LAS in every PCD and PLY encoding: the classes (and the
/// intensities) of every point come back.
#[test]
fn las_classes_survive_pcd_and_ply_in_every_encoding() {
    use cloud::{CloudFormat, PcdEncoding, PlyEncoding};
    let dir = tempfile::tempdir().unwrap();
    let las = dir.path().join("in.las");
    write_cloud(&las, &sample()).unwrap();
    let from_las = read(&las);
    assert_eq!(from_las.classification, sample().classification);
    let formats = [
        CloudFormat::Pcd(PcdEncoding::Ascii),
        CloudFormat::Pcd(PcdEncoding::Binary),
        CloudFormat::Pcd(PcdEncoding::BinaryCompressed),
        CloudFormat::Ply(PlyEncoding::Ascii),
        CloudFormat::Ply(PlyEncoding::BinaryLittleEndian),
        CloudFormat::Ply(PlyEncoding::BinaryBigEndian),
    ];
    for (k, format) in formats.into_iter().enumerate() {
        let ext = if matches!(format, CloudFormat::Pcd(_)) {
            "pcd"
        } else {
            "ply"
        };
        let mid = dir.path().join(format!("mid{k}.{ext}"));
        cloud::write_cloud_as(&mid, &from_las, format).unwrap();
        let via = read(&mid);
        assert_eq!(via.classification, from_las.classification, "{format:?}");
        let out = dir.path().join(format!("out{k}.las"));
        write_cloud(&out, &via).unwrap();
        let back = read(&out);
        assert_eq!(
            back.classification,
            sample().classification,
            "las -> {format:?} -> las"
        );
        assert_eq!(
            back.intensity,
            sample().intensity,
            "las -> {format:?} -> las"
        );
        assert_eq!(back.len(), from_las.len(), "las -> {format:?} -> las");
        for (p, q) in back.points.iter().zip(&sample().points) {
            let tol = 2.0 * tolerance("las");
            assert!(
                (*p - *q).abs().max_element() <= tol,
                "{format:?}: {p} vs {q}"
            );
        }
    }
}

fn organised() -> PointCloud {
    let mut c = PointCloud::from_points(
        (0..20)
            .map(|i| Vec3::new(i as f32 * 0.25, 1.0, -(i as f32) * 0.125))
            .collect(),
    );
    for i in [2, 9, 15] {
        c.points[i] = Vec3::NAN;
    }
    c.intensity = Some((0..20).map(|i| i as f32).collect());
    c.organized = Some(Organized { rows: 4, cols: 5 });
    c
}

#[test]
fn organised_clouds_keep_their_grid_in_pcd_and_e57_and_lose_it_in_las() {
    let dir = tempfile::tempdir().unwrap();
    let cloud = organised();
    for ext in ["pcd", "e57"] {
        let path = dir.path().join(format!("grid.{ext}"));
        write_cloud(&path, &cloud).unwrap();
        let back = read(&path);
        assert_eq!(back.organized, cloud.organized, "{ext}");
        assert_eq!(back.intensity, cloud.intensity, "{ext}");
        for (a, b) in back.points.iter().zip(&cloud.points) {
            assert!(
                a == b || (a.is_nan() && b.is_nan()),
                "{ext}: {a:?} vs {b:?}"
            );
        }
    }
    for ext in ["las", "laz"] {
        let path = dir.path().join(format!("grid.{ext}"));
        write_cloud(&path, &cloud).unwrap();
        let back = read(&path);
        assert_eq!(back.organized, None, "{ext}");
        assert_eq!(back.len(), 17, "{ext}: the missing returns are not written");
    }
}

#[test]
fn native_formats_read_as_one_unposed_scan() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("room.pcd");
    write_cloud(&path, &sample()).unwrap();
    let set = read_scans(&path, &ReadOptions::default()).unwrap();
    assert_eq!(set.scans.len(), 1);
    assert_eq!(set.scans[0].name, "room");
    assert!(set.scans[0].world_from_scan.is_none() && set.odometry.is_none());
    assert_eq!(set.local_origin_m, glam::DVec3::ZERO);

    let e57 = dir.path().join("one.e57");
    write_cloud(&e57, &sample()).unwrap();
    let set = read_scans(&e57, &ReadOptions::default()).unwrap();
    assert_eq!(set.scans[0].name, "one");
    assert_eq!(set.scans[0].world_from_scan, Some(glam::DAffine3::IDENTITY));

    let unknown = dir.path().join("cloud.abc");
    for e in [
        read_scans(&unknown, &ReadOptions::default()).unwrap_err(),
        write_cloud(&unknown, &sample()).unwrap_err(),
    ] {
        assert!(
            matches!(
                e,
                InteropError::Cloud(cloud::CloudError::UnknownFormat { .. })
            ),
            "{e}"
        );
    }
    let e = write_cloud(&dir.path().join("out.mcap"), &sample()).unwrap_err();
    assert!(
        matches!(e, InteropError::Unsupported { .. }) && e.to_string().contains("out.mcap"),
        "{e}"
    );
    assert!(is_sequence_file(Path::new("a/b.E57")) && is_sequence_file(Path::new("bag.mcap")));
    assert!(!is_sequence_file(Path::new("a.las")) && !is_sequence_file(Path::new("a.pcd")));
}

#[test]
fn georeferenced_clouds_keep_their_place_in_las() {
    // A cloud far from zero (as read_cloud gives a georeferenced file, minus its origin, or a
    // user's own large frame): written at 0.1 mm about its centre, read back relative to a
    // local origin that the note names.
    let dir = tempfile::tempdir().unwrap();
    let far = PointCloud::from_points(vec![
        Vec3::new(2500.0, -1200.5, 30.0),
        Vec3::new(2510.25, -1190.0, 31.5),
    ]);
    let path = dir.path().join("far.laz");
    write_cloud(&path, &far).unwrap();
    let set = read_scans(&path, &ReadOptions::default()).unwrap();
    assert_eq!(set.local_origin_m, glam::DVec3::new(2505.0, -1195.0, 31.0));
    for (p, q) in set.scans[0].cloud.points.iter().zip(&far.points) {
        let world = p.as_dvec3() + set.local_origin_m;
        assert!(
            (world - q.as_dvec3()).abs().max_element() < 1e-4,
            "{world:?} vs {q:?}"
        );
    }
    assert!(
        set.notes
            .iter()
            .any(|n| n.contains("local origin (2505, -1195, 31)")),
        "{:?}",
        set.notes
    );
}

#[test]
fn writing_to_a_missing_folder_names_the_file() {
    let dir = tempfile::tempdir().unwrap();
    for ext in ["e57", "las", "laz"] {
        let path = dir.path().join("missing").join(format!("out.{ext}"));
        let e = write_cloud(&path, &sample()).unwrap_err();
        assert!(matches!(e, InteropError::Cloud(_)), "{e}");
        assert!(scans_support::names_file(&e.to_string(), &path), "{e}");
    }
}

/// Enough points for the LAZ reader's two-thread path (fixed 50,000-point chunks, split at
/// the middle chunk): every point, intensity and class comes back in order.
#[test]
fn large_laz_files_decoded_on_two_threads_keep_every_point_in_order() {
    let dir = tempfile::tempdir().unwrap();
    let n = 260_123;
    let mut big = PointCloud::from_points(
        (0..n)
            .map(|i| {
                let t = i as f32 * 1e-3;
                Vec3::new(t.sin() * 9.0, t.cos() * 7.0, (i % 97) as f32 * 0.01)
            })
            .collect(),
    );
    big.intensity = Some((0..n).map(|i| (i % 65_000) as f32).collect());
    big.classification = Some((0..n).map(|i| (i % 31) as u8).collect());
    for ext in ["laz", "las"] {
        let path = dir.path().join(format!("big.{ext}"));
        write_cloud(&path, &big).unwrap();
        let back = read(&path);
        assert_eq!(back.len(), n, "{ext}");
        for (i, (p, q)) in back.points.iter().zip(&big.points).enumerate() {
            assert!(
                (*p - *q).abs().max_element() <= 5e-5 + 1e-6,
                "{ext} point {i}: {p} vs {q}"
            );
        }
        assert_eq!(back.intensity, big.intensity, "{ext}");
        assert_eq!(back.classification, big.classification, "{ext}");
    }
}

/// The local origin comes from the points, not from the header's bounds: a georeferenced file
/// whose header bounds are zero reads to the same origin and points as the correct file.
#[test]
fn wrong_header_bounds_do_not_move_the_local_origin() {
    let dir = tempfile::tempdir().unwrap();
    let far = PointCloud::from_points(vec![
        Vec3::new(2500.0, -1200.5, 30.0),
        Vec3::new(2510.25, -1190.0, 31.5),
        Vec3::new(2503.125, -1195.75, 30.5),
    ]);
    for ext in ["las", "laz"] {
        let good = dir.path().join(format!("good.{ext}"));
        write_cloud(&good, &far).unwrap();
        let mut bytes = std::fs::read(&good).unwrap();
        // Max x, min x, max y, min y, max z, min z (f64 each) from byte 179: all zero.
        bytes[179..227].fill(0);
        let bad = dir.path().join(format!("zero_bounds.{ext}"));
        std::fs::write(&bad, &bytes).unwrap();
        let a = read_scans(&good, &ReadOptions::default()).unwrap();
        let b = read_scans(&bad, &ReadOptions::default()).unwrap();
        assert_eq!(
            a.local_origin_m,
            glam::DVec3::new(2505.0, -1195.0, 31.0),
            "{ext}"
        );
        assert_eq!(b.local_origin_m, a.local_origin_m, "{ext}");
        assert_eq!(b.scans[0].cloud.points, a.scans[0].cloud.points, "{ext}");
    }
}
