//! The pipeline's typed errors: each stage's own error, or what the chain itself checks
//! (scan folders, pose files against scans, scan poses in a building).

/// Everything that can go wrong between scans and a verdict.
#[derive(Debug, thiserror::Error)]
pub enum PipelineError {
    /// Reading or writing a cloud, a pose file or any output.
    #[error(transparent)]
    Cloud(#[from] cloud::CloudError),
    /// A building description or the virtual laser.
    #[error(transparent)]
    Scanner(#[from] scanner::ScannerError),
    /// Registration.
    #[error(transparent)]
    Registration(#[from] registration::RegistrationError),
    /// The GPU (benchmarks open one directly).
    #[error(transparent)]
    Gpu(#[from] gpu::GpuError),
    /// The semantic map.
    #[error(transparent)]
    Semantic(#[from] semantic::SemanticError),
    /// Scans read from E57, LAS/LAZ or a ROS 2 bag, or a world exported.
    #[error(transparent)]
    Interop(#[from] interop::InteropError),
    /// The simulation, its scenario or its world.
    #[error(transparent)]
    Sim(#[from] sim::SimError),
    /// Evaluation against ground truth.
    #[error(transparent)]
    Eval(#[from] evaluate::EvalError),
    /// Input the chain cannot use: the message names the file or option and the problem.
    #[error("{0}")]
    BadInput(String),
    /// The configuration file.
    #[error("{path}: {msg}")]
    Config {
        /// The file.
        path: std::path::PathBuf,
        /// What is wrong (the TOML parser's message with line and column).
        msg: String,
    },
    /// A chart could not be drawn.
    #[error("{path}: {msg}")]
    Plot {
        /// The chart's file.
        path: std::path::PathBuf,
        /// What failed.
        msg: String,
    },
    /// A report could not be serialised (a bug, not the input's fault).
    #[error("serialising {what}: {msg}")]
    Serialise {
        /// What was being serialised.
        what: &'static str,
        /// The serialiser's message.
        msg: String,
    },
}

impl PipelineError {
    /// Shorthand for [`PipelineError::BadInput`].
    pub fn bad_input(msg: impl Into<String>) -> PipelineError {
        PipelineError::BadInput(msg.into())
    }
}

impl cloud::BadInput for PipelineError {
    fn is_bad_input(&self) -> bool {
        match self {
            PipelineError::Cloud(e) => e.is_bad_input(),
            PipelineError::Scanner(e) => e.is_bad_input(),
            PipelineError::Registration(e) => e.is_bad_input(),
            PipelineError::Gpu(e) => e.is_bad_input(),
            PipelineError::Semantic(e) => e.is_bad_input(),
            PipelineError::Sim(e) => e.is_bad_input(),
            PipelineError::Interop(e) => e.is_bad_input(),
            PipelineError::Eval(e) => e.is_bad_input(),
            PipelineError::BadInput(_) | PipelineError::Config { .. } => true,
            PipelineError::Serialise { .. } | PipelineError::Plot { .. } => false,
        }
    }
}

/// Result with [`PipelineError`].
pub type Result<T, E = PipelineError> = std::result::Result<T, E>;

/// Serialises `value` as pretty JSON.
pub(crate) fn to_json<T: serde::Serialize>(what: &'static str, value: &T) -> Result<String> {
    serde_json::to_string_pretty(value).map_err(|e| PipelineError::Serialise {
        what,
        msg: e.to_string(),
    })
}
