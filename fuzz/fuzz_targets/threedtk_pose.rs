//! Any bytes as a 3DTK `.pose` file.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let name = "scan000.pose";
    match cloud::fuzzing::read_pose_3dtk_bytes(semsim_fuzz::path(name), data) {
        Ok(pose) => semsim_fuzz::check_pose(&pose),
        Err(e) => semsim_fuzz::check_error(&e, name),
    }
});
