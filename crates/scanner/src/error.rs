//! The scanner crate's typed errors.

use std::path::PathBuf;

/// Everything that can go wrong with a building description, a laser configuration or a scan.
#[derive(Debug, thiserror::Error)]
pub enum ScannerError {
    /// The file could not be read or written.
    #[error(transparent)]
    Cloud(#[from] cloud::CloudError),
    /// The building file is not valid TOML/JSON for a building.
    #[error("{path}: {msg}")]
    Syntax {
        /// The building file.
        path: PathBuf,
        /// The parser's message (with line and column).
        msg: String,
    },
    /// The building parses but describes something impossible.
    #[error("{path}: {element}: {msg}")]
    InvalidBuilding {
        /// The building file (`<built-in>` for an embedded one).
        path: PathBuf,
        /// Which element is wrong, e.g. `walls[3].doors[0]`.
        element: String,
        /// What is wrong.
        msg: String,
    },
    /// A parameter outside its sensible range.
    #[error("invalid parameter {name} = {value}: {msg}")]
    InvalidParameter {
        /// Parameter name with unit.
        name: &'static str,
        /// The value given.
        value: f64,
        /// What would be valid.
        msg: &'static str,
    },
}

/// Result with [`ScannerError`].
pub type Result<T, E = ScannerError> = std::result::Result<T, E>;

/// Checks `lo <= value <= hi` (and finiteness) for a named parameter.
pub(crate) fn check_range(
    name: &'static str,
    value: f64,
    lo: f64,
    hi: f64,
    msg: &'static str,
) -> Result<()> {
    if value.is_finite() && value >= lo && value <= hi {
        Ok(())
    } else {
        Err(ScannerError::InvalidParameter { name, value, msg })
    }
}
