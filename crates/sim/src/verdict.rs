//! The verdict on a run: each rule of its scenario passed or failed, with a one-line reason
//! and the time it was decided (the judge, `judge`, writes it).

use serde::{Deserialize, Serialize};

/// One rule's outcome.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RuleResult {
    /// The rule as written, e.g. `pass_through_door = walls[4].doors[2]`.
    pub rule: String,
    /// Whether it passed.
    pub passed: bool,
    /// Why, in one line.
    pub reason: String,
    /// When it was decided (s).
    pub decided_s: f64,
    /// The run was interrupted before the rule was decided (then `passed` is false, `reason`
    /// says so and what was seen so far, and `decided_s` is when the run was interrupted).
    #[serde(default, skip_serializing_if = "is_false")]
    pub undecided: bool,
}

fn is_false(b: &bool) -> bool {
    !*b
}

/// The verdict on a run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Verdict {
    /// Every rule passed.
    pub passed: bool,
    /// Each rule, in the order of [`Rules`](crate::Rules)' fields.
    pub rules: Vec<RuleResult>,
    /// When the run ended (s).
    pub end_time_s: f64,
    /// When the run was interrupted (s), if it was stopped before its end (see
    /// [`crate::run_scenario_with`]); then `passed` is false and the rules not yet decided
    /// say so.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub interrupted_at_s: Option<f64>,
}
