//! Precision, recall and F1 of one class.

use serde::{Deserialize, Serialize};

/// Precision, recall and F1 of one class.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct ClassScore {
    /// Expected (ground truth) instances.
    pub expected: usize,
    /// Detected instances.
    pub detected: usize,
    /// Matched pairs.
    pub matched: usize,
    /// matched / detected (1 when nothing was detected and nothing expected).
    pub precision: f64,
    /// matched / expected (1 when nothing was expected).
    pub recall: f64,
    /// Harmonic mean of precision and recall.
    pub f1: f64,
}

impl ClassScore {
    pub(crate) fn new(expected: usize, detected: usize, matched: usize) -> ClassScore {
        let ratio = |a: usize, b: usize| {
            if b == 0 {
                if expected == 0 && detected == 0 {
                    1.0
                } else {
                    0.0
                }
            } else {
                a as f64 / b as f64
            }
        };
        let (precision, recall) = (ratio(matched, detected), ratio(matched, expected));
        let f1 = if precision + recall > 0.0 {
            2.0 * precision * recall / (precision + recall)
        } else {
            0.0
        };
        ClassScore {
            expected,
            detected,
            matched,
            precision,
            recall,
            f1,
        }
    }
}
