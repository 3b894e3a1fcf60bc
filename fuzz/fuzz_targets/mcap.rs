//! Any bytes as a ROS 2 bag (`.mcap`), read with the default options (the only PointCloud2
//! topic, the only Odometry topic).
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    semsim_fuzz::scans_target("fuzz.mcap", |p| interop::fuzzing::read_mcap_bytes(p, data));
});
