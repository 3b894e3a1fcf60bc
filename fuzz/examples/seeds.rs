//! Writes the seed corpora in `fuzz/corpus/<target>/`: small files written by semsim's own
//! writers, and small valid cuts of the real scans in `../shared/data/real` (kept only where
//! that folder exists). Every seed is under 64 KiB.
//!
//! Run from the repository root: `cargo run --manifest-path fuzz/Cargo.toml --example seeds`
//! (an optional argument names the real data folder).

use cloud::io::{pcd, ply};
use cloud::{
    write_cloud_as, write_poses, CloudFormat, EntityClass, Label, NamedPose, Organized,
    PcdEncoding, PlyEncoding, PointCloud,
};
use glam::{DAffine3, DQuat, DVec3, Quat, Vec3};
use std::path::{Path, PathBuf};

const MAX_SEED: usize = 64 * 1024;

fn main() {
    let fuzz = Path::new(env!("CARGO_MANIFEST_DIR"));
    let real = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| fuzz.join("../../shared/data/real"));
    let corpus = fuzz.join("corpus");
    let dir = |t: &str| {
        let d = corpus.join(t);
        std::fs::create_dir_all(&d).expect("corpus folder");
        d
    };
    own_clouds(&dir("pcd"), &dir("ply"), &dir("xyz"), &dir("threedtk_3d"));
    own_poses(
        &dir("poses"),
        &dir("threedtk_pose"),
        &dir("threedtk_frames"),
    );
    foreign(&dir("pcd"), &dir("ply"));
    if real.is_dir() {
        real_cuts(&real, &corpus);
    } else {
        eprintln!(
            "note: {} not found: no seeds from the real scans",
            real.display()
        );
    }
    let mut total = 0;
    for entry in walk(&corpus) {
        let len = std::fs::metadata(&entry).expect("seed").len() as usize;
        assert!(len < MAX_SEED, "{} is {len} bytes", entry.display());
        total += len;
    }
    println!("corpus: {total} bytes");
}

fn walk(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).expect("readable").flatten() {
        let p = e.path();
        if p.is_dir() {
            out.extend(walk(&p));
        } else {
            out.push(p);
        }
    }
    out
}

/// An organised 4 x 6 cloud with missing returns, intensity, labels and a sensor pose.
fn organised() -> PointCloud {
    let (rows, cols) = (4, 6);
    let n = rows * cols;
    PointCloud {
        points: (0..n)
            .map(|i| {
                if [3, 10].contains(&i) {
                    Vec3::NAN
                } else {
                    Vec3::new(i as f32 / 3.0, 1e-3 * i as f32, 2.5 - i as f32 * 0.1)
                }
            })
            .collect(),
        intensity: Some((0..n).map(|i| i as f32 * 0.37).collect()),
        labels: Some(
            (0..n)
                .map(|i| Label {
                    entity: i as u32 * 7,
                    class: EntityClass::ALL[i % EntityClass::ALL.len()],
                })
                .collect(),
        ),
        organized: Some(Organized { rows, cols }),
        sensor_origin: Vec3::new(1.0, 2.0, 0.5),
        sensor_orientation: Quat::from_rotation_z(0.3),
    }
}

fn plain(n: usize) -> PointCloud {
    PointCloud::from_points(
        (0..n)
            .map(|i| Vec3::new((i as f32 * 0.7).sin() * 4.0, i as f32 * 0.05, 1.25))
            .collect(),
    )
}

fn own_clouds(pcd_dir: &Path, ply_dir: &Path, xyz_dir: &Path, tdk_dir: &Path) {
    let org = organised();
    let unorg = org.without_invalid();
    for enc in [
        PcdEncoding::Ascii,
        PcdEncoding::Binary,
        PcdEncoding::BinaryCompressed,
    ] {
        let name = format!("own_organised_{}.pcd", enc.keyword());
        write_cloud_as(&pcd_dir.join(name), &org, CloudFormat::Pcd(enc)).expect("pcd");
        let name = format!("own_plain_{}.pcd", enc.keyword());
        write_cloud_as(&pcd_dir.join(name), &plain(40), CloudFormat::Pcd(enc)).expect("pcd");
    }
    for enc in [
        PlyEncoding::Ascii,
        PlyEncoding::BinaryLittleEndian,
        PlyEncoding::BinaryBigEndian,
    ] {
        let name = format!("own_labelled_{}.ply", enc.keyword());
        write_cloud_as(&ply_dir.join(name), &unorg, CloudFormat::Ply(enc)).expect("ply");
        let name = format!("own_plain_{}.ply", enc.keyword());
        write_cloud_as(&ply_dir.join(name), &plain(30), CloudFormat::Ply(enc)).expect("ply");
    }
    write_cloud_as(&xyz_dir.join("own_intensity.xyz"), &unorg, CloudFormat::Xyz).expect("xyz");
    write_cloud_as(&xyz_dir.join("own_plain.xyz"), &plain(30), CloudFormat::Xyz).expect("xyz");
    std::fs::write(
        xyz_dir.join("commas_and_comments.xyz"),
        "# x, y, z, intensity\n\n1.5,2,3,0.5\n-1e-3\t0 2.5 1 99\n4,5,6,7\n",
    )
    .expect("xyz");
    let mut full = org.clone();
    full.points.iter_mut().for_each(|p| {
        if !p.is_finite() {
            *p = Vec3::ONE;
        }
    });
    write_cloud_as(
        &tdk_dir.join("own_organised.3d"),
        &full,
        CloudFormat::ThreeDtk,
    )
    .expect("3d");
    write_cloud_as(
        &tdk_dir.join("own_plain.3d"),
        &plain(30),
        CloudFormat::ThreeDtk,
    )
    .expect("3d");
}

