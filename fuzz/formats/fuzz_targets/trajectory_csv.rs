//! Any bytes as a run folder's `trajectory.csv`: never a panic; a trajectory read is not empty,
//! finite and in time order; an error names the file and is bad input.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let name = "trajectory.csv";
    match console::fuzzing::read_trajectory_bytes(semsim_fuzz_formats::path(name), data) {
        Ok(track) => {
            assert!(!track.is_empty());
            for p in &track {
                let v = [
                    p.time_s,
                    p.x_m,
                    p.y_m,
                    p.z_m,
                    p.roll_deg,
                    p.pitch_deg,
                    p.yaw_deg,
                    p.speed_mps,
                ];
                assert!(v.iter().all(|x| x.is_finite()));
            }
            assert!(track.windows(2).all(|w| w[0].time_s <= w[1].time_s));
        }
        Err(e) => semsim_fuzz_formats::check_other_error(&e, name),
    }
});
