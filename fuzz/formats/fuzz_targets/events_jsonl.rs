//! Any bytes as a run folder's `events.jsonl`: never a panic; every event read has a finite
//! `time_s` and a `kind` string; an error names the file and is bad input.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let name = "events.jsonl";
    match console::fuzzing::read_events_bytes(semsim_fuzz_formats::path(name), data) {
        Ok(events) => {
            for e in &events {
                assert!(e["time_s"].as_f64().is_some_and(f64::is_finite));
                assert!(e["kind"].is_string());
            }
        }
        Err(e) => semsim_fuzz_formats::check_other_error(&e, name),
    }
});
