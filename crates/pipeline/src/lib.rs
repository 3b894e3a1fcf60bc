//! semsim's chain as a library (placeholder).
#![warn(missing_docs)]
