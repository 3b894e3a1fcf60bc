//! The realistic virtual laser against ground truth: each effect of the `real` preset measured
//! on buildings made for it (a flat wall at two ranges, the floor at grazing incidence, a dark
//! and a matte box, a glass wall, a box in front of a wall, people, a tilted mount), the
//! no-echo value, reproducibility, and the ideal laser pinned bit for bit.

use cloud::{EntityClass, PointCloud};
use glam::{DVec3, Vec3};
use scanner::{
    Building, BuildingGeometry, LaserConfig, MixedPixels, Mount, People, RangeNoise, Realism,
    ScanPose, VirtualLaser,
};
use std::path::Path;

/// A closed room `x` 0..24 m, `y` -4..4 m (inner faces at 0.1 from the wall lines), 2.8 m
/// high, plus `extra` TOML (boxes, walls).
fn room(extra: &str) -> (Building, BuildingGeometry) {
    let text = format!(
        r#"
[floor]
min_m = [-0.2, -4.2]
max_m = [24.2, 4.2]
thickness_m = 0.2
[ceiling]
height_m = 2.8
thickness_m = 0.2
[[walls]]
name = "west"
start_m = [0.0, -4.1]
end_m = [0.0, 4.1]
thickness_m = 0.2
[[walls]]
name = "east"
start_m = [24.0, -4.1]
end_m = [24.0, 4.1]
thickness_m = 0.2
[[walls]]
name = "south"
start_m = [-0.1, -4.0]
end_m = [24.1, -4.0]
thickness_m = 0.2
[[walls]]
name = "north"
start_m = [-0.1, 4.0]
end_m = [24.1, 4.0]
thickness_m = 0.2
{extra}
"#
    );
    let building = Building::from_toml_str(&text, Path::new("<test room>")).expect("valid room");
    let geometry = BuildingGeometry::new(&building);
    (building, geometry)
}

fn entity(geometry: &BuildingGeometry, name: &str) -> u32 {
    geometry
        .entities()
        .iter()
        .find(|e| e.name == name)
        .unwrap_or_else(|| panic!("no entity {name}"))
        .id
}

fn laser(realism: Realism) -> VirtualLaser {
    VirtualLaser::new(LaserConfig {
        realism,
        ..Default::default()
    })
    .expect("valid laser")
}

/// The real preset without the effects a test does not look at.
fn real_without_people_and_mixing() -> Realism {
    Realism {
        people: People::off(),
        mixed: MixedPixels::off(),
        ..Realism::real()
    }
}

fn at(x_m: f64, y_m: f64) -> ScanPose {
    ScanPose {
        x_m,
        y_m,
        yaw_deg: 0.0,
    }
}

/// The scan's points in the world frame (by the sensor's true pose), and the sensor's origin.
fn in_world(laser: &VirtualLaser, scan: &PointCloud, pose: &ScanPose) -> (Vec<Vec3>, Vec3) {
    let mut s = scan.clone();
    let world_from_sensor = laser.world_from_sensor(pose);
    s.transform(&world_from_sensor);
    (s.points, world_from_sensor.translation.as_vec3())
}

fn labels(scan: &PointCloud) -> &[cloud::Label] {
    scan.labels.as_deref().expect("labelled")
}

/// FNV-1a over the bits of every point and label.
fn fingerprint(scan: &PointCloud) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |x: u32| {
        for b in x.to_le_bytes() {
            h ^= b as u64;
            h = h.wrapping_mul(0x100_0000_01b3);
        }
    };
    for (p, l) in scan.points.iter().zip(labels(scan)) {
        eat(p.x.to_bits());
        eat(p.y.to_bits());
        eat(p.z.to_bits());
        eat(l.entity);
        eat(l.class.code() as u32);
    }
    h
}

