//! Exit codes: 2 where the input (a file, a parameter, the command line) is at fault, 1 where the job failed.

use std::fmt;

/// An error caused by what the user gave: bad arguments, files or parameters.
#[derive(Debug)]
pub struct BadInput(pub String);

impl fmt::Display for BadInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for BadInput {}

/// Shorthand for a bad-input error.
pub fn bad_input(msg: impl Into<String>) -> anyhow::Error {
    anyhow::Error::new(BadInput(msg.into()))
}

/// The exit code for an error: 2 for bad input, 1 otherwise.
pub fn code_for(e: &anyhow::Error) -> u8 {
    for cause in e.chain() {
        if cause.is::<BadInput>() {
            return 2;
        }
        if let Some(c) = cause.downcast_ref::<cloud::CloudError>() {
            return if c.is_bad_input() { 2 } else { 1 };
        }
        if let Some(r) = cause.downcast_ref::<registration::RegistrationError>() {
            return match r {
                registration::RegistrationError::NotConverged { .. } => 1,
                // No adapter for `--device gpu`, or a cloud too large for the device: the
                // user's to fix; a device or driver failure is the job's.
                registration::RegistrationError::Gpu { error, .. } => {
                    if error.is_bad_input() {
                        2
                    } else {
                        1
                    }
                }
                _ => 2,
            };
        }
        if let Some(s) = cause.downcast_ref::<semantic::SemanticError>() {
            return match s {
                semantic::SemanticError::Cloud(c) if !c.is_bad_input() => 1,
                semantic::SemanticError::Image { .. } => 1,
                _ => 2,
            };
        }
        if cause.is::<sim::SimError>() {
            return 2;
        }
        if let Some(s) = cause.downcast_ref::<scanner::ScannerError>() {
            return match s {
                scanner::ScannerError::Cloud(c) if !c.is_bad_input() => 1,
                _ => 2,
            };
        }
    }
    1
}
