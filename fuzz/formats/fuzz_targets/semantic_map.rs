//! Any bytes as a semantic map (JSON): parsed and validated, then imported as a simulation
//! world, never a panic; an error names the file and is bad input.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let name = "semantic_map.json";
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match semantic::SemanticMap::from_json_str(text, semsim_fuzz_formats::path(name)) {
        Ok(map) => {
            if let Err(e) = sim::WorldSpec::from_semantic_map(&map) {
                assert!(cloud::BadInput::is_bad_input(&e), "{e}");
            }
        }
        Err(e) => semsim_fuzz_formats::check_other_error(&e, name),
    }
});
