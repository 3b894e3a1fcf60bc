//! The cloud crate's typed errors: every variant names the file (where there is one) and what is wrong.

use std::path::PathBuf;

/// Everything that can go wrong reading, writing or processing a point cloud.
#[derive(Debug, thiserror::Error)]
pub enum CloudError {
    /// The operating system refused a read or write.
    #[error("{path}: {source}")]
    Io {
        /// The file concerned.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// A header or a line of text that does not follow the format.
    #[error("{path}:{line}: {msg}")]
    Parse {
        /// The file concerned.
        path: PathBuf,
        /// 1-based line number (0 where no line applies, e.g. binary data).
        line: usize,
        /// What is wrong.
        msg: String,
    },
    /// The file ends before the data its header promises.
    #[error("{path}: truncated: {msg}")]
    Truncated {
        /// The file concerned.
        path: PathBuf,
        /// What was expected and what was found.
        msg: String,
    },
    /// A point with a NaN or infinite coordinate where the format does not allow one.
    #[error("{path}: point {index} has a non-finite coordinate ({value:?}); only organised clouds may mark missing returns with NaN")]
    NonFinite {
        /// The file concerned (empty for in-memory clouds).
        path: PathBuf,
        /// 0-based point index.
        index: usize,
        /// The offending coordinates.
        value: [f32; 3],
    },
    /// The file extension names no format semsim knows.
    #[error("{path}: unknown point cloud format (known extensions: .pcd, .ply, .xyz, .txt, .3d)")]
    UnknownFormat {
        /// The file concerned.
        path: PathBuf,
    },
    /// A feature of a format that semsim does not support (yet), named precisely.
    #[error("{path}: unsupported: {msg}")]
    Unsupported {
        /// The file concerned.
        path: PathBuf,
        /// What is unsupported.
        msg: String,
    },
    /// A parameter outside its sensible range (e.g. a voxel size of 0).
    #[error(transparent)]
    InvalidParameter(#[from] crate::param::InvalidParameter),
    /// A cloud whose parts disagree (e.g. label count != point count).
    #[error("inconsistent cloud: {0}")]
    Inconsistent(String),
}

impl CloudError {
    /// Wraps an I/O error with the file it concerns.
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        CloudError::Io {
            path: path.into(),
            source,
        }
    }

    /// A parse error at a 1-based line.
    pub fn parse(path: impl Into<PathBuf>, line: usize, msg: impl Into<String>) -> Self {
        CloudError::Parse {
            path: path.into(),
            line,
            msg: msg.into(),
        }
    }

}

impl crate::BadInput for CloudError {
    /// True where the input (a file or a parameter) is at fault rather than the system: every
    /// error but one the operating system raised reading or writing (other than a missing file).
    fn is_bad_input(&self) -> bool {
        !matches!(self, CloudError::Io { source, .. } if source.kind() != std::io::ErrorKind::NotFound && source.kind() != std::io::ErrorKind::InvalidData && source.kind() != std::io::ErrorKind::UnexpectedEof)
    }
}

/// Result with [`CloudError`].
pub type Result<T, E = CloudError> = std::result::Result<T, E>;