#[test]
fn ideal_laser_scans_are_bit_for_bit_those_of_the_laser_before_realism() {
    // Fingerprints of the laser as it was before the realism section existed (commit
    // ba46bfc's laser.rs), on the default building.
    let building = Building::default_building().expect("default");
    let geometry = BuildingGeometry::new(&building);
    let cases = [
        (
            LaserConfig::default(),
            at(6.5, 0.0),
            0,
            0xb581_567a_67d5_31f6,
        ),
        (
            LaserConfig {
                beams: 181,
                rotation_steps: 91,
                ..Default::default()
            },
            ScanPose {
                x_m: 14.4,
                y_m: 0.3,
                yaw_deg: 30.0,
            },
            3,
            0x5d0d_b4a8_5372_5c05,
        ),
    ];
    for (config, pose, k, expected) in cases {
        assert!(config.realism.is_off());
        let scan = VirtualLaser::new(config)
            .expect("valid")
            .scan(&geometry, &pose, k);
        assert_eq!(fingerprint(&scan), expected, "pose {pose:?}");
    }
}

/// Range errors of the returns from the west wall (inner face x = 0.1) near head-on: measured
/// std, and the std the configuration predicts for those very beams.
fn wall_range_errors(
    laser: &VirtualLaser,
    geometry: &BuildingGeometry,
    x_m: f64,
    pose_index: u64,
) -> (f64, f64, usize) {
    let pose = at(x_m, 0.0);
    let scan = laser.scan(geometry, &pose, pose_index);
    let west = entity(geometry, "walls[0]");
    let (pts, o) = in_world(laser, &scan, &pose);
    let c = laser.config();
    let (mut errs, mut predicted) = (Vec::new(), Vec::new());
    for (p, l) in pts.iter().zip(labels(&scan)) {
        if l.entity != west || !p.is_finite() {
            continue;
        }
        let d = (*p - o).normalize();
        // Near head-on (within 14 degrees), where the incidence term is small.
        if -d.x < 0.97 {
            continue;
        }
        let truth = (0.1 - o.x) / d.x;
        errs.push(((*p - o).length() - truth) as f64);
        predicted.push(c.realism.noise.sigma_m(
            c.range_noise_sigma_m,
            truth as f64,
            -d.x as f64,
            c.realism.beam_divergence_mrad * 1e-3,
        ));
    }
    let n = errs.len() as f64;
    let mean = errs.iter().sum::<f64>() / n;
    let std = (errs.iter().map(|e| (e - mean).powi(2)).sum::<f64>() / n).sqrt();
    let rms = (predicted.iter().map(|s| s * s).sum::<f64>() / n).sqrt();
    (std, rms, errs.len())
}

#[test]
fn range_noise_on_a_flat_wall_grows_from_2_m_to_10_m_as_configured() {
    let (_, geometry) = room("");
    let laser = laser(Realism::real());
    let (near, near_predicted, n_near) = wall_range_errors(&laser, &geometry, 2.1, 1);
    let (far, far_predicted, n_far) = wall_range_errors(&laser, &geometry, 10.1, 1);
    assert!(
        n_near > 1000 && n_far > 50,
        "{n_near} and {n_far} wall returns"
    );
    // The sample std of n gaussian errors is within 3/sqrt(2n) of the truth (3 sigma).
    for (std, predicted, n) in [(near, near_predicted, n_near), (far, far_predicted, n_far)] {
        let tolerance = 3.0 / (2.0 * n as f64).sqrt();
        assert!(
            (std / predicted - 1.0).abs() < tolerance,
            "std {std} vs configured {predicted} ({n} points)"
        );
    }
    // 1 cm and 1 mm/m: 1.02 cm at 2 m, 1.41 cm at 10 m.
    eprintln!(
        "range error std {near:.5} m at 2 m ({n_near} points, configured {near_predicted:.5}), \
         {far:.5} m at 10 m ({n_far}, configured {far_predicted:.5})"
    );
    assert!(far > 1.25 * near, "std {near} at 2 m, {far} at 10 m");
}

