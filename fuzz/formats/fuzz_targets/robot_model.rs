//! Any bytes as a robot model (TOML): parsed and validated, never a panic; an error names the
//! file and is bad input.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let name = "robot.toml";
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Err(e) = sim::RobotModel::from_toml_str(text, name) {
        semsim_fuzz_formats::check_other_error(&e, name);
    }
});
