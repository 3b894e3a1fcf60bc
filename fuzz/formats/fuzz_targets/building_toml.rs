//! Any bytes as a building description (toml): parsed and validated, never a panic; an error
//! names the file and is bad input.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let name = "building.toml";
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match scanner::Building::from_toml_str(text, semsim_fuzz_formats::path(name)) {
        // A valid building must also give its geometry without a panic.
        Ok(b) => {
            let _ = scanner::BuildingGeometry::new(&b).parts().len();
        }
        Err(e) => semsim_fuzz_formats::check_other_error(&e, name),
    }
});
