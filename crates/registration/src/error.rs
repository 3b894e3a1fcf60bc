//! Typed registration errors, each with the context needed to act on it.

use crate::result::IcpResult;

/// Everything that can go wrong in a registration.
#[derive(Debug, thiserror::Error)]
pub enum RegistrationError {
    /// A cloud holds no usable point (after dropping missing returns and downsampling).
    #[error("the {which} cloud has no valid point")]
    EmptyCloud {
        /// `"source"`, `"target"` or `"scan N"`.
        which: String,
    },
    /// An unorganised cloud holds a NaN or infinite coordinate (organised clouds may hold
    /// all-NaN missing returns, which are skipped).
    #[error("the {which} cloud has a non-finite point at index {index}")]
    NonFinite {
        /// `"source"`, `"target"` or `"scan N"`.
        which: String,
        /// Index of the first bad point.
        index: usize,
    },
    /// The first iteration found (almost) no correspondences: the clouds do not overlap from
    /// the given guess within the correspondence distance.
    #[error(
        "no overlap: the first iteration found {correspondences} correspondences within \
         {max_correspondence_distance_m} m (need at least {needed})"
    )]
    NoOverlap {
        /// The correspondence distance of the first iteration.
        max_correspondence_distance_m: f64,
        /// Correspondences found.
        correspondences: usize,
        /// Correspondences needed.
        needed: usize,
    },
    /// The iterations ended without meeting the stop criteria, or with too small a fitness.
    /// The result reached so far is carried for inspection.
    #[error("ICP did not converge: {reason} (rmse {:.4} m, fitness {:.3}, {} iterations)",
        result.rmse_m, result.fitness, result.iterations.len())]
    NotConverged {
        /// The last state of the registration.
        result: Box<IcpResult>,
        /// Why it is not a converged result.
        reason: String,
    },
    /// A configuration value is out of its meaningful range (the parameter's name is as in
    /// the configuration file).
    #[error(transparent)]
    InvalidParameter(#[from] cloud::InvalidParameter),
    /// A choice (not a number) that this configuration or build cannot run, e.g. `device = gpu`
    /// with GICP.
    #[error("{name} = {choice}: {msg}")]
    UnsupportedChoice {
        /// The parameter, as in the configuration file.
        name: &'static str,
        /// The value chosen.
        choice: String,
        /// Why it cannot run and what to choose instead.
        msg: &'static str,
    },
    /// The GPU path failed: no adapter for `device = gpu`, an input too large for the device,
    /// or a device / driver error.
    /// (The GPU error is part of the message, not a separate `source()`, so that printing the
    /// error chain does not repeat it.)
    #[cfg(feature = "gpu")]
    #[error("GPU registration failed while {context}: {error}")]
    Gpu {
        /// What was being done.
        context: String,
        /// The GPU error.
        error: gpu::GpuError,
    },
    /// The two inputs to a sequence registration disagree (e.g. poses and scans counts).
    #[error("{what}: {msg}")]
    Mismatch {
        /// What disagrees.
        what: &'static str,
        /// How.
        msg: String,
    },
}

impl RegistrationError {
    /// Shorthand for [`RegistrationError::InvalidParameter`].
    pub(crate) fn invalid(
        name: &'static str,
        value: f64,
        msg: impl Into<std::borrow::Cow<'static, str>>,
    ) -> Self {
        RegistrationError::InvalidParameter(cloud::InvalidParameter {
            name: name.into(),
            value,
            msg: msg.into(),
        })
    }
}

#[cfg(feature = "gpu")]
impl RegistrationError {
    /// Wraps a GPU error with what was being done.
    pub(crate) fn gpu(context: impl Into<String>) -> impl FnOnce(gpu::GpuError) -> Self {
        let context = context.into();
        move |error| RegistrationError::Gpu { context, error }
    }
}

impl cloud::BadInput for RegistrationError {
    /// A registration that ran but did not converge is no fault of the input; a GPU error says
    /// for itself; everything else (a bad cloud, parameter, or mismatched inputs) is.
    fn is_bad_input(&self) -> bool {
        match self {
            RegistrationError::NotConverged { .. } => false,
            #[cfg(feature = "gpu")]
            RegistrationError::Gpu { error, .. } => cloud::BadInput::is_bad_input(error),
            _ => true,
        }
    }
}

/// Result alias for this crate.
pub type Result<T, E = RegistrationError> = std::result::Result<T, E>;
