//! Files as other tools write them: PCL field layouts (padding, COUNT > 1, F8, other types),
//! PLY with extra elements and list properties, 3DTK shape lines, poses and frames.

use cloud::io::threedtk::{read_3d, read_frames_3dtk, read_pose_3dtk};
use cloud::{read_cloud, EntityClass, Label, Organized};
use glam::{DVec3, Quat, Vec3};
use std::path::PathBuf;

fn file(name: &str, bytes: &[u8]) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join(name);
    std::fs::write(&path, bytes).expect("write");
    (dir, path)
}

const PCL_HEAD: &str = "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z _ rgb intensity label\nSIZE 8 8 8 1 4 2 2\nTYPE F F F U F U U\nCOUNT 1 1 1 3 1 1 1\nWIDTH 2\nHEIGHT 2\nVIEWPOINT 1 2 3 0.7071068 0 0 0.7071068\nPOINTS 4\n";

/// Four points: (i, -i, 0.5 i) with the third a missing return, intensity 100 i, label 10 i.
/// Each element is `(field bytes in field order)`.
fn pcl_points() -> Vec<Vec<Vec<u8>>> {
    (0..4u16)
        .map(|i| {
            let f = f64::from(i);
            let (x, y, z) = if i == 2 {
                (f64::NAN, f64::NAN, f64::NAN)
            } else {
                (f, -f, 0.5 * f)
            };
            vec![
                x.to_le_bytes().to_vec(),
                y.to_le_bytes().to_vec(),
                z.to_le_bytes().to_vec(),
                vec![0xaa; 3],
                0.25f32.to_le_bytes().to_vec(),
                (100 * i).to_le_bytes().to_vec(),
                (10 * i).to_le_bytes().to_vec(),
            ]
        })
        .collect()
}

fn check_pcl_cloud(path: &std::path::Path) {
    let c = read_cloud(path).expect("PCL layout");
    assert_eq!(c.organized, Some(Organized { rows: 2, cols: 2 }));
    assert_eq!(c.points[1], Vec3::new(1.0, -1.0, 0.5));
    assert!(c.points[2].is_nan());
    assert_eq!(c.intensity, Some(vec![0.0, 100.0, 200.0, 300.0]));
    let entities: Vec<u32> = c
        .labels
        .as_ref()
        .expect("labels")
        .iter()
        .map(|l| l.entity)
        .collect();
    assert_eq!(entities, [0, 10, 20, 30]);
    assert!(c
        .labels
        .expect("labels")
        .iter()
        .all(|l| l.class == EntityClass::Unknown));
    assert_eq!(c.sensor_origin, Vec3::new(1.0, 2.0, 3.0));
    assert!(
        c.sensor_orientation
            .angle_between(Quat::from_rotation_z(std::f32::consts::FRAC_PI_2))
            < 1e-5
    );
}

#[test]
fn pcl_binary_layout_with_padding_and_doubles() {
    let mut bytes = format!("{PCL_HEAD}DATA binary\n").into_bytes();
    bytes.extend(pcl_points().concat().concat());
    let (_dir, path) = file("pcl.pcd", &bytes);
    check_pcl_cloud(&path);
}

#[test]
fn pcl_binary_compressed_layout_is_field_after_field() {
    let points = pcl_points();
    let soa: Vec<u8> = (0..7)
        .flat_map(|f| points.iter().flat_map(move |p| p[f].clone()))
        .collect();
    // A valid LZF stream made only of literal runs.
    let lzf: Vec<u8> = soa
        .chunks(32)
        .flat_map(|c| [vec![(c.len() - 1) as u8], c.to_vec()].concat())
        .collect();
    let mut bytes = format!("{PCL_HEAD}DATA binary_compressed\n").into_bytes();
    bytes.extend((lzf.len() as u32).to_le_bytes());
    bytes.extend((soa.len() as u32).to_le_bytes());
    bytes.extend(lzf);
    let (_dir, path) = file("pcl_lzf.pcd", &bytes);
    check_pcl_cloud(&path);
}

#[test]
fn pcd_ascii_with_counts_and_class_without_label() {
    let text = "# comment\nVERSION .7\nFIELDS normal x y z class\nSIZE 4 4 4 4 1\nTYPE F F F F U\nCOUNT 3 1 1 1 1\nWIDTH 2\nHEIGHT 1\nPOINTS 2\nDATA ascii\n0 0 1 1.5 2.5 3.5 3\n\n0 1 0 -1 -2 -3 1\n";
    let (_dir, path) = file("ascii.pcd", text.as_bytes());
    let c = read_cloud(&path).expect("valid");
    assert_eq!(
        c.points,
        [Vec3::new(1.5, 2.5, 3.5), Vec3::new(-1.0, -2.0, -3.0)]
    );
    assert_eq!(
        c.labels.expect("labels")[0],
        Label {
            entity: 0,
            class: EntityClass::Wall
        }
    );
    assert_eq!((c.organized, c.intensity), (None, None));
    assert_eq!(c.sensor_orientation, Quat::IDENTITY);
}