fn own_poses(dir: &Path, pose_dir: &Path, frames_dir: &Path) {
    std::fs::write(pose_dir.join("hand.pose"), "100 0 -50\n0 90 0\n").expect("pose");
    std::fs::write(
        frames_dir.join("hand.frames"),
        "1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 2\n\n0 0 -1 0 0 1 0 0 1 0 0 0 100 200 300 1 1\n",
    )
    .expect("frames");
    let poses: Vec<NamedPose> = (0..3)
        .map(|k| NamedPose {
            name: format!("scan{k:03}"),
            world_from_scan: DAffine3::from_rotation_translation(
                DQuat::from_euler(glam::EulerRot::ZYX, 0.3 * k as f64, 0.01, -0.02),
                DVec3::new(1.5 * k as f64, -2.0, 0.4),
            ),
        })
        .collect();
    write_poses(&dir.join("own_poses.txt"), &poses).expect("poses");
}

/// Layouts other tools write: PCL padding, rgb, COUNT > 1, doubles, a signed label; PLY with
/// extra elements and list properties.
fn foreign(pcd_dir: &Path, ply_dir: &Path) {
    let head = "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z _ rgb intensity label\nSIZE 8 8 8 1 4 2 4\nTYPE F F F U F U I\nCOUNT 1 1 1 3 1 1 1\nWIDTH 2\nHEIGHT 2\nVIEWPOINT 1 2 3 0.7071068 0 0 0.7071068\nPOINTS 4\n";
    let mut bin = format!("{head}DATA binary\n").into_bytes();
    for i in 0..4i32 {
        let f = if i == 2 { f64::NAN } else { f64::from(i) };
        for v in [f, -f, 0.5 * f] {
            bin.extend(v.to_le_bytes());
        }
        bin.extend([0xaa; 3]);
        bin.extend(0.25f32.to_le_bytes());
        bin.extend((100 * i as u16).to_le_bytes());
        bin.extend((10 * i - 15).to_le_bytes());
    }
    std::fs::write(pcd_dir.join("pcl_layout_binary.pcd"), bin).expect("pcd");
    let ascii = "# .PCD v0.7\nVERSION .7\nFIELDS normal x y z class label\nSIZE 4 4 4 4 1 4\nTYPE F F F F U I\nCOUNT 3 1 1 1 1 1\nWIDTH 2\nHEIGHT 1\nPOINTS 2\nDATA ascii\n0 0 1 1.5 2.5 3.5 3 -1\n\n0 1 0 -1 -2 -3 1 12\n";
    std::fs::write(pcd_dir.join("pcl_layout_ascii.pcd"), ascii).expect("pcd");
    let mesh = "ply\nformat ascii 1.0\ncomment a mesh\nelement camera 1\nproperty float view\nelement vertex 3\nproperty float x\nproperty list uchar int near\nproperty float y\nproperty float z\nproperty float scalar_intensity\nproperty int label\nproperty uchar class\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n9\n0 2 5 6 0.5 0 200 4 1\n1 0 1.5 -1 201 0 6\n2 1 7 2 2 202 -3 3\n3 0 1 2\n";
    std::fs::write(ply_dir.join("mesh_ascii.ply"), mesh).expect("ply");
    let mut be = b"ply\nformat binary_big_endian 1.0\nobj_info x\nelement camera 1\nproperty float view\nelement vertex 2\nproperty double x\nproperty list uchar int near\nproperty float64 y\nproperty float32 z\nproperty ushort intensity\nproperty short label\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n".to_vec();
    be.extend(9.0f32.to_be_bytes());
    for (i, n) in [(0u8, 2u8), (1, 0)] {
        be.extend(f64::from(i).to_be_bytes());
        be.push(n);
        (0..n).for_each(|k| be.extend(i32::from(k).to_be_bytes()));
        be.extend((f64::from(i) + 0.5).to_be_bytes());
        be.extend((-f32::from(i)).to_be_bytes());
        be.extend((200 + u16::from(i)).to_be_bytes());
        be.extend((i16::from(i) - 1).to_be_bytes());
    }
    be.push(3);
    [0i32, 1, 1].iter().for_each(|v| be.extend(v.to_be_bytes()));
    std::fs::write(ply_dir.join("mesh_big_endian.ply"), be).expect("ply");
}

