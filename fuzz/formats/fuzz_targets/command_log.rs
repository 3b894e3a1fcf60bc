//! Any bytes as a console session's `commands.jsonl` (replayed by `semsim simulate --replay`):
//! never a panic; a log read has its steps in order, every command within its limits and no
//! command after its end; an error names the file and is bad input.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let name = "commands.jsonl";
    match console::fuzzing::read_command_log_bytes(semsim_fuzz_formats::path(name), data) {
        Ok(log) => {
            assert!(log.commands.windows(2).all(|w| w[0].0 <= w[1].0));
            for (_, c) in &log.commands {
                assert!(c.check().is_ok(), "{c:?}");
            }
            if let (Some((end, _)), Some((last, _))) = (log.end, log.commands.last()) {
                assert!(*last <= end);
            }
        }
        Err(e) => semsim_fuzz_formats::check_other_error(&e, name),
    }
});