#[test]
fn grazing_returns_drop_out_above_the_configured_angle_and_not_head_on() {
    let (_, geometry) = room("");
    let realism = real_without_people_and_mixing();
    let start = realism.returns.grazing_dropout_start_deg;
    let real = laser(realism.clone());
    // The same laser without losses: every beam's true first surface.
    let truth = laser(Realism {
        mount: realism.mount.clone(),
        ..Realism::off()
    });
    let pose = at(12.0, 0.0);
    let (a, b) = (
        real.scan(&geometry, &pose, 0),
        truth.scan(&geometry, &pose, 0),
    );
    let floor = entity(&geometry, "floor");
    let (pts, o) = in_world(&truth, &b, &pose);
    // Per incidence band on the floor within 6 m (where power is no limit): beams, drops.
    let mut below = (0, 0);
    let mut above = (0, 0, 0.0);
    for (k, (p, l)) in pts.iter().zip(labels(&b)).enumerate() {
        let range = (*p - o).length();
        if l.entity != floor || range > 6.0 {
            continue;
        }
        let incidence = ((*p - o).normalize().z.abs() as f64).acos().to_degrees();
        let dropped = labels(&a)[k].entity != floor;
        if incidence < start - 1.0 {
            below.0 += 1;
            below.1 += dropped as usize;
        } else if incidence > start + 3.0 {
            above.0 += 1;
            above.1 += dropped as usize;
            above.2 += realism
                .returns
                .grazing_dropout((90.0 - incidence).to_radians().sin());
        }
    }
    eprintln!("grazing: below {start} deg {below:?} (beams, dropped); above {above:?} (beams, dropped, expected)");
    assert!(below.0 > 5000 && above.0 > 500, "{below:?} {above:?}");
    // Below the start angle: none, but for the rare beam short of power (none at 6 m).
    assert!((below.1 as f64) < 0.002 * below.0 as f64, "{below:?}");
    // Above: as many as the linear ramp says (within 3 binomial sigmas and 2 %).
    let (n, dropped, expected) = (above.0 as f64, above.1 as f64, above.2);
    let sigma = (expected * (1.0 - expected / n)).sqrt();
    assert!(
        (dropped - expected).abs() < 3.0 * sigma + 0.02 * n,
        "{dropped} dropped of {n}, expected {expected}"
    );
    assert!(dropped > 0.2 * n, "{dropped} of {n}");
}

#[test]
fn a_dark_box_returns_fewer_points_than_a_matte_one_of_the_same_size() {
    let boxes = r#"
[[boxes]]
center_m = [6.0, 2.5, 0.4]
size_m = [0.8, 0.8, 0.8]
[[boxes]]
material = "dark"
center_m = [6.0, -2.5, 0.4]
size_m = [0.8, 0.8, 0.8]
"#;
    let (_, geometry) = room(boxes);
    let (matte, dark) = (entity(&geometry, "boxes[0]"), entity(&geometry, "boxes[1]"));
    let count = |laser: &VirtualLaser| {
        let scan = laser.scan(&geometry, &at(2.0, 0.0), 0);
        let n = |id| labels(&scan).iter().filter(|l| l.entity == id).count();
        (n(matte), n(dark))
    };
    // Ideal: the two boxes are mirror images about the sensor: the same count within 2 %.
    let (m, d) = count(&laser(Realism::off()));
    assert!(
        m > 300 && (m as f64 - d as f64).abs() < 0.02 * m as f64,
        "{m} {d}"
    );
    // Real: 2.4 % against 70 % reflectivity, 4.7 m away (about the range at which a 2.4 %
    // target head-on is detected half the time): the dark box loses many returns.
    let (m, d) = count(&laser(real_without_people_and_mixing()));
    eprintln!("real: matte box {m} returns, dark box {d}");
    assert!(m > 300, "{m}");
    assert!((d as f64) < 0.7 * m as f64, "dark {d} vs matte {m}");
}

