//! Any bytes as a pose file (`name` and a row-major 4x4 matrix a line).
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let name = "poses.txt";
    match cloud::fuzzing::read_poses_bytes(semsim_fuzz::path(name), data) {
        Ok(poses) => poses
            .iter()
            .for_each(|p| semsim_fuzz::check_pose(&p.world_from_scan)),
        Err(e) => semsim_fuzz::check_error(&e, name),
    }
});
