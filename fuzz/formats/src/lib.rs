//! What the description-file targets check beyond libFuzzer's own (no panic, no abort, no
//! timeout, no allocation over the RSS limit): an error names the file and is the input's fault.
//! (Control characters a parser quotes are escaped by the binary when it prints, not here.)

use std::fmt::Display;

/// The path every target hands to the reader.
pub fn path(name: &str) -> &std::path::Path {
    std::path::Path::new(name)
}

/// Checks an error: names `name` and is bad input (exit 2).
pub fn check_other_error<E: Display + cloud::BadInput>(e: &E, name: &str) {
    let text = e.to_string();
    assert!(text.contains(name), "message does not name {name}: {text}");
    assert!(
        e.is_bad_input(),
        "an error reading a file must be the input's fault: {text}"
    );
}