#[test]
fn a_glass_wall_lets_most_beams_through_and_returns_some() {
    let glass_wall = r#"
[[walls]]
name = "glass"
start_m = [8.0, -3.9]
end_m = [8.0, 3.9]
thickness_m = 0.02
material = "glass"
"#;
    let (_, geometry) = room(glass_wall);
    let glass = entity(&geometry, "walls[4]");
    let pose = at(4.0, 0.0);
    let realism = real_without_people_and_mixing();
    let ideal = laser(Realism {
        mount: realism.mount.clone(),
        ..Realism::off()
    })
    .scan(&geometry, &pose, 0);
    let real_laser = laser(realism.clone());
    let real = real_laser.scan(&geometry, &pose, 0);
    let (pts, o) = in_world(&real_laser, &real, &pose);
    let (mut on_glass, mut behind, mut beams) = (0, 0, 0);
    for (k, p) in pts.iter().enumerate() {
        // Beams meeting the glass within 8 m (where power behind it is no limit).
        if labels(&ideal)[k].entity != glass || ideal.points[k].length() > 8.0 {
            continue;
        }
        beams += 1;
        if labels(&real)[k].entity == glass {
            on_glass += 1;
        } else if p.is_finite() && p.x > 8.01 && (*p - o).length() < 30.0 {
            behind += 1;
        }
    }
    eprintln!("glass: {beams} beams, {on_glass} returned by the glass, {behind} from behind it");
    assert!(beams > 3000, "{beams}");
    let share = |n: usize| n as f64 / beams as f64;
    let (ret, pass) = (
        realism.returns.glass_return_probability,
        realism.returns.glass_pass_probability,
    );
    // Returns from the glass: the configured share (3 binomial sigmas); behind it: most, at
    // most the pass share (some are lost behind it at grazing incidence).
    let sigma = (ret * (1.0 - ret) / beams as f64).sqrt();
    assert!(
        (share(on_glass) - ret).abs() < 3.0 * sigma,
        "{on_glass} of {beams}"
    );
    assert!(
        share(behind) > 0.6 && share(behind) <= pass + 0.02,
        "{behind} of {beams}"
    );
}

#[test]
fn mixed_pixels_lie_between_foreground_and_background_only_at_depth_edges() {
    // A box 3 m in front of the sensor, the east part of the room 1 m behind its far face.
    let boxes = r#"
[[walls]]
name = "backdrop"
start_m = [7.0, -3.9]
end_m = [7.0, 3.9]
thickness_m = 0.2
[[boxes]]
center_m = [5.5, 0.0, 1.0]
size_m = [1.0, 1.2, 2.0]
"#;
    let (_, geometry) = room(boxes);
    let realism = Realism {
        people: People::off(),
        ..Realism::real()
    };
    let pose = at(2.0, 0.0);
    let real = laser(realism.clone()).scan(&geometry, &pose, 0);
    let exact = VirtualLaser::new(LaserConfig {
        range_noise_sigma_m: 0.0,
        realism: Realism {
            mount: realism.mount.clone(),
            ..Realism::off()
        },
        ..Default::default()
    })
    .expect("valid")
    .scan(&geometry, &pose, 0);
    let cols = real.organized.expect("organised").cols;
    let no_echo = realism.no_echo_range_m.expect("preset writes no-echo") as f32;
    let mut mixed = 0;
    for (k, (p, l)) in real.points.iter().zip(labels(&real)).enumerate() {
        let r = p.length();
        if l.entity != 0 || !p.is_finite() || (r - no_echo).abs() < 1e-3 {
            continue;
        }
        mixed += 1;
        // Its 3 x 3 neighbourhood in the exact scan spans a depth edge, from one surface to
        // another (not one surface at a grazing angle), and the point lies within it.
        let (j, i) = ((k / cols) as i64, (k % cols) as i64);
        let around: Vec<(f32, u32)> = (-1..=1)
            .flat_map(|dj| (-1..=1).map(move |di| (j + dj, i + di)))
            .filter(|&(jj, ii)| jj >= 0 && ii >= 0 && (ii as usize) < cols)
            .map(|(jj, ii)| jj as usize * cols + ii as usize)
            .filter(|&n| n < exact.len() && exact.points[n].is_finite())
            .map(|n| (exact.points[n].length(), labels(&exact)[n].entity))
            .collect();
        let near = around.iter().map(|a| a.0).fold(f32::INFINITY, f32::min);
        let far = around.iter().map(|a| a.0).fold(0.0, f32::max);
        assert!(
            far - near > realism.mixed.min_separation_m as f32
                && around.iter().any(|a| a.1 != around[0].1),
            "beam {k}: no edge around it ({around:?})"
        );
        assert!(r > near && r < far, "beam {k}: {r} outside {near}..{far}");
    }
    eprintln!("{mixed} mixed pixels of {} points", real.len());
    assert!(mixed > 50, "{mixed} mixed pixels");
    // Without mixing: no such points at all.
    let none = laser(real_without_people_and_mixing()).scan(&geometry, &pose, 0);
    let stray = none
        .points
        .iter()
        .zip(labels(&none))
        .filter(|(p, l)| l.entity == 0 && p.is_finite() && (p.length() - no_echo).abs() > 1e-3)
        .count();
    assert_eq!(stray, 0);
}

