//! Exit codes: 2 where the input (a file, a parameter, the command line) is at fault, 1 where
//! the job failed. Every library error answers which through `cloud::BadInput`.

use cloud::BadInput;
use std::fmt;

/// An error in what the user gave on the command line.
#[derive(Debug)]
pub struct UsageError(pub String);

impl fmt::Display for UsageError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for UsageError {}

/// Shorthand for a command-line error (exit 2).
pub fn bad_input(msg: impl Into<String>) -> anyhow::Error {
    anyhow::Error::new(UsageError(msg.into()))
}

/// The exit code for an error: 2 if the first library error in its chain is the input's
/// fault (or a command-line error), 1 otherwise.
pub fn code_for(e: &anyhow::Error) -> u8 {
    for cause in e.chain() {
        if cause.is::<UsageError>() {
            return 2;
        }
        if let Some(bad) = as_bad_input(cause) {
            return if bad { 2 } else { 1 };
        }
    }
    1
}

/// Whether a library error is the input's fault; `None` for errors of no library crate.
fn as_bad_input(cause: &(dyn std::error::Error + 'static)) -> Option<bool> {
    macro_rules! try_types {
        ($($t:ty),*) => {
            $(if let Some(e) = cause.downcast_ref::<$t>() {
                return Some(e.is_bad_input());
            })*
        };
    }
    try_types!(
        pipeline::PipelineError,
        cloud::CloudError,
        cloud::InvalidParameter,
        scanner::ScannerError,
        registration::RegistrationError,
        gpu::GpuError,
        semantic::SemanticError,
        evaluate::EvalError,
        sim::SimError,
        interop::InteropError,
        console::ConsoleError
    );
    None
}