/// The header of a PCD or PLY file: the bytes up to and including the line starting with `end`.
fn header(bytes: &[u8], end: &str) -> String {
    let text = String::from_utf8_lossy(bytes);
    let mut out = String::new();
    for line in text.split_inclusive('\n') {
        out.push_str(line);
        if line.starts_with(end) {
            return out;
        }
    }
    panic!("no {end} line");
}

fn real_cuts(real: &Path, corpus: &Path) {
    // The licence of each source, beside the cuts (outside the targets' folders, which
    // libFuzzer reads as inputs).
    let licences = corpus.join("LICENSES");
    std::fs::create_dir_all(&licences).expect("licences folder");
    for l in [
        "pcl-room/LICENSE.pcl-data",
        "small-gicp/LICENSE.small_gicp",
        "3dtk-corridor/LICENSING.3DTK",
    ] {
        let from = real.join(l);
        let name = from.file_name().expect("name").to_owned();
        std::fs::copy(&from, licences.join(name)).expect("licence");
    }
    // pcl-room: the first points, in PCL's own header, binary_compressed and ascii.
    let room = real.join("pcl-room/room_scan1.pcd");
    let bytes = std::fs::read(&room).expect("room");
    let pcl_head = header(&bytes, "DATA");
    let full = cloud::read_cloud(&room).expect("room reads");
    for (n, enc) in [
        (2500, PcdEncoding::BinaryCompressed),
        (300, PcdEncoding::Ascii),
    ] {
        let cut = full.select(&(0..n).collect::<Vec<_>>());
        let out = corpus.join(format!("pcd/pcl_room_{n}_{}.pcd", enc.keyword()));
        pcd::write_pcd(&out, &cut, enc).expect("write");
        let ours = std::fs::read(&out).expect("read");
        let our_head = header(&ours, "DATA");
        let head = pcl_head
            .replace("WIDTH 112586", &format!("WIDTH {n}"))
            .replace("POINTS 112586", &format!("POINTS {n}"))
            .replace("DATA binary_compressed", &format!("DATA {}", enc.keyword()));
        let mut seed = head.into_bytes();
        seed.extend(&ours[our_head.len()..]);
        std::fs::write(&out, seed).expect("write");
        let back = cloud::read_cloud(&out).expect("the cut reads");
        assert_eq!(back.len(), n);
    }
    // small-gicp: CloudCompare's header with the first vertices.
    let src = real.join("small-gicp/source.ply");
    let bytes = std::fs::read(&src).expect("ply");
    let head = header(&bytes, "end_header");
    let n = 600;
    let mut seed = head
        .replace("element vertex 69792", &format!("element vertex {n}"))
        .into_bytes();
    seed.extend(&bytes[head.len()..head.len() + 16 * n]);
    let out = corpus.join(format!("ply/small_gicp_{n}.ply"));
    std::fs::write(&out, seed).expect("write");
    assert_eq!(ply::read_ply(&out).expect("the cut reads").len(), n);
    // 3dtk-corridor: the first lines of a scan, the poses and the frames as they are.
    let scan = std::fs::read_to_string(real.join("3dtk-corridor/scan000.3d")).expect("3d");
    let cut: String = scan.lines().take(1500).map(|l| format!("{l}\n")).collect();
    std::fs::write(corpus.join("threedtk_3d/corridor_1500.3d"), cut).expect("write");
    for k in 0..3 {
        let name = format!("scan{k:03}.pose");
        std::fs::copy(
            real.join("3dtk-corridor").join(&name),
            corpus.join("threedtk_pose").join(&name),
        )
        .expect("pose");
        let name = format!("scan{k:03}.frames");
        std::fs::copy(
            real.join("3dtk-corridor/frames_2009").join(&name),
            corpus.join("threedtk_frames").join(&name),
        )
        .expect("frames");
    }
}
