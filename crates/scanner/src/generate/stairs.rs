//! Staircases for the generated styles: human-scale straight flights with a top landing, and
//! straight staircases of two flights with a landing half-way (the second flight a
//! `[[stairs]]` of its own, starting on the first's landing at `base_m`).

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
        base_m: 0.0,
    })
}

/// A straight staircase of two flights with a landing between them, starting at `start` and
/// rising along `direction_deg`, no longer than `max_len` (flights and landings) and leaving
/// 1.2 m of headroom under a ceiling at `height` (`None` if not 3 steps fit in each flight).
/// The mid landing is as deep as the flights are wide at least (building codes ask a landing
/// at least the stair's width); rises and runs as in [`flight`].
pub(super) fn two_flights(
    r: &mut Rng,
    start: [f64; 2],
    direction_deg: f64,
    max_len: f64,
    height: f64,
    name: &str,
) -> Option<[Staircase; 2]> {
    let run = r.range(0.25, 0.32);
    let rise = r.range(0.15, 0.19);
    let width = r.range(0.9, 1.3);
    let mid = r.range(width.max(1.0), 1.3);
    let top = r.range(0.9, 1.2);
    let by_height = ((height - 1.2) / rise).floor();
    let by_length = ((max_len - mid - top) / run).floor();
    let most = by_height.min(by_length).min(16.0);
    if most < 6.0 {
        return None;
    }
    let total = r.int(6, most as i64) as u32;
    let first = total / 2;
    let yaw = direction_deg.to_radians();
    let along = first as f64 * run + mid;
    let flight = |n: &str, start_m: [f64; 2], steps: u32, landing_m: f64, base_m: f64| Staircase {
        name: format!("{name} {n}"),
        start_m,
        direction_deg,
        steps,
        rise_m: rise,
        run_m: run,
        width_m: width,
        landing_m,
        base_m,
    };
    Some([
        flight("flight 1", start, first, mid, 0.0),
        flight(
            "flight 2",
            [start[0] + yaw.cos() * along, start[1] + yaw.sin() * along],
            total - first,
            top,
            first as f64 * rise,
        ),
    ])
}
