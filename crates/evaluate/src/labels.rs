//! Point-level agreement of predicted labels with the ground truth.

use crate::score::ClassScore;
use cloud::{EntityClass, Label};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// Point-level agreement of predicted labels with the ground truth, by surface class.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct LabelEvaluation {
    /// Points compared (finite, both labels present).
    pub points: usize,
    /// Fraction of them whose class agrees.
    pub accuracy: f64,
    /// Per class (by name): expected = true points of the class, detected = predicted, matched = both.
    pub classes: Vec<(String, ClassScore)>,
}

/// Compares predicted per-point classes with the truth (same order, e.g. `MapOutput::labels`
/// and the input cloud's ground-truth labels). Furniture counts as unknown.
pub fn evaluate_labels(predicted: &[Label], truth: &[Label]) -> LabelEvaluation {
    let norm = |c: EntityClass| {
        if c == EntityClass::Furniture {
            EntityClass::Unknown
        } else {
            c
        }
    };
    let mut tally: HashMap<EntityClass, (usize, usize, usize)> = HashMap::new();
    let mut agree = 0;
    let n = predicted.len().min(truth.len());
    for (p, t) in predicted.iter().zip(truth) {
        let (p, t) = (norm(p.class), norm(t.class));
        tally.entry(t).or_default().0 += 1;
        tally.entry(p).or_default().1 += 1;
        if p == t {
            tally.entry(t).or_default().2 += 1;
            agree += 1;
        }
    }
    let mut classes: Vec<(String, ClassScore)> = EntityClass::ALL
        .iter()
        .filter_map(|c| {
            tally
                .get(c)
                .map(|&(e, d, m)| (c.name().to_string(), ClassScore::new(e, d, m)))
        })
        .collect();
    classes.sort_by(|a, b| a.0.cmp(&b.0));
    LabelEvaluation {
        points: n,
        accuracy: if n == 0 { 1.0 } else { agree as f64 / n as f64 },
        classes,
    }
}
