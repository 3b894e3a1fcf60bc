//! The gpu crate's typed errors.

/// Everything that can go wrong on the GPU path.
#[derive(Debug, Clone, thiserror::Error)]
pub enum GpuError {
    /// No GPU adapter (not even a software one) is available.
    #[error("no GPU adapter found ({0}); install a Vulkan driver (e.g. Mesa's lavapipe: mesa-vulkan-drivers) or use --device cpu")]
    NoAdapter(String),
    /// The adapter refused to create a device.
    #[error("the GPU adapter '{adapter}' could not open a device: {msg}")]
    Device {
        /// Adapter name.
        adapter: String,
        /// The driver's message.
        msg: String,
    },
    /// A cloud or grid too large for the device's limits.
    #[error("too large for the GPU: {0}")]
    TooLarge(String),
    /// An input the GPU path cannot use (empty, non-finite, bad parameter).
    #[error("invalid input for the GPU path: {0}")]
    Invalid(String),
    /// A buffer could not be read back.
    #[error("reading GPU results failed: {0}")]
    Readback(String),
    /// wgpu rejected an operation (a validation error: a bug in the kernels' use of wgpu, or
    /// an input the checks above missed).
    #[error("GPU validation error while {during}: {msg}")]
    Validation {
        /// What was being done.
        during: String,
        /// wgpu's description.
        msg: String,
    },
    /// The device ran out of memory.
    #[error("GPU out of memory while {during}: {msg}")]
    OutOfMemory {
        /// What was being done.
        during: String,
        /// wgpu's description.
        msg: String,
    },
    /// An internal driver error (e.g. a lost device).
    #[error("GPU driver error while {during}: {msg}")]
    Internal {
        /// What was being done.
        during: String,
        /// The driver's description.
        msg: String,
    },
}

impl cloud::BadInput for GpuError {
    /// Whether the error is the caller's (no adapter, an unusable or too large input) rather
    /// than a failure of the device or driver.
    fn is_bad_input(&self) -> bool {
        matches!(
            self,
            GpuError::NoAdapter(_) | GpuError::TooLarge(_) | GpuError::Invalid(_)
        )
    }
}

impl GpuError {
    pub(crate) fn from_wgpu(during: &str, e: wgpu::Error) -> GpuError {
        let during = during.to_string();
        match e {
            wgpu::Error::OutOfMemory { source } => GpuError::OutOfMemory {
                during,
                msg: source.to_string(),
            },
            wgpu::Error::Validation { description, .. } => GpuError::Validation {
                during,
                msg: description,
            },
            wgpu::Error::Internal { description, .. } => GpuError::Internal {
                during,
                msg: description,
            },
        }
    }
}

/// Result with [`GpuError`].
pub type Result<T, E = GpuError> = std::result::Result<T, E>;
