//! Semantic maps (work in progress).
