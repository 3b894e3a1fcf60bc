//! Any bytes as a run folder's `doors.csv` (the door angles the console and `semsim report`
//! replay): never a panic; a track read has one finite angle per door in every sample, in time
//! order; an error names the file and is bad input.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let name = "doors.csv";
    match console::fuzzing::read_doors_bytes(semsim_fuzz_formats::path(name), data) {
        Ok(track) => {
            for s in &track.samples {
                assert_eq!(s.angles_deg.len(), track.doors.len(), "a sample per door");
                assert!(s.time_s.is_finite() && s.angles_deg.iter().all(|a| a.is_finite()));
            }
            assert!(track.samples.windows(2).all(|w| w[0].time_s <= w[1].time_s));
        }
        Err(e) => semsim_fuzz_formats::check_other_error(&e, name),
    }
});
