//! Shared by the tests, the examples and the benchmark: survey poses chosen from a building,
//! virtual scans from them, merged in the world frame with the true poses.
#![allow(dead_code)]

use cloud::PointCloud;
use glam::Vec3;
use scanner::{Building, BuildingGeometry, LaserConfig, ScanPose, VirtualLaser};

/// The laser mount height used everywhere here (the scanner's default).
pub const MOUNT_M: f64 = 0.5;

/// A moderate laser for the tests: 271 beams x 151 rotation steps.
pub fn test_laser() -> LaserConfig {
    LaserConfig {
        beams: 271,
        rotation_steps: 151,
        ..LaserConfig::default()
    }
}

/// True if a laser at (x, y) would stand clear of every solid (30 cm around it).
fn clear(g: &BuildingGeometry, x: f64, y: f64) -> bool {
    let r = 0.3;
    [(0.0, 0.0), (r, 0.0), (-r, 0.0), (0.0, r), (0.0, -r)]
        .iter()
        .all(|(dx, dy)| {
            [0.1, MOUNT_M].iter().all(|&z| {
                g.entity_containing(Vec3::new((x + dx) as f32, (y + dy) as f32, z as f32))
                    .is_none()
            })
        })
}

/// Survey poses for a generated (or the default) building: along the corridor every ~2.5 m,
/// and one inside each room behind an open, half-open or empty doorway (at the room's centre,
/// or 1.5 m beside the middle of a staircase in the room). Falls back to the
/// floor's centre for buildings without walls named "corridor north" / "corridor south".
pub fn survey_poses(b: &Building, g: &BuildingGeometry) -> Vec<ScanPose> {
    let (mut poses, visits) = survey_visits(b, g);
    poses.extend(visits.into_iter().map(|v| v.room));
    poses
}

/// A surveyor's visit of a room: a scan standing in the doorway, then one inside.
pub struct RoomVisit {
    /// In the doorway (or just beside it, where the leaf is in the way).
    pub doorway: Option<ScanPose>,
    /// Inside the room (as in [`survey_poses`]).
    pub room: ScanPose,
    /// How far the door's leaf is open (`None`: no leaf).
    pub open_deg: Option<f64>,
}

/// The corridor poses of [`survey_poses`] and its room poses, each with a doorway pose.
pub fn survey_visits(b: &Building, g: &BuildingGeometry) -> (Vec<ScanPose>, Vec<RoomVisit>) {
    let mut visits = Vec::new();
    let north = b.walls.iter().find(|w| w.name == "corridor north");
    let south = b.walls.iter().find(|w| w.name == "corridor south");
    let (Some(n), Some(s)) = (north, south) else {
        let f = &b.floor;
        let centre = ScanPose {
            x_m: (f.min_m[0] + f.max_m[0]) / 2.0,
            y_m: (f.min_m[1] + f.max_m[1]) / 2.0,
            yaw_deg: 0.0,
        };
        return (vec![centre], visits);
    };
    let y_mid = (n.start_m[1] + s.start_m[1]) / 2.0;
    let (x0, x1) = (
        n.start_m[0].min(n.end_m[0]) + 1.0,
        n.start_m[0].max(n.end_m[0]) - 1.0,
    );
    let k = ((x1 - x0) / 2.5).ceil().max(1.0) as usize;
    let poses: Vec<ScanPose> = (0..=k)
        .map(|i| ScanPose {
            x_m: x0 + (x1 - x0) * i as f64 / k as f64,
            y_m: y_mid,
            yaw_deg: 0.0,
        })
        .filter(|p| clear(g, p.x_m, p.y_m))
        .collect();
    for (w, sign) in [(n, 1.0), (s, -1.0)] {
        let dir = (w.end_m[0] - w.start_m[0]).signum();
        for d in &w.doors {
            let open = d.leaf.as_ref().is_none_or(|l| l.open_deg >= 30.0);
            if !open {
                continue;
            }
            // The room: between the partitions (or outer walls) either side of the door, from
            // the corridor wall to the outer wall. Its centre, else near it.
            let xc = w.start_m[0] + dir * (d.offset_m + d.width_m / 2.0);
            let (room_x, depth) = room_centre(b, xc, w.start_m[1], sign);
            let mut centre = (room_x, w.start_m[1] + sign * depth / 2.0);
            // A room with a staircase is scanned from beside the staircase's middle instead,
            // 1.5 m off its side towards the room's centre (a surveyor scans stairs closely).
            for st in &b.stairs {
                let d = (
                    st.direction_deg.to_radians().cos(),
                    st.direction_deg.to_radians().sin(),
                );
                let half = (st.steps as f64 * st.run_m + st.landing_m) / 2.0;
                let mid = (st.start_m[0] + d.0 * half, st.start_m[1] + d.1 * half);
                let inside = !b.walls.iter().any(|w| {
                    segments_cross([centre.0, centre.1], [mid.0, mid.1], w.start_m, w.end_m)
                });
                if inside {
                    let n = (-d.1, d.0);
                    let toward = if (centre.0 - mid.0) * n.0 + (centre.1 - mid.1) * n.1 >= 0.0 {
                        1.0
                    } else {
                        -1.0
                    };
                    let off = st.width_m / 2.0 + 1.5;
                    centre = (mid.0 + toward * n.0 * off, mid.1 + toward * n.1 * off);
                }
            }
            let doorway = [0.0, 0.3, -0.3, 0.6, -0.6].iter().find_map(|&dy| {
                let (x, y) = (xc, w.start_m[1] + sign * dy);
                clear(g, x, y).then_some(ScanPose {
                    x_m: x,
                    y_m: y,
                    yaw_deg: 0.0,
                })
            });
            'search: for dy in [0.0, 0.5, -0.5, 1.0, -1.0] {
                for dx in [0.0, 0.6, -0.6, 1.2, -1.2] {
                    let (x, y) = (centre.0 + dx, centre.1 + sign * dy);
                    if clear(g, x, y) {
                        let room = ScanPose {
                            x_m: x,
                            y_m: y,
                            yaw_deg: 0.0,
                        };
                        visits.push(RoomVisit {
                            doorway,
                            room,
                            open_deg: d.leaf.as_ref().map(|l| l.open_deg),
                        });
                        break 'search;
                    }
                }
            }
        }
    }
    (poses, visits)
}

