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
    /// No survey can be planned in the building (e.g. no free floor space for the tripod).
    #[error("{building}: {msg}")]
    Survey {
        /// The building's name (or file).
        building: String,
        /// Why not.
        msg: String,
    },
    /// A parameter outside its sensible range.
    #[error(transparent)]
    InvalidParameter(#[from] cloud::InvalidParameter),
}

/// Result with [`ScannerError`].
pub type Result<T, E = ScannerError> = std::result::Result<T, E>;

impl cloud::BadInput for ScannerError {
    fn is_bad_input(&self) -> bool {
        match self {
            ScannerError::Cloud(c) => c.is_bad_input(),
            ScannerError::Syntax { .. }
            | ScannerError::InvalidBuilding { .. }
            | ScannerError::Survey { .. }
            | ScannerError::InvalidParameter(_) => true,
        }
    }
}
