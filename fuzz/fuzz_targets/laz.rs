//! Any bytes as a `.laz` file: the same reader as `las`, seeded with LAZ files so that the
//! mutations exercise the LAZ decompressor.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    semsim_fuzz::tolerate_laz_panics();
    semsim_fuzz::scans_target("fuzz.laz", |p| interop::fuzzing::read_las_bytes(p, data));
});
