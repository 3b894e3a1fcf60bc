//! Any bytes as a 3DTK `.frames` file.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let name = "scan000.frames";
    match cloud::fuzzing::read_frames_3dtk_bytes(semsim_fuzz::path(name), data) {
        Ok(frames) => {
            assert!(!frames.is_empty(), "a frames file has at least one frame");
            frames.iter().for_each(semsim_fuzz::check_pose);
        }
        Err(e) => semsim_fuzz::check_error(&e, name),
    }
});