fn segments_cross(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> bool {
    let orient = |p: [f64; 2], q: [f64; 2], r: [f64; 2]| {
        (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])
    };
    let (o1, o2) = (orient(a, b, c), orient(a, b, d));
    let (o3, o4) = (orient(c, d, a), orient(c, d, b));
    o1 * o2 < 0.0 && o3 * o4 < 0.0
}

/// The x of the centre of the room behind a door at `x` in the corridor wall at `y`, on side
/// `sign` (+1 north), and the room's depth from that wall: the nearest walls across x either
/// side, and the nearest wall along x beyond.
fn room_centre(b: &Building, x: f64, y: f64, sign: f64) -> (f64, f64) {
    let probe = y + sign * 1.0;
    let (mut west, mut east) = (f64::NEG_INFINITY, f64::INFINITY);
    let mut far = f64::INFINITY;
    for w in &b.walls {
        let (x0, x1) = (w.start_m[0].min(w.end_m[0]), w.start_m[0].max(w.end_m[0]));
        let (y0, y1) = (w.start_m[1].min(w.end_m[1]), w.start_m[1].max(w.end_m[1]));
        if (x1 - x0) < 1e-6 && probe >= y0 && probe <= y1 {
            if x0 < x && x0 > west {
                west = x0;
            }
            if x0 > x && x0 < east {
                east = x0;
            }
        }
        if (y1 - y0) < 1e-6 && x >= x0 && x <= x1 && sign * (y0 - y) > 0.5 {
            far = far.min(sign * (y0 - y));
        }
    }
    let cx = if west.is_finite() && east.is_finite() {
        (west + east) / 2.0
    } else {
        x
    };
    (cx, if far.is_finite() { far } else { 3.0 })
}

/// Scans `b` from `poses` and merges the scans in the world frame (missing returns dropped,
/// ground-truth labels kept), then voxel-downsamples to `voxel_m` (0 = keep every point).
pub fn scan_building(
    b: &Building,
    poses: &[ScanPose],
    laser: &LaserConfig,
    voxel_m: f64,
) -> PointCloud {
    let g = BuildingGeometry::new(b);
    let laser = VirtualLaser::new(laser.clone()).expect("valid laser");
    let mut merged = PointCloud::from_points(Vec::new());
    let mut labels = Vec::new();
    for (k, pose) in poses.iter().enumerate() {
        let mut scan = laser.scan(&g, pose, k as u64);
        scan.transform(&pose.world_from_scan(laser.config().mount_height_m));
        let scan = scan.without_invalid();
        merged.points.extend(scan.points);
        labels.extend(scan.labels.unwrap_or_default());
    }
    merged.labels = Some(labels);
    if voxel_m > 0.0 {
        cloud::voxel_downsample(&merged, voxel_m).expect("valid voxel size")
    } else {
        merged
    }
}

/// The 3DTK corridor (`../shared/data/real/3dtk-corridor` beside the checkout), its three scans
/// placed with the last pose of their `.frames` (3DTK's 2009 registration), "no echo" readings
/// (over 30 m from the scanner) dropped. `None` if the folder is absent.
pub fn threedtk_corridor() -> Option<PointCloud> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/data/real/3dtk-corridor");
    if !dir.is_dir() {
        return None;
    }
    let mut merged = PointCloud::from_points(Vec::new());
    for k in 0..3 {
        let scan = cloud::io::threedtk::read_3d(&dir.join(format!("scan{k:03}.3d")))
            .expect("readable scan");
        let frames = cloud::io::threedtk::read_frames_3dtk(
            &dir.join(format!("frames_2009/scan{k:03}.frames")),
        )
        .expect("readable frames");
        let world_from_scan = *frames.last().expect("a frame");
        let t = glam::Affine3A::from_mat4(glam::DMat4::from(world_from_scan).as_mat4());
        merged.points.extend(
            scan.points
                .iter()
                .filter(|p| p.is_finite() && p.length() < 30.0)
                .map(|p| t.transform_point3(*p)),
        );
    }
    Some(merged)
}

