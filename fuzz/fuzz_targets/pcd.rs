//! Any bytes as a `.pcd` file (ascii, binary and binary_compressed).
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    semsim_fuzz::cloud_target("fuzz.pcd", |p| cloud::fuzzing::read_pcd_bytes(p, data));
});
