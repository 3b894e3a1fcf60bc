//! Any bytes as a `.xyz` file.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    semsim_fuzz::cloud_target("fuzz.xyz", |p| {
        cloud::fuzzing::read_xyz_bytes(p, data).map(|c| (c, Vec::new()))
    });
});
