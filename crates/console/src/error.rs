//! The console's typed errors: the world, scenario or robot it was given, its configuration,
//! the listening socket, a command log, and writing a session's run folder.

use std::net::SocketAddr;
use std::path::PathBuf;

/// Everything that can go wrong in the console.
#[derive(Debug, thiserror::Error)]
pub enum ConsoleError {
    /// Reading or writing a file (a run folder, a command log).
    #[error(transparent)]
    Cloud(#[from] cloud::CloudError),
    /// The simulation, its scenario, robot or world.
    #[error(transparent)]
    Sim(#[from] sim::SimError),
    /// A building description.
    #[error(transparent)]
    Scanner(#[from] scanner::ScannerError),
    /// A semantic map.
    #[error(transparent)]
    Semantic(#[from] semantic::SemanticError),
    /// The world's GLB export.
    #[error(transparent)]
    Interop(#[from] interop::InteropError),
    /// A configuration value out of range.
    #[error("console configuration: {0}")]
    Config(String),
    /// The listening socket could not be opened.
    #[error("cannot listen on {addr}: {source}")]
    Bind {
        /// The address asked for.
        addr: SocketAddr,
        /// Why not.
        source: std::io::Error,
    },
    /// The server failed while serving.
    #[error("the console server failed: {0}")]
    Serve(std::io::Error),
    /// A command log (`commands.jsonl`) that does not follow its format.
    #[error("{path}:{line}: {msg}")]
    CommandLog {
        /// The file.
        path: PathBuf,
        /// The line (1-based).
        line: usize,
        /// What is wrong.
        msg: String,
    },
    /// A run folder (or one of its files) that is missing or malformed.
    #[error("{}{}: {msg}", path.display(), line.map(|l| format!(":{l}")).unwrap_or_default())]
    RunFolder {
        /// The folder or file.
        path: PathBuf,
        /// The line (1-based), where one is at fault.
        line: Option<usize>,
        /// What is wrong.
        msg: String,
    },
    /// A cloud for the page's cloud layer that has nothing to show.
    #[error("{}: {msg}", path.display())]
    CloudLayer {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        msg: String,
    },
    /// The simulation thread ended unexpectedly (a bug, not the input's fault).
    #[error("the simulation thread ended unexpectedly")]
    SimulationThread,
}

impl cloud::BadInput for ConsoleError {
    fn is_bad_input(&self) -> bool {
        match self {
            ConsoleError::Cloud(e) => e.is_bad_input(),
            ConsoleError::Sim(e) => e.is_bad_input(),
            ConsoleError::Scanner(e) => e.is_bad_input(),
            ConsoleError::Semantic(e) => e.is_bad_input(),
            ConsoleError::Interop(e) => e.is_bad_input(),
            ConsoleError::Config(_)
            | ConsoleError::CommandLog { .. }
            | ConsoleError::RunFolder { .. }
            | ConsoleError::CloudLayer { .. } => true,
            // An address this machine does not have is the user's; a port in use is not.
            ConsoleError::Bind { source, .. } => {
                source.kind() == std::io::ErrorKind::AddrNotAvailable
            }
            ConsoleError::Serve(_) | ConsoleError::SimulationThread => false,
        }
    }
}

/// Result with [`ConsoleError`].
pub type Result<T, E = ConsoleError> = std::result::Result<T, E>;
