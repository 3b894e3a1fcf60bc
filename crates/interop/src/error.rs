//! The interop crate's typed errors: every variant names the file and what is wrong.

use std::path::PathBuf;

/// Everything that can go wrong importing scans or exporting a world.
#[derive(Debug, thiserror::Error)]
pub enum InteropError {
    /// Reading or writing a format the cloud crate owns (PCD, PLY, XYZ, 3DTK), or an I/O error.
    #[error(transparent)]
    Cloud(#[from] cloud::CloudError),
    /// The world or robot to export is not valid.
    #[error(transparent)]
    Sim(#[from] sim::SimError),
    /// A file that does not follow its format (cut short, corrupt, or holding what semsim
    /// cannot use).
    #[error("{path}: {message}")]
    Format {
        /// The file concerned.
        path: PathBuf,
        /// What is wrong, in the file's terms.
        message: String,
    },
    /// Something valid in the format that semsim cannot represent (e.g. a URDF joint type).
    #[error("{path}: unsupported: {message}")]
    Unsupported {
        /// The file concerned.
        path: PathBuf,
        /// What cannot be used, and why.
        message: String,
    },
    /// Memory for the file's data could not be had.
    #[error("{path}: not enough memory for {what}")]
    OutOfMemory {
        /// The file concerned.
        path: PathBuf,
        /// What was being allocated.
        what: String,
    },
}

impl InteropError {
    /// A format error naming the file.
    pub fn format(path: impl Into<PathBuf>, message: impl Into<String>) -> Self {
        InteropError::Format {
            path: path.into(),
            message: message.into(),
        }
    }

    /// An unsupported-content error naming the file.
    pub fn unsupported(path: impl Into<PathBuf>, message: impl Into<String>) -> Self {
        InteropError::Unsupported {
            path: path.into(),
            message: message.into(),
        }
    }
}

impl cloud::BadInput for InteropError {
    /// True where the file or the parameters are at fault: everything but out-of-memory and
    /// the system's own I/O failures (as the cloud crate decides them).
    fn is_bad_input(&self) -> bool {
        match self {
            InteropError::Cloud(e) => e.is_bad_input(),
            InteropError::Sim(e) => e.is_bad_input(),
            InteropError::OutOfMemory { .. } => false,
            InteropError::Format { .. } | InteropError::Unsupported { .. } => true,
        }
    }
}

/// The interop crate's result type.
pub type Result<T> = std::result::Result<T, InteropError>;
