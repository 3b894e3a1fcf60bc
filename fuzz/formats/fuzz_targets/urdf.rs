//! Any bytes as a URDF robot description: parsed and mapped to a robot model, never a panic;
//! an error names the file and is bad input.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let name = "robot.urdf";
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Err(e) = sim::RobotModel::from_urdf_str(text, std::path::Path::new(name)) {
        semsim_fuzz_formats::check_other_error(&e, name);
    }
});
