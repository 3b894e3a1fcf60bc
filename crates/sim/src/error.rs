//! The sim crate's typed errors: every variant says which input, which element and what is wrong.

use std::path::PathBuf;

/// Everything that can go wrong building, running, judging or checkpointing a simulation.
#[derive(Debug, thiserror::Error)]
pub enum SimError {
    /// A file could not be read or written.
    #[error(transparent)]
    Cloud(#[from] cloud::CloudError),
    /// The building could not be loaded.
    #[error(transparent)]
    Building(#[from] scanner::ScannerError),
    /// A file could not be read.
    #[error("{path}: {source}")]
    Io {
        /// The file concerned.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// A robot model, scenario or world file is not valid TOML/JSON for its kind
    /// (including unknown fields, which the parser names).
    #[error("{source_name}: {msg}")]
    Syntax {
        /// The file, or a description of an embedded source.
        source_name: String,
        /// The parser's message (with line and column where known).
        msg: String,
    },
    /// A number that must be finite is NaN or infinite.
    #[error("{element}: {field} is not a finite number ({value})")]
    NonFinite {
        /// Which element, e.g. `doors[2]` or `robot model pioneer3at`.
        element: String,
        /// Which field, with its unit.
        field: String,
        /// The value given.
        value: f64,
    },
    /// A size, mass, time or rate outside its sensible range.
    #[error("{element}: {field} = {value} is out of range: {msg}")]
    OutOfRange {
        /// Which element.
        element: String,
        /// Which field, with its unit.
        field: String,
        /// The value given.
        value: f64,
        /// What would be valid.
        msg: String,
    },
    /// A door whose `wall` names no wall of the world.
    #[error("door {door}: its wall (entity {wall}) is not a wall of this world")]
    DoorWithoutWall {
        /// The door's name.
        door: String,
        /// The wall entity id it names.
        wall: u32,
    },
    /// A reference (in a world spec or a scenario) to an entity that does not exist.
    #[error("{element}: unknown entity {reference:?}{hint}")]
    UnknownEntity {
        /// Where the reference was made, e.g. `rules.pass_through_door`.
        element: String,
        /// The name or id given.
        reference: String,
        /// A hint listing candidates (may be empty).
        hint: String,
    },
    /// A reference to an entity of the wrong class (e.g. `reach_top_of_stairs` naming a wall).
    #[error("{element}: entity {reference:?} is a {found}, expected {expected}")]
    WrongEntityClass {
        /// Where the reference was made.
        element: String,
        /// The name or id given.
        reference: String,
        /// The class found.
        found: String,
        /// The class(es) expected.
        expected: String,
    },
    /// Two entities with the same id, or an element that is inconsistent in itself.
    #[error("{element}: {msg}")]
    Invalid {
        /// Which element.
        element: String,
        /// What is wrong.
        msg: String,
    },
    /// An unknown built-in robot model name (and not an existing file).
    #[error("unknown robot model {name:?}: not a built-in ({builtins}) and no such file")]
    UnknownRobotModel {
        /// The name given.
        name: String,
        /// The built-in names.
        builtins: String,
    },
    /// A checkpoint that cannot be written or read back.
    #[error("checkpoint {path}: {msg}")]
    Checkpoint {
        /// The checkpoint file.
        path: PathBuf,
        /// What went wrong.
        msg: String,
    },
}

impl cloud::BadInput for SimError {
    /// A simulation error is the input's (a file, a world, a robot model or a scenario that is
    /// not valid, or a reference to something that does not exist), except where reading or
    /// writing a file failed for the system's reasons.
    fn is_bad_input(&self) -> bool {
        match self {
            SimError::Cloud(e) => e.is_bad_input(),
            SimError::Building(e) => e.is_bad_input(),
            _ => true,
        }
    }
}

/// Result with [`SimError`].
pub type Result<T, E = SimError> = std::result::Result<T, E>;

/// Fails with [`SimError::NonFinite`] unless every value is finite.
pub(crate) fn check_finite(element: &str, field: &str, values: &[f64]) -> Result<()> {
    match values.iter().find(|v| !v.is_finite()) {
        Some(&value) => Err(SimError::NonFinite {
            element: element.to_string(),
            field: field.to_string(),
            value,
        }),
        None => Ok(()),
    }
}

/// Fails unless `lo <= value <= hi` (and finite): [`SimError::NonFinite`] for NaN or an
/// infinity, else [`cloud::check_range`]'s verdict as [`SimError::OutOfRange`] on `element`.
pub(crate) fn check_range(
    element: &str,
    field: &str,
    value: f64,
    lo: f64,
    hi: f64,
    msg: &str,
) -> Result<()> {
    check_finite(element, field, &[value])?;
    cloud::check_range(field.to_string(), value, lo, hi, msg.to_string()).map_err(|e| {
        SimError::OutOfRange {
            element: element.to_string(),
            field: e.name.into_owned(),
            value: e.value,
            msg: e.msg.into_owned(),
        }
    })
}

/// Reads a text file, mapping the error to [`SimError::Io`].
pub(crate) fn read_text(path: &std::path::Path) -> Result<String> {
    std::fs::read_to_string(path).map_err(|source| SimError::Io {
        path: path.to_path_buf(),
        source,
    })
}
