//! The gpu crate's typed errors.

/// Everything that can go wrong on the GPU path.
#[derive(Debug, thiserror::Error)]
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
}

/// Result with [`GpuError`].
pub type Result<T, E = GpuError> = std::result::Result<T, E>;
