//! Any bytes as a simulation checkpoint: decoded, never a panic or an allocation the bytes
//! dictate; an error is bad input.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Err(e) = sim::Simulation::from_checkpoint_bytes(data) {
        semsim_fuzz_formats::check_other_error(&e, "<memory>");
    }
});
