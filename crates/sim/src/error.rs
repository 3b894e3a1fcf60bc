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
    /// The semantic map could not be loaded.
    #[cfg(feature = "semantic")]
    #[error(transparent)]
    SemanticMap(#[from] semantic::SemanticError),
    /// A file could not be read.
    #[error("{path}: {error}")]
    Io {
        /// The file concerned.
        path: PathBuf,
        /// The underlying error (in the message, not chained, so the OS text appears once).
        error: std::io::Error,
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
    #[error("{element}: {field} = {} is out of range: {msg}", fmt_num(*value))]
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
    #[error(
        "{}door {door}: its wall (entity {wall}) is not a wall of this world",
        prefix(source_name)
    )]
    DoorWithoutWall {
        /// The file (or built-in input) the world came from; empty when unknown.
        source_name: String,
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
    /// A world with more elements of a kind than a simulation can hold (refused up front,
    /// before any memory is spent on them).
    #[error("{element}: {count} {what} is more than the {limit} a simulation can hold")]
    TooMany {
        /// The input, e.g. `world` or `stairs stairs_3`.
        element: String,
        /// What was counted, e.g. `static boxes (fixed boxes, stair steps and landings)`.
        what: String,
        /// How many there are.
        count: usize,
        /// The most accepted.
        limit: usize,
    },
    /// A URDF robot description that is not well-formed XML, not valid URDF, or describes a
    /// robot semsim cannot model (a prismatic joint, a wheel without a cylinder, no wheels...).
    #[error("{}: {msg}", path.display())]
    Urdf {
        /// The URDF file.
        path: PathBuf,
        /// What is wrong, with the line and the element where known.
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
            #[cfg(feature = "semantic")]
            SimError::SemanticMap(e) => e.is_bad_input(),
            _ => true,
        }
    }
}

impl SimError {
    /// The same error naming the file (or built-in input) it is about, e.g. a scenario's path:
    /// the element of [`NonFinite`](SimError::NonFinite), [`OutOfRange`](SimError::OutOfRange),
    /// [`UnknownEntity`](SimError::UnknownEntity), [`WrongEntityClass`](SimError::WrongEntityClass),
    /// [`Invalid`](SimError::Invalid) and [`TooMany`](SimError::TooMany) becomes
    /// `<source>: <element>`, and a [`DoorWithoutWall`](SimError::DoorWithoutWall) names it.
    /// Errors that name their file already (syntax, I/O, ...) are returned as they are, as are
    /// all errors when `source` is empty.
    pub fn in_source(self, source: &str) -> SimError {
        if source.is_empty() {
            return self;
        }
        let pre = |element: String| {
            if element.starts_with(&format!("{source}: ")) {
                element
            } else {
                format!("{source}: {element}")
            }
        };
        match self {
            SimError::NonFinite {
                element,
                field,
                value,
            } => SimError::NonFinite {
                element: pre(element),
                field,
                value,
            },
            SimError::OutOfRange {
                element,
                field,
                value,
                msg,
            } => SimError::OutOfRange {
                element: pre(element),
                field,
                value,
                msg,
            },
            SimError::UnknownEntity {
                element,
                reference,
                hint,
            } => SimError::UnknownEntity {
                element: pre(element),
                reference,
                hint,
            },
            SimError::WrongEntityClass {
                element,
                reference,
                found,
                expected,
            } => SimError::WrongEntityClass {
                element: pre(element),
                reference,
                found,
                expected,
            },
            SimError::Invalid { element, msg } => SimError::Invalid {
                element: pre(element),
                msg,
            },
            SimError::TooMany {
                element,
                what,
                count,
                limit,
            } => SimError::TooMany {
                element: pre(element),
                what,
                count,
                limit,
            },
            SimError::DoorWithoutWall {
                source_name,
                door,
                wall,
            } if source_name.is_empty() => SimError::DoorWithoutWall {
                source_name: source.to_string(),
                door,
                wall,
            },
            e => e,
        }
    }
}

/// A number for people: plain (`2000000`, `0.5`), or in exponent form when very large or
/// small (`1e300`, `1e-9`).
pub(crate) fn fmt_num(v: f64) -> String {
    if v != 0.0 && v.is_finite() && !(1e-4..1e7).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// `"<s>: "`, or nothing for an empty `s`.
fn prefix(s: &str) -> String {
    if s.is_empty() {
        String::new()
    } else {
        format!("{s}: ")
    }
}

/// Result with [`SimError`].
pub type Result<T, E = SimError> = std::result::Result<T, E>;

/// Fails with [`SimError::NonFinite`] unless every value is finite. `field` names the values:
/// one name per value (`"x_m, y_m"`: the one at fault is named), or one name for them all
/// (`"center_m"`: the one at fault is named `center_m[i]`).
pub(crate) fn check_finite(element: &str, field: &str, values: &[f64]) -> Result<()> {
    let Some((i, &value)) = values.iter().enumerate().find(|(_, v)| !v.is_finite()) else {
        return Ok(());
    };
    let names: Vec<&str> = field.split(", ").collect();
    let field = if names.len() == values.len() {
        names[i].to_string()
    } else if values.len() > 1 {
        format!("{field}[{i}]")
    } else {
        field.to_string()
    };
    Err(SimError::NonFinite {
        element: element.to_string(),
        field,
        value,
    })
}

/// Fails unless `lo <= value <= hi` (and finite): [`SimError::NonFinite`] for NaN or an
/// infinity, else [`SimError::OutOfRange`] on `element` saying which bound it passes
/// (`less than <lo>` or `more than <hi>`) and then `msg`, what would be valid.
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
        let bound = if value < lo {
            format!("less than {}", fmt_num(lo))
        } else {
            format!("more than {}", fmt_num(hi))
        };
        SimError::OutOfRange {
            element: element.to_string(),
            field: e.name.into_owned(),
            value: e.value,
            msg: format!("{bound}; expected {}", e.msg),
        }
    })
}

/// Reads a text file, mapping the error to [`SimError::Io`].
pub(crate) fn read_text(path: &std::path::Path) -> Result<String> {
    std::fs::read_to_string(path).map_err(|error| SimError::Io {
        path: path.to_path_buf(),
        error,
    })
}