#[test]
fn walking_people_leave_streaks_labelled_unknown_and_none_without_people() {
    let (_, geometry) = room("");
    let realism = Realism {
        mixed: MixedPixels::off(),
        ..Realism::real()
    };
    let people = realism.people.clone();
    let no_echo = realism.no_echo_range_m.expect("no-echo") as f32;
    let pose = at(10.0, 0.0);
    let is_person = |p: &Vec3, l: &cloud::Label| {
        l.entity == 0 && p.is_finite() && (p.length() - no_echo).abs() > 1e-3
    };
    let laser_with = laser(realism.clone());
    let scan = laser_with.scan(&geometry, &pose, 2);
    let walkers = laser_with.people_at(&geometry, &pose, 2);
    assert_eq!(walkers.len(), 301);
    assert_eq!(walkers[0].len(), people.count);
    let cols = scan.organized.expect("organised").cols;
    let (pts, _) = in_world(&laser_with, &scan, &pose);
    // Each person's points, projected on the direction that person walks.
    let mut along: Vec<Vec<f32>> = vec![Vec::new(); people.count];
    let mut n = 0;
    for (k, (p, l)) in scan.points.iter().zip(labels(&scan)).enumerate() {
        if !is_person(p, l) {
            continue;
        }
        assert_eq!(l.class, EntityClass::Unknown);
        n += 1;
        let w = pts[k];
        let row = &walkers[k / cols];
        // On the surface of a person where that person was at this rotation step.
        let (who, d) = row
            .iter()
            .enumerate()
            .map(|(q, c)| (q, (w.truncate() - *c).length()))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .expect("people");
        assert!(
            (d - people.radius_m as f32).abs() < 0.08
                && w.z > -0.05
                && w.z < people.height_m as f32 + 0.05,
            "point {w} is {d} m from person {who}"
        );
        let heading = (walkers[300][who] - walkers[0][who]).normalize();
        along[who].push(w.truncate().dot(heading));
    }
    eprintln!("{n} people points");
    assert!(n > 50, "{n} people points");
    // A streak: some person's points spread along the walk farther than one body is wide.
    let spread = along
        .iter()
        .filter(|a| !a.is_empty())
        .map(|a| {
            a.iter().copied().fold(f32::MIN, f32::max) - a.iter().copied().fold(f32::MAX, f32::min)
        })
        .fold(0.0, f32::max);
    eprintln!("people streak spread {spread} m along the walk");
    assert!(
        spread > 2.0 * people.radius_m as f32 + 0.3,
        "spread {spread} m"
    );
    // Without people: no such points.
    let empty = laser(Realism {
        people: People::off(),
        ..realism
    })
    .scan(&geometry, &pose, 2);
    assert_eq!(
        empty
            .points
            .iter()
            .zip(labels(&empty))
            .filter(|(p, l)| is_person(p, l))
            .count(),
        0
    );
}

