//! The one range check for stage parameters, shared by every crate's configuration.

use std::borrow::Cow;

/// A parameter outside its sensible range, e.g. a voxel edge of 0 or `max_iterations = 0`.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("invalid parameter {name} = {value}: {msg}")]
pub struct InvalidParameter {
    /// The parameter's name, with its unit (e.g. `voxel_m`, `walls[2].thickness_m`).
    pub name: Cow<'static, str>,
    /// The value given.
    pub value: f64,
    /// What would be valid.
    pub msg: Cow<'static, str>,
}

/// `Ok` if `value` is finite and within `lo..=hi`; else an [`InvalidParameter`] naming it.
///
/// ```
/// assert!(cloud::check_range("voxel_m", 0.05, 1e-4, 10.0, "within 0.1 mm..10 m").is_ok());
/// let e = cloud::check_range("voxel_m", f64::NAN, 1e-4, 10.0, "within 0.1 mm..10 m").unwrap_err();
/// assert_eq!(e.to_string(), "invalid parameter voxel_m = NaN: within 0.1 mm..10 m");
/// ```
pub fn check_range(
    name: impl Into<Cow<'static, str>>,
    value: f64,
    lo: f64,
    hi: f64,
    msg: impl Into<Cow<'static, str>>,
) -> Result<(), InvalidParameter> {
    if value.is_finite() && value >= lo && value <= hi {
        Ok(())
    } else {
        Err(InvalidParameter {
            name: name.into(),
            value,
            msg: msg.into(),
        })
    }
}

/// Errors that know whether the user's input (a file, a parameter, the command line) is at
/// fault, or the system (a device, the disk, a job that did not converge). The binary maps
/// the first to exit code 2 and the second to 1.
pub trait BadInput {
    /// True where what the user gave is at fault.
    fn is_bad_input(&self) -> bool;
}

impl BadInput for InvalidParameter {
    fn is_bad_input(&self) -> bool {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_are_inclusive_and_non_finite_values_fail() {
        assert!(check_range("a", 1.0, 1.0, 2.0, "").is_ok());
        assert!(check_range("a", 2.0, 1.0, 2.0, "").is_ok());
        assert!(check_range("a", 2.000_001, 1.0, 2.0, "").is_err());
        assert!(check_range("a", f64::INFINITY, 1.0, f64::INFINITY, "").is_err());
        let e = check_range(
            format!("walls[{}].thickness_m", 3),
            -1.0,
            0.0,
            1.0,
            "positive",
        )
        .unwrap_err();
        assert_eq!(e.name, "walls[3].thickness_m");
        assert!(e.is_bad_input());
    }
}
