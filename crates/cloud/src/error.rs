//! The cloud crate's typed errors: every variant names the file (where there is one) and what is wrong.

use std::io::ErrorKind;
use std::path::{Path, PathBuf};

/// Everything that can go wrong reading, writing or processing a point cloud.
#[derive(Debug, thiserror::Error)]
pub enum CloudError {
    /// The operating system refused a read or write. The message holds the operating system's
    /// text once: `error` is not reported again as the error's `source()`.
    #[error("{path}: {error}")]
    Io {
        /// The file concerned.
        path: PathBuf,
        /// The operating system's error (its text is part of this error's message).
        error: std::io::Error,
    },
    /// A header or a line of text that does not follow the format.
    #[error("{}", located(.path, *.line, .msg))]
    Parse {
        /// The file concerned.
        path: PathBuf,
        /// 1-based line number (0 where no line applies, e.g. binary data or the whole file).
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
    /// The memory a (valid) file needs could not be had: the job failed, the file is not at
    /// fault (exit code 1, not 2).
    #[error("{path}: out of memory: could not allocate {bytes} bytes ({}) for {what}", human_bytes(*.bytes))]
    OutOfMemory {
        /// The file being read or written.
        path: PathBuf,
        /// The size of the allocation that failed.
        bytes: u64,
        /// What the memory was for (e.g. `the decompressed data`).
        what: String,
    },
    /// A parameter outside its sensible range (e.g. a voxel size of 0).
    #[error(transparent)]
    InvalidParameter(#[from] crate::param::InvalidParameter),
    /// A cloud whose parts disagree (e.g. label count != point count).
    #[error("inconsistent cloud: {0}")]
    Inconsistent(String),
}

/// `path:line: msg`, or `path: msg` where no line applies (line 0).
fn located(path: &Path, line: usize, msg: &str) -> String {
    if line == 0 {
        format!("{}: {msg}", path.display())
    } else {
        format!("{}:{line}: {msg}", path.display())
    }
}

/// A byte count for people: `2.20 GB`, `512 KB`, `17 bytes`.
fn human_bytes(bytes: u64) -> String {
    const UNITS: [(f64, &str); 4] = [(1e12, "TB"), (1e9, "GB"), (1e6, "MB"), (1e3, "KB")];
    let b = bytes as f64;
    UNITS.iter().find(|(scale, _)| b >= *scale).map_or_else(
        || format!("{bytes} bytes"),
        |(scale, unit)| format!("{:.2} {unit}", b / scale),
    )
}

impl CloudError {
    /// Wraps an I/O error with the file it concerns.
    pub fn io(path: impl Into<PathBuf>, error: std::io::Error) -> Self {
        CloudError::Io {
            path: path.into(),
            error,
        }
    }

    /// A parse error at a 1-based line (0: no particular line).
    pub fn parse(path: impl Into<PathBuf>, line: usize, msg: impl Into<String>) -> Self {
        CloudError::Parse {
            path: path.into(),
            line,
            msg: msg.into(),
        }
    }

    /// The error for a file that could not be read: "is a folder, not a file" for a folder,
    /// else the operating system's error.
    pub(crate) fn reading(path: &Path, error: std::io::Error) -> Self {
        if error.kind() == ErrorKind::IsADirectory || path.is_dir() {
            return CloudError::io(
                path,
                std::io::Error::new(ErrorKind::IsADirectory, "is a folder, not a file"),
            );
        }
        CloudError::io(path, error)
    }
}

/// Whether an I/O error is the fault of the path the user gave (bad input, exit code 2) rather
/// than of the system (the job failed, exit code 1).
///
/// The rule: a path that cannot be used is bad input: it does not exist, is a folder where a
/// file is wanted (or the reverse), may not be read or written, already exists, lies on a
/// read-only file system, has an invalid name, or its content is invalid or cut short. A failure
/// of the system itself is not: a full disk or quota, no memory, an interrupted, timed-out,
/// blocking or busy operation, a failed write, a network error, and every kind not listed
/// (`Other`, kinds newer than this list).
pub(crate) fn io_kind_is_bad_input(kind: ErrorKind) -> bool {
    match kind {
        ErrorKind::NotFound
        | ErrorKind::PermissionDenied
        | ErrorKind::AlreadyExists
        | ErrorKind::InvalidInput
        | ErrorKind::InvalidData
        | ErrorKind::UnexpectedEof
        | ErrorKind::NotADirectory
        | ErrorKind::IsADirectory
        | ErrorKind::DirectoryNotEmpty
        | ErrorKind::ReadOnlyFilesystem
        | ErrorKind::NotSeekable
        | ErrorKind::TooManyLinks => true,
        ErrorKind::StorageFull
        | ErrorKind::QuotaExceeded
        | ErrorKind::FileTooLarge
        | ErrorKind::OutOfMemory
        | ErrorKind::Interrupted
        | ErrorKind::TimedOut
        | ErrorKind::WouldBlock
        | ErrorKind::ResourceBusy
        | ErrorKind::ExecutableFileBusy
        | ErrorKind::Deadlock
        | ErrorKind::WriteZero
        | ErrorKind::CrossesDevices
        | ErrorKind::StaleNetworkFileHandle
        | ErrorKind::Unsupported
        | ErrorKind::Other => false,
        // Kinds stabilised after the workspace's MSRV (1.85), or still unstable, by name:
        // `InvalidFilename` (ENAMETOOLONG, 1.87) and `FilesystemLoop` (ELOOP) are the path's fault.
        other => matches!(
            format!("{other:?}").as_str(),
            "InvalidFilename" | "FilesystemLoop"
        ),
    }
}

impl crate::BadInput for CloudError {
    /// True where the input (a file, a path or a parameter) is at fault rather than the system:
    /// every error except [`CloudError::OutOfMemory`] and the I/O errors of the system itself.
    ///
    /// A path the user gave that cannot be used is bad input (exit code 2): it does not exist,
    /// is a folder where a file is wanted (or the reverse), may not be read or written, already
    /// exists, lies on a read-only file system, has an invalid or too long name, or its content
    /// is invalid or cut short. The job failed (exit code 1) where the system did: a full disk
    /// or quota, no memory, an interrupted, timed-out, blocking or busy operation, a failed
    /// write, a network error, and every kind of I/O error not named here (`Other`, new kinds).
    fn is_bad_input(&self) -> bool {
        match self {
            CloudError::Io { error, .. } => io_kind_is_bad_input(error.kind()),
            CloudError::OutOfMemory { .. } => false,
            _ => true,
        }
    }
}

/// An empty vector with room for `n` items, or [`CloudError::OutOfMemory`] naming the file and
/// `what` where the memory cannot be had (instead of aborting the process).
pub(crate) fn try_vec<T>(path: &Path, n: usize, what: &str) -> Result<Vec<T>> {
    let mut v = Vec::new();
    try_reserve(path, &mut v, n, what)?;
    Ok(v)
}

/// `v.try_reserve_exact(additional)`, with the error of [`try_vec`].
pub(crate) fn try_reserve<T>(
    path: &Path,
    v: &mut Vec<T>,
    additional: usize,
    what: &str,
) -> Result<()> {
    v.try_reserve_exact(additional)
        .map_err(|_| CloudError::OutOfMemory {
            path: path.to_path_buf(),
            bytes: (additional as u64).saturating_mul(std::mem::size_of::<T>() as u64),
            what: what.to_string(),
        })
}

/// `n` copies of `value`, or [`CloudError::OutOfMemory`] (see [`try_vec`]).
pub(crate) fn try_filled<T: Clone>(path: &Path, n: usize, value: T, what: &str) -> Result<Vec<T>> {
    let mut v = try_vec(path, n, what)?;
    v.resize(n, value);
    Ok(v)
}

/// Result with [`CloudError`].
pub type Result<T, E = CloudError> = std::result::Result<T, E>;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::BadInput;

    #[test]
    fn io_kinds_split_into_path_faults_and_system_failures() {
        for kind in [
            ErrorKind::NotFound,
            ErrorKind::PermissionDenied,
            ErrorKind::IsADirectory,
            ErrorKind::NotADirectory,
            ErrorKind::AlreadyExists,
            ErrorKind::InvalidInput,
            ErrorKind::InvalidData,
            ErrorKind::UnexpectedEof,
            ErrorKind::ReadOnlyFilesystem,
            ErrorKind::DirectoryNotEmpty,
        ] {
            assert!(io_kind_is_bad_input(kind), "{kind:?}");
        }
        for kind in [
            ErrorKind::StorageFull,
            ErrorKind::OutOfMemory,
            ErrorKind::Interrupted,
            ErrorKind::TimedOut,
            ErrorKind::WouldBlock,
            ErrorKind::ResourceBusy,
            ErrorKind::WriteZero,
            ErrorKind::Other,
            ErrorKind::BrokenPipe,
            ErrorKind::ConnectionReset,
        ] {
            assert!(!io_kind_is_bad_input(kind), "{kind:?}");
        }
        // ENAMETOOLONG is InvalidFilename (a kind newer than the MSRV, matched by name).
        #[cfg(target_os = "linux")]
        assert!(io_kind_is_bad_input(
            std::io::Error::from_raw_os_error(36).kind()
        ));
    }

    #[test]
    fn out_of_memory_is_not_bad_input_and_names_the_size() {
        let e = try_vec::<u64>(Path::new("big.pcd"), usize::MAX / 4, "the points").unwrap_err();
        assert!(!e.is_bad_input());
        let text = e.to_string();
        assert!(text.starts_with("big.pcd: out of memory"), "{text}");
        assert!(text.contains("for the points"), "{text}");
        assert_eq!(human_bytes(2_200_000_000), "2.20 GB");
        assert_eq!(human_bytes(17), "17 bytes");
    }

    #[test]
    fn parse_errors_without_a_line_name_only_the_file() {
        assert_eq!(
            CloudError::parse("a.xyz", 0, "no points").to_string(),
            "a.xyz: no points"
        );
        assert_eq!(
            CloudError::parse("a.xyz", 3, "bad").to_string(),
            "a.xyz:3: bad"
        );
    }
}