/// The unit normal of a least-squares plane through `pts` (smallest eigenvector of the
/// covariance, by power iteration on its inverse-free shifted form), pointing up.
fn plane_normal(pts: &[Vec3]) -> DVec3 {
    let n = pts.len() as f64;
    let c = pts.iter().map(|p| p.as_dvec3()).sum::<DVec3>() / n;
    let mut m = glam::DMat3::ZERO;
    for p in pts {
        let d = p.as_dvec3() - c;
        m += glam::DMat3::from_cols(d * d.x, d * d.y, d * d.z);
    }
    // The smallest eigenvector of m is the largest of (trace * I - m).
    let shifted =
        glam::DMat3::from_diagonal(DVec3::splat(m.x_axis.x + m.y_axis.y + m.z_axis.z)) - m;
    let mut v = DVec3::Z;
    for _ in 0..200 {
        v = (shifted * v).normalize();
    }
    if v.z < 0.0 {
        -v
    } else {
        v
    }
}

#[test]
fn a_tilted_mount_tilts_the_floor_in_the_scan_by_the_mount() {
    let (_, geometry) = room("");
    let pose = at(10.0, 0.0);
    let floor = entity(&geometry, "floor");
    let floor_normal = |realism: Realism| {
        let l = laser(realism);
        let scan = l.scan(&geometry, &pose, 0);
        let pts: Vec<Vec3> = scan
            .points
            .iter()
            .zip(labels(&scan))
            .filter(|(p, lab)| lab.entity == floor && p.length() < 5.0)
            .map(|(p, _)| *p)
            .collect();
        // In the world (by the true pose), the floor is level at z = 0.
        let (world, _) = in_world(&l, &scan, &pose);
        let worst = world
            .iter()
            .zip(labels(&scan))
            .filter(|(p, lab)| lab.entity == floor && p.is_finite())
            .map(|(p, _)| p.z.abs())
            .fold(0.0, f32::max);
        assert!(
            worst < 0.2,
            "floor point {worst} m off the floor in the world"
        );
        plane_normal(&pts)
    };
    let level = floor_normal(Realism {
        mount: Mount::off(),
        ..real_without_people_and_mixing()
    });
    let tilted_realism = real_without_people_and_mixing();
    let tilt = tilted_realism.mount.scan_from_sensor();
    let tilted = floor_normal(tilted_realism);
    // Level: the floor's normal is the sensor's z within 0.02 degrees (thousands of points
    // with 1 cm noise); tilted: it is the world's up seen from the tilted sensor.
    assert!(level.angle_between(DVec3::Z).to_degrees() < 0.02, "{level}");
    let expected = tilt.inverse() * DVec3::Z;
    assert!(
        tilted.angle_between(expected).to_degrees() < 0.02,
        "{tilted} vs {expected}"
    );
    let tilt_deg = expected.angle_between(DVec3::Z).to_degrees();
    eprintln!(
        "floor normal: level {:.4} deg off z, tilted {:.4} deg (mount {tilt_deg:.4}), {:.4} deg from expected",
        level.angle_between(DVec3::Z).to_degrees(),
        tilted.angle_between(DVec3::Z).to_degrees(),
        tilted.angle_between(expected).to_degrees()
    );
    assert!(tilt_deg > 0.3, "the preset tilts by {tilt_deg} degrees");
    assert!((tilted.angle_between(DVec3::Z).to_degrees() - tilt_deg).abs() < 0.02);
}

