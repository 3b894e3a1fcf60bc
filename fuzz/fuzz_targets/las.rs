//! Any bytes as a `.las` file (LAS 1.0-1.4; a LAZ header is read as LAZ, as the reader does).
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    semsim_fuzz::tolerate_laz_panics();
    semsim_fuzz::scans_target("fuzz.las", |p| interop::fuzzing::read_las_bytes(p, data));
});
