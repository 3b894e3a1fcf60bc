//! Any bytes as a 3DTK `.3d` scan.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    semsim_fuzz::cloud_target("scan000.3d", |p| {
        cloud::fuzzing::read_3d_bytes(p, data).map(|c| (c, Vec::new()))
    });
});