#[test]
fn missing_returns_are_written_at_the_no_echo_range_or_nan() {
    let (_, geometry) = room("");
    let pose = at(10.0, 0.0);
    let realism = real_without_people_and_mixing();
    let no_echo = realism.no_echo_range_m.expect("preset") as f32;
    let scan = laser(realism.clone()).scan(&geometry, &pose, 0);
    let at_no_echo: Vec<usize> = (0..scan.len())
        .filter(|&k| (scan.points[k].length() - no_echo).abs() < 1e-3)
        .collect();
    eprintln!("{} no-echo readings of {}", at_no_echo.len(), scan.len());
    assert!(
        at_no_echo.len() > scan.len() / 500,
        "{} no-echo readings",
        at_no_echo.len()
    );
    assert!(at_no_echo.iter().all(|&k| labels(&scan)[k].entity == 0));
    assert!(scan.points.iter().all(|p| p.is_finite()));
    // With no no-echo value the same beams are NaN.
    let nan = laser(Realism {
        no_echo_range_m: None,
        ..realism
    })
    .scan(&geometry, &pose, 0);
    let missing: Vec<usize> = (0..nan.len()).filter(|&k| nan.points[k].is_nan()).collect();
    assert_eq!(missing, at_no_echo);
}

#[test]
fn a_real_scan_is_the_same_for_the_same_seed_whatever_the_thread_count() {
    let building = Building::default_building().expect("default");
    let geometry = BuildingGeometry::new(&building);
    let l = laser(Realism::real());
    let pose = at(6.5, 0.0);
    let in_pool = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool")
            .install(|| fingerprint(&l.scan(&geometry, &pose, 4)))
    };
    let one = in_pool(1);
    assert_eq!(in_pool(3), one);
    assert_eq!(fingerprint(&l.scan(&geometry, &pose, 4)), one);
    // Another pose index draws other noise, other people.
    assert_ne!(fingerprint(&l.scan(&geometry, &pose, 5)), one);
}

#[test]
fn presets_are_named_or_tabled_in_the_laser_section_and_checked() {
    let real: LaserConfig = toml::from_str("realism = \"real\"\n").expect("preset by name");
    assert_eq!(real.realism, Realism::real());
    let ideal: LaserConfig = toml::from_str("realism = \"ideal\"\n").expect("preset by name");
    assert!(ideal.realism.is_off());
    // A written configuration reads back equal; a table's missing values are the ideal's.
    let text = toml::to_string(&real).expect("serialises");
    assert_eq!(
        toml::from_str::<LaserConfig>(&text).expect("reads back"),
        real
    );
    let partial: LaserConfig =
        toml::from_str("[realism.people]\ncount = 3\n").expect("partial table");
    assert_eq!(partial.realism.people.count, 3);
    assert_eq!(partial.realism.noise, RangeNoise::off());
    for bad in [
        "realism = \"perfect\"\n",
        "[realism]\nbeam_divergence = 1.0\n",
        "[realism.noise]\nsigma_per_m = 0.001\nextra = 1\n",
    ] {
        let e = toml::from_str::<LaserConfig>(bad).expect_err(bad);
        assert!(!e.to_string().is_empty());
    }
    let unknown = toml::from_str::<LaserConfig>("realism = \"perfect\"\n").expect_err("unknown");
    assert!(unknown.to_string().contains("ideal, real"), "{unknown}");
    // Values out of range are refused when the laser is made.
    for realism in [
        Realism {
            no_echo_range_m: Some(20.0),
            ..Realism::real()
        },
        Realism {
            mount: Mount {
                roll_deg: 30.0,
                pitch_deg: 0.0,
            },
            ..Realism::real()
        },
        Realism {
            beam_divergence_mrad: f64::NAN,
            ..Realism::real()
        },
    ] {
        assert!(VirtualLaser::new(LaserConfig {
            realism,
            ..Default::default()
        })
        .is_err());
    }
}
