//! The semantic crate's typed errors.

use std::path::PathBuf;

/// Everything that can go wrong while building, loading or saving a semantic map.
#[derive(Debug, thiserror::Error)]
pub enum SemanticError {
    /// The input cloud holds no finite point.
    #[error("the cloud holds no finite point ({total} points given)")]
    EmptyCloud {
        /// Number of points in the input, missing returns included.
        total: usize,
    },
    /// A configuration value outside its sensible range (its name with its stage, e.g.
    /// `projection.resolution_m`).
    #[error(transparent)]
    InvalidParameter(#[from] cloud::InvalidParameter),
    /// The projection image would exceed the pixel cap (a cloud far too wide for the resolution).
    #[error(
        "the projection image would be {width_px} x {height_px} px ({width_m:.1} m x {height_m:.1} m \
         at {resolution_m} m/px), over the cap of {max_pixels} px: crop the cloud or raise \
         projection.resolution_m / projection.max_pixels"
    )]
    ImageTooLarge {
        /// Image width the cloud would need.
        width_px: u64,
        /// Image height the cloud would need.
        height_px: u64,
        /// Extent of the cloud along x (robust, outliers excluded).
        width_m: f64,
        /// Extent of the cloud along y (robust, outliers excluded).
        height_m: f64,
        /// The configured resolution.
        resolution_m: f64,
        /// The configured cap.
        max_pixels: u64,
    },
    /// Reading or writing a file failed.
    #[error(transparent)]
    Cloud(#[from] cloud::CloudError),
    /// An image could not be encoded.
    #[error("{path}: cannot encode the image: {msg}")]
    Image {
        /// The image file.
        path: PathBuf,
        /// The encoder's message.
        msg: String,
    },
    /// A map file is not valid JSON, or not the expected structure.
    #[error("{path}: {msg}")]
    Syntax {
        /// The map file.
        path: PathBuf,
        /// The parser's message (with line and column where known).
        msg: String,
    },
    /// The file's `format` is not a semantic map.
    #[error("{path}: format {found:?} is not a semantic map (expected {expected:?})")]
    WrongFormat {
        /// The map file.
        path: PathBuf,
        /// The `format` found.
        found: String,
        /// The `format` expected.
        expected: &'static str,
    },
    /// The file's `version` is not one this build reads.
    #[error("{path}: semantic map version {found} is not supported (this build reads version {supported})")]
    UnsupportedVersion {
        /// The map file.
        path: PathBuf,
        /// The version found.
        found: u64,
        /// The version this build reads and writes.
        supported: u32,
    },
    /// An entity with a class this build does not know.
    #[error("{path}: entities[{index}]: unknown class {class:?} (known: {known})")]
    UnknownClass {
        /// The map file.
        path: PathBuf,
        /// Position of the entity in `entities`.
        index: usize,
        /// The class found.
        class: String,
        /// The known class names.
        known: String,
    },
    /// A relation with a type this build does not know.
    #[error("{path}: relations[{index}]: unknown relation type {kind:?} (known: {known})")]
    UnknownRelation {
        /// The map file.
        path: PathBuf,
        /// Position of the relation in `relations`.
        index: usize,
        /// The type found.
        kind: String,
        /// The known relation types.
        known: String,
    },
    /// A relation names an entity id that no entity has.
    #[error("{path}: relations[{index}] ({kind}): entity id {id} does not exist")]
    DanglingId {
        /// The map file.
        path: PathBuf,
        /// Position of the relation in `relations`.
        index: usize,
        /// The relation's type.
        kind: String,
        /// The missing id.
        id: u32,
    },
    /// Two entities share an id (or an id is 0).
    #[error("{path}: entities[{index}]: id {id} is {problem}")]
    BadId {
        /// The map file.
        path: PathBuf,
        /// Position of the entity in `entities`.
        index: usize,
        /// The id.
        id: u32,
        /// `"0 (ids start at 1)"` or `"used twice"`.
        problem: &'static str,
    },
    /// An entity whose geometry is inconsistent with its class.
    #[error("{path}: entity {id} ({class}): {msg}")]
    InvalidEntity {
        /// The map file.
        path: PathBuf,
        /// The entity's id.
        id: u32,
        /// The entity's class name.
        class: &'static str,
        /// What is wrong.
        msg: String,
    },
}

/// Result with [`SemanticError`].
pub type Result<T, E = SemanticError> = std::result::Result<T, E>;

impl cloud::BadInput for SemanticError {
    /// The user's input is at fault, except where reading or writing a file failed for the
    /// system's reasons, or a picture could not be written (a failure of the job).
    fn is_bad_input(&self) -> bool {
        match self {
            SemanticError::Cloud(c) => c.is_bad_input(),
            SemanticError::Image { .. } => false,
            _ => true,
        }
    }
}
