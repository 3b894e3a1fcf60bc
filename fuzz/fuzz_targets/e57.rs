//! Any bytes as an `.e57` file; and the same bytes with every page's CRC recomputed, so that
//! mutations get past the page checks into the XML and the binary sections.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let read = |bytes: &[u8]| {
        semsim_fuzz::scans_target("fuzz.e57", |p| interop::fuzzing::read_e57_bytes(p, bytes))
    };
    read(data);
    if let Some(fixed) = semsim_fuzz::e57_with_page_crcs(data) {
        read(&fixed);
    }
});
