//! The 3DTK corridor (`shared/data/real/3dtk-corridor`, see its MANIFEST.md) read and
//! registered as `semsim register --sequence` does, with the default configuration, against
//! the registration 3DTK's slam6d computed in 2009 (`frames_2009/`). Skips, saying so, when the
//! folder is absent.

use cloud::io::threedtk::{read_3d, read_frames_3dtk};
use cloud::pose_error;
use std::path::PathBuf;

/// The 3DTK corridor's folder, or `None` (skip) where it is absent.
fn corridor() -> Option<PathBuf> {
    fixtures::real_data_dir("3dtk-corridor")
}

#[test]
fn the_corridor_scans_lose_their_no_echo_readings_and_nothing_else() {
    let Some(dir) = corridor() else { return };
    for k in 0..3 {
        let path = dir.join(format!("scan{k:03}.3d"));
        let raw = read_3d(&path).expect("scan").without_invalid();
        let found = pipeline::find_no_echo(&raw).expect("the corridor scans have no-echo readings");
        // The SICK scanner writes 32.767 m (3DTK's centimetres: 3276.7) for no echo.
        assert!((found.range_m - 32.767).abs() < 0.01, "{found:?}");
        let share = found.count as f64 / raw.len() as f64;
        assert!((0.01..0.03).contains(&share), "{share}");
        let (kept, _) = pipeline::drop_no_echo(&raw);
        assert_eq!(kept.len() + found.count, raw.len());
        let farthest = kept
            .points
            .iter()
            .map(|p| p.distance(kept.sensor_origin))
            .fold(0.0f32, f32::max);
        assert!(farthest < 32.5, "{farthest}");
        // What is left is a real scan: no second pile-up.
        assert_eq!(pipeline::find_no_echo(&kept), None);
    }
}

#[test]
fn the_default_registration_lands_within_5_cm_and_1_degree_of_slam6d() {
    let Some(dir) = corridor() else { return };
    let input =
        pipeline::read_sequence(std::slice::from_ref(&dir), None, None, &Default::default())
            .expect("sequence");
    let scans = pipeline::read_scans(&input.scans, None).expect("scans");
    let cfg = pipeline::Config::default();
    let mut registrar = pipeline::open_registrar(&cfg.registration).expect("registrar");
    let reg = pipeline::register_scans(
        &input,
        &scans,
        &cfg.registration,
        &mut registrar,
        &mut |_, _| {},
    )
    .expect("registers");
    let world_from_scan = &reg.sequence.world_from_scan;
    let reference: Vec<_> = (0..3)
        .map(|k| {
            let frames =
                read_frames_3dtk(&dir.join("frames_2009").join(format!("scan{k:03}.frames")))
                    .expect("frames");
            *frames.last().expect("a frame")
        })
        .collect();
    for k in 1..3 {
        let ours = world_from_scan[0].inverse() * world_from_scan[k];
        let theirs = reference[0].inverse() * reference[k];
        let (et, er) = pose_error(&ours, &theirs);
        eprintln!("3dtk scan {k} with the defaults: {et:.4} m {er:.3} deg from slam6d 2009");
        // With the no-echo sphere kept, the defaults ended 7.5 and 11.8 cm, 1.5 and 2.2 deg
        // away (issue 15); without it 6.6 and 4.8 cm, 1.5 and 1.8 deg (mostly pitch); with the
        // sequence's range weighting (far points of a rotating laser are less certain)
        // 1.3 and 1.1 cm, 0.47 and 0.45 deg. The goal: 5 cm and 1 deg.
        assert!(et < 0.05 && er < 1.0, "scan {k}: {et} m {er} deg");
    }
}
