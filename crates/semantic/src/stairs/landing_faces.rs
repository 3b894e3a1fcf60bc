//! A landing's side face read as a flight of its own (see the `stairs` module).
//!
//! A mid landing stands on a solid base; seen from the floor beside it, in horizontal scan
//! lines sparse enough, its side face is returns at a few heights all along it, and a fit of
//! small steps under its top finds them on every "step" (the returns over a step are taken for
//! something standing over the flight, and each step has side face under it). Where the blobs
//! part the face under the lower flight from the face under its landing, the lower flight is
//! found in its part, and the landing's face is read as a flight from the floor in the next
//! part, with the upper flight on its "landing" (office-151 of seeds 151-155: 4 steps to 0.66
//! m, then "3 steps of 0.225 m" from the floor to 0.67 m over the landing's first 0.7 m, then
//! the upper flight on it).
//!
//! A flight from the floor cannot stand where another flight's landing stands: one climbing the
//! same way, in line with it, from beyond its top step to its top level, over no more than a
//! landing's depth, is that landing's side face. It is dropped, and the flight on it, if any,
//! starts on the other flight's landing.

use super::{DetectedStairs, StairsConfig};

/// The deepest landing looked over beyond a flight's top step, in the flight's widths: a
/// landing is at least as deep as the stair is wide, and rarely more than half again as deep.
const LANDING_WIDTHS: f64 = 1.5;

/// A face's top this near the flight's top level (in the flight's rises) is level with it.
const SAME_TOP_RISES: f64 = 0.5;

/// Drops each flight from the floor in `found` (by part) that is the side face of another
/// part's flight's landing (see the module docs); the flight on it starts on that landing.
pub(super) fn drop_landing_faces(found: &mut [Option<Vec<DetectedStairs>>], c: &StairsConfig) {
    for j in 0..found.len() {
        let Some(face) = found[j].as_ref().and_then(|v| v.first()).cloned() else {
            continue;
        };
        let under = (0..found.len()).filter(|&i| i != j).find_map(|i| {
            found[i]
                .as_ref()?
                .iter()
                .find(|f| is_landing_face(&face, f, c))
                .cloned()
        });
        let Some(lower) = under else {
            continue;
        };
        let Some(flights) = found[j].as_mut() else {
            continue;
        };
        flights.remove(0);
        let top = lower.rise * f64::from(lower.steps);
        for upper in flights.iter_mut() {
            upper.base = top;
            upper.rules.push(format!(
                "starts on the landing of the flight below, {top:.2} m above the floor (the landing's side face under it read as a flight of its own, dropped)"
            ));
        }
        if flights.is_empty() {
            found[j] = None;
        }
    }
}

/// True if `face` (a flight from the floor) stands where the landing of `lower` (another
/// flight from the floor) does: it climbs the same way, in line with it, starts beyond its
/// top step (by half a run at most before its end), ends within [`LANDING_WIDTHS`] of its width
/// beyond it, and climbs to its top level (within [`SAME_TOP_RISES`] of its rise).
fn is_landing_face(face: &DetectedStairs, lower: &DetectedStairs, c: &StairsConfig) -> bool {
    if face.base != 0.0 || lower.base != 0.0 {
        return false;
    }
    let dir = lower.dir;
    let same_way = face.dir.dot(dir) >= c.snap_direction_deg.to_radians().cos();
    let in_line = dir.perp_dot(face.start - lower.start).abs() <= lower.width / 2.0;
    let top_end = lower.start.dot(dir) + lower.run * f64::from(lower.steps);
    let (from, to) = (
        face.start.dot(dir),
        face.start.dot(dir) + face.run * f64::from(face.steps),
    );
    let on_landing =
        from >= top_end - lower.run / 2.0 && to <= top_end + LANDING_WIDTHS * lower.width;
    let lower_top = lower.rise * f64::from(lower.steps);
    let same_top =
        (face.rise * f64::from(face.steps) - lower_top).abs() <= SAME_TOP_RISES * lower.rise;
    same_way && in_line && on_landing && same_top
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    /// Regression (office-151 of seeds 151-155): 4 steps of 0.166 m to a landing 1.2 m deep;
    /// the landing's side face, in the next part, read as 3 steps of 0.225 m from the floor
    /// 0.17 m past the top step, with the upper flight on it. The face is dropped, and the
    /// upper flight starts on the lower flight's landing.
    #[test]
    fn a_landings_side_face_read_as_a_flight_is_dropped() {
        let c = StairsConfig::default();
        let lower = DetectedStairs::straight(0.0, 4, 0.166, 0.266);
        let face = DetectedStairs::straight(1.23, 3, 0.225, 0.222);
        let mut upper = DetectedStairs::straight(2.26, 3, 0.197, 0.231);
        upper.base = 0.675;
        let mut found = vec![Some(vec![lower.clone()]), Some(vec![face, upper])];
        drop_landing_faces(&mut found, &c);
        assert_eq!(found[0].as_ref().map(Vec::len), Some(1));
        let rest = found[1].as_ref().expect("the upper flight");
        assert_eq!(rest.len(), 1);
        assert_eq!(rest[0].steps, 3);
        assert!((rest[0].base - 4.0 * 0.166).abs() < 1e-9);
        // A face alone on the landing goes too.
        let mut found = vec![
            Some(vec![lower]),
            Some(vec![DetectedStairs::straight(1.23, 3, 0.225, 0.222)]),
        ];
        drop_landing_faces(&mut found, &c);
        assert!(found[1].is_none());
    }

    /// Flights that do not stand on the landing stay: one beyond it, one to another height,
    /// one beside the line, one climbing the other way.
    #[test]
    fn flights_off_the_landing_or_to_another_top_stay() {
        let c = StairsConfig::default();
        let lower = DetectedStairs::straight(0.0, 4, 0.166, 0.266);
        let beyond = DetectedStairs::straight(3.0, 3, 0.225, 0.222);
        let higher = DetectedStairs::straight(1.23, 5, 0.18, 0.27);
        let mut beside = DetectedStairs::straight(1.23, 3, 0.225, 0.222);
        beside.start.y = 1.2;
        let mut back = DetectedStairs::straight(1.9, 3, 0.225, 0.222);
        back.dir = -DVec2::X;
        for other in [beyond, higher, beside, back] {
            let mut found = vec![Some(vec![lower.clone()]), Some(vec![other])];
            drop_landing_faces(&mut found, &c);
            assert!(found[1].is_some());
        }
    }
}