/// The default building scanned from its first `n` survey poses at the laser's full resolution
/// (541 x 301), merged, not downsampled (missing returns dropped): the benchmark's cloud.
pub fn default_building_full_scans(n: usize) -> PointCloud {
    let b = Building::default_building().expect("built-in building");
    let g = BuildingGeometry::new(&b);
    let mut poses = survey_poses(&b, &g);
    poses.truncate(n);
    scan_building(&b, &poses, &LaserConfig::default(), 0.0)
}

/// Generated building `seed`, its survey poses and the merged, downsampled test scan.
pub fn generated(seed: u64, voxel_m: f64) -> (Building, PointCloud) {
    let b = scanner::generate_building(seed, &scanner::GeneratorConfig::default())
        .expect("valid building");
    let g = BuildingGeometry::new(&b);
    let poses = survey_poses(&b, &g);
    let cloud = scan_building(&b, &poses, &test_laser(), voxel_m);
    (b, cloud)
}

/// The survey in the order a surveyor walks it: down the corridor, stepping into each room
/// (doorway, then inside) from the corridor pose nearest to its door. Rooms behind a leaf open
/// less than 60 degrees are left out: the leaf hides the room from the doorway, and a room
/// scan that shares only a sliver with the map cannot be registered.
pub fn survey_path(b: &Building, g: &BuildingGeometry) -> Vec<ScanPose> {
    let (corridor, visits) = survey_visits(b, g);
    let mut path = Vec::new();
    for (i, c) in corridor.iter().enumerate() {
        path.push(*c);
        for v in visits
            .iter()
            .filter(|v| v.open_deg.is_none_or(|a| a >= 60.0))
        {
            let door_x = v.doorway.map_or(v.room.x_m, |d| d.x_m);
            let nearest = corridor
                .iter()
                .enumerate()
                .min_by(|a, b| {
                    (a.1.x_m - door_x)
                        .abs()
                        .total_cmp(&(b.1.x_m - door_x).abs())
                })
                .map(|(k, _)| k);
            if nearest == Some(i) {
                path.extend(v.doorway);
                path.push(v.room);
            }
        }
    }
    path
}

/// Registration settings for a survey in short hops: the defaults with a 0.5 m first gate.
pub fn sequence_config() -> registration::SequenceConfig {
    let mut c = registration::SequenceConfig::default();
    c.icp.max_correspondence_distance_m = 0.5;
    c.icp.max_iterations = 50;
    c.icp.kernel = registration::RobustKernel::Cauchy { k_m: 0.05 };
    c
}

/// The registered map of generated building `seed`: each survey scan in its own frame, the
/// noisy odometry (`scanner::odometry_from_truth`, default drift and noise) as the guess,
/// `registration::register_sequence` (default settings), then the full scans merged with the
/// *registered* poses and downsampled to `voxel_m`. Also returns the worst registered
/// position error against the true poses (metres).
pub fn generated_registered(seed: u64, voxel_m: f64) -> (Building, PointCloud, f64) {
    let b = scanner::generate_building(seed, &scanner::GeneratorConfig::default())
        .expect("valid building");
    let g = BuildingGeometry::new(&b);
    let poses = survey_path(&b, &g);
    let laser = VirtualLaser::new(test_laser()).expect("valid laser");
    let mount = laser.config().mount_height_m;
    let scans: Vec<PointCloud> = poses
        .iter()
        .enumerate()
        .map(|(k, p)| laser.scan(&g, p, k as u64).without_invalid())
        .collect();
    let odometry = scanner::odometry_from_truth(
        &poses,
        &scanner::OdometryConfig {
            seed,
            ..Default::default()
        },
    )
    .expect("valid odometry settings");
    let guess: Vec<glam::DAffine3> = odometry.iter().map(|p| p.world_from_scan(mount)).collect();
    let result =
        registration::register_sequence(&scans, &guess, &sequence_config(), &mut |_, _| {})
            .unwrap_or_else(|e| panic!("seed {seed}: registration failed: {e}"));
    let mut worst = 0.0f64;
    let mut merged = PointCloud::from_points(Vec::new());
    let mut labels = Vec::new();
    for ((scan, pose), truth) in scans.into_iter().zip(&result.world_from_scan).zip(&poses) {
        let t = truth.world_from_scan(mount);
        worst = worst.max((pose.translation - t.translation).length());
        let mut scan = scan;
        scan.transform(pose);
        merged.points.extend(scan.points);
        labels.extend(scan.labels.unwrap_or_default());
    }
    merged.labels = Some(labels);
    let cloud = cloud::voxel_downsample(&merged, voxel_m).expect("valid voxel size");
    (b, cloud, worst)
}
