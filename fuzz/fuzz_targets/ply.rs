//! Any bytes as a `.ply` file (ascii, binary_little_endian, binary_big_endian).
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    semsim_fuzz::cloud_target("fuzz.ply", |p| cloud::fuzzing::read_ply_bytes(p, data));
});
