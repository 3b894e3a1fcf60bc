//! Scores semantic maps against the ground truth of the building they were scanned in
//! (placeholder: the evaluation moves here from `semantic`).
#![warn(missing_docs)]
