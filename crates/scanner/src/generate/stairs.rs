//! Staircases for the generated styles: human-scale straight flights with a top landing.
//!
//! A flight with a landing half-way (two flights, the second starting on the first's
//! landing) cannot be described yet: every `[[stairs]]` flight rises from the floor (z = 0),
//! so the styles build straight flights with a top landing only.

use crate::building::Staircase;
use cloud::Rng;

/// A straight flight with a top landing, starting at `start` and rising along
/// `direction_deg`, no longer than `max_len` (steps and landing) and leaving 1.2 m of headroom
/// under a ceiling at `height` (`None` if not even 3 steps fit).
/// Rises 0.15-0.19 m and runs 0.25-0.32 m: the range of building codes' comfortable stairs.
pub(super) fn flight(
    r: &mut Rng,
    start: [f64; 2],
    direction_deg: f64,
    max_len: f64,
    height: f64,
    name: &str,
) -> Option<Staircase> {
    let run = r.range(0.25, 0.32);
    let rise = r.range(0.15, 0.19);
    let landing = r.range(0.9, 1.2);
    let width = r.range(0.9, 1.3);
    let by_height = ((height - 1.2) / rise).floor();
    let by_length = ((max_len - landing) / run).floor();
    let most = by_height.min(by_length).min(12.0);
    if most < 3.0 {
        return None;
    }
    let steps = r.int(3.min(most as i64), most as i64) as u32;
    Some(Staircase {
        name: name.into(),
        start_m: start,
        direction_deg,
        steps: steps.max(3),
        rise_m: rise,
        run_m: run,
        width_m: width,
        landing_m: landing,
    })
}