#[test]
fn ply_big_endian_with_extra_elements_and_lists() {
    let mut bytes = b"ply\nformat binary_big_endian 1.0\nobj_info x\nelement camera 1\nproperty float view\nelement vertex 2\nproperty double x\nproperty list uchar int near\nproperty float64 y\nproperty float32 z\nproperty uchar intensity\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n".to_vec();
    bytes.extend(9.0f32.to_be_bytes());
    for (i, n) in [(0u8, 2u8), (1, 0)] {
        bytes.extend(f64::from(i).to_be_bytes());
        bytes.push(n);
        (0..n).for_each(|k| bytes.extend(i32::from(k).to_be_bytes()));
        bytes.extend((f64::from(i) + 0.5).to_be_bytes());
        bytes.extend((-f32::from(i)).to_be_bytes());
        bytes.push(200 + i);
    }
    bytes.extend([3, 0, 0, 0, 0]); // a face, cut short: never read
    let (_dir, path) = file("lists.ply", &bytes);
    let c = read_cloud(&path).expect("valid");
    assert_eq!(
        c.points,
        [Vec3::new(0.0, 0.5, 0.0), Vec3::new(1.0, 1.5, -1.0)]
    );
    assert_eq!(c.intensity, Some(vec![200.0, 201.0]));
    let ascii = "ply\nformat ascii 1.0\nelement camera 1\nproperty float view\nelement vertex 2\nproperty float x\nproperty list uchar int near\nproperty float y\nproperty float z\nproperty float scalar_intensity\nproperty int label\nproperty uchar class\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n9\n0 2 5 6 0.5 0 200 4 1\n1 0 1.5 -1 201 0 6\n3 0 1 2\n";
    let (_dir, path) = file("lists_ascii.ply", ascii.as_bytes());
    let d = read_cloud(&path).expect("valid");
    assert_eq!((&d.points, &d.intensity), (&c.points, &c.intensity));
    let classes: Vec<EntityClass> = d.labels.expect("labels").iter().map(|l| l.class).collect();
    assert_eq!(classes, [EntityClass::Floor, EntityClass::Stairs]);
}

#[test]
fn threedtk_shape_line_and_reflectance() {
    let (_dir, path) = file(
        "scan001.3d",
        b"2 x 2\n100 0 0 7\n0 100 0 8\n0 0 100 9\n-100 0 0 10\n",
    );
    let c = read_3d(&path).expect("valid");
    assert_eq!(c.organized, Some(Organized { rows: 2, cols: 2 }));
    // 3DTK x right, y up, z forward (cm) -> semsim x forward, y left, z up (m).
    assert_eq!(c.points, [-Vec3::Y, Vec3::Z, Vec3::X, Vec3::Y]);
    assert_eq!(c.intensity, Some(vec![7.0, 8.0, 9.0, 10.0]));
    // A shape line that does not match the point count is ignored.
    let (_dir, path) = file("scan002.3d", b"360 x 225\n100 0 0\n");
    let c = read_3d(&path).expect("valid");
    assert_eq!((c.len(), c.organized, c.intensity), (1, None, None));
}

#[test]
fn threedtk_pose_and_frames_convert_to_semsim_axes() {
    let (_dir, path) = file("scan001.pose", b"100 0 -50\n0 90 0\n");
    let pose = read_pose_3dtk(&path).expect("valid");
    assert!(pose
        .translation
        .abs_diff_eq(DVec3::new(-0.5, -1.0, 0.0), 1e-12));
    // A positive 3DTK yaw (about y, up) turns clockwise seen from above: x -> -y, z stays.
    assert!(pose
        .transform_vector3(DVec3::X)
        .abs_diff_eq(-DVec3::Y, 1e-12));
    assert!(pose
        .transform_vector3(DVec3::Z)
        .abs_diff_eq(DVec3::Z, 1e-12));
    let frames = "1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 2\n\n1 0 0 0 0 1 0 0 0 0 1 0 100 200 300 1 1\n";
    let (_dir, path) = file("scan001.frames", frames.as_bytes());
    let f = read_frames_3dtk(&path).expect("valid");
    assert_eq!(f.len(), 2);
    assert!(f[1]
        .translation
        .abs_diff_eq(DVec3::new(3.0, -1.0, 2.0), 1e-12));
    // A frame built from the same pose numbers agrees with the .pose reader.
    let m = glam::DMat4::from(pose);
    let p = glam::DMat3::from_cols(DVec3::new(0.0, -1.0, 0.0), DVec3::Z, DVec3::X);
    let r = p.transpose() * glam::DMat3::from_mat4(m) * p;
    let t = p.transpose() * m.w_axis.truncate() * 100.0;
    let mut cols: Vec<f64> = [r.x_axis, r.y_axis, r.z_axis]
        .iter()
        .flat_map(|c| [c.x, c.y, c.z, 0.0])
        .collect();
    cols.extend([t.x, t.y, t.z, 1.0]);
    let line: Vec<String> = cols.iter().map(|v| format!("{v}")).collect();
    let (_dir, path) = file("same.frames", format!("{} 2\n", line.join(" ")).as_bytes());
    let same = read_frames_3dtk(&path).expect("valid");
    assert!(same[0].abs_diff_eq(pose, 1e-9));
}

#[test]
fn ply_skips_huge_elements_of_nothing_and_reports_missing_data() {
    let head = "ply\nformat binary_little_endian 1.0\nelement nothing 1000000000000000000\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
    let mut bytes = head.as_bytes().to_vec();
    [1.0f32, 2.0, 3.0]
        .iter()
        .for_each(|v| bytes.extend(v.to_le_bytes()));
    let (_dir, path) = file("nothing.ply", &bytes);
    assert_eq!(
        read_cloud(&path).expect("valid").points,
        [Vec3::new(1.0, 2.0, 3.0)]
    );
    let huge = head.replace(
        "element nothing 1000000000000000000",
        "element pad 1000000000000000000\nproperty uchar p",
    );
    let (_dir, path) = file("pad.ply", huge.as_bytes());
    assert!(matches!(
        read_cloud(&path),
        Err(cloud::CloudError::Truncated { .. })
    ));
}
