//! Any bytes as a `--config` file (TOML, one section per stage): parsed and every section
//! checked, never a panic.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(config) = toml::from_str::<pipeline::Config>(text) {
        let _ = config.validate();
    }
});
