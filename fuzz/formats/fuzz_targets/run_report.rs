//! Any bytes as a run folder's `report.md` (its title, verdict and rules table, read back by
//! the console and `semsim report`): never a panic; an error names the file and is bad input.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let name = "report.md";
    if let Err(e) = console::fuzzing::read_report_bytes(semsim_fuzz_formats::path(name), data) {
        semsim_fuzz_formats::check_other_error(&e, name);
    }
});
