//! The realistic virtual laser in scenes: mixed pixels at depth edges (a box in front of a
//! wall), walking people, a tilted mount, the no-echo value, reproducibility whatever the
//! thread count, and the presets of the laser section.

mod common;

use cloud::EntityClass;
use common::{
    at, entity, fingerprint, in_world, labels, laser, real_without_people_and_mixing, room,
};
use glam::{DVec3, Vec3};
use scanner::{
    Building, BuildingGeometry, LaserConfig, MixedPixels, Mount, People, RangeNoise, Realism,
    VirtualLaser,
};

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
