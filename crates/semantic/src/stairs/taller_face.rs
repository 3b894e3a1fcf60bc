//! A flight seen from its side only ends at its stepped top edge: over the treads is the open
//! air people climb in, so the side face's plane holds nothing more than a rise over a step's
//! edge, but for a person crossing it at one step (a spike over the profile, see `envelope`).
//! The face of something taller whose upper part the laser lost shows its surviving returns
//! there, step after step: office-355 of seeds 351-355, a dark cabinet (1.95 m tall) against a
//! wall, its front seen from 2-4 m away, most of its upper returns dropped (a dark surface at a
//! grazing angle), the highest surviving one per column stepping up from 0.2 to 0.8 m along
//! 0.9 m of it, read as a 4-step flight seen from its side; returns 0.8-1.8 m up stood over
//! three of its four "steps".
//!
//! (A handrail or balustrade on a flight's open side stands over every step too; but it tops
//! the part's profile there, which then climbs as a slope, and no side face is read at all.)

use super::profile::Profile;
use glam::DVec2;

/// Returns this near the face's line (across it) are on its plane: the range noise and the
/// registration's error, a few centimetres.
const HALF_WIDTH_M: f64 = 0.05;

/// Over a step's top edge, returns this much more than a rise up are over its tread's air (the
/// measurement's few centimetres over the next level).
const MARGIN_M: f64 = 0.05;

/// Steps with that many returns over them that make the face one of something taller: more
/// than the one a person crossing it stands at.
const TALLER_STEPS: usize = 2;

/// True if the side face at `face_m` across the flight `p` (`dir.perp_dot`) goes on up over
/// its steps: at least [`TALLER_STEPS`] of them hold `min_points` of `pts` (`(xy, height over
/// the foot)`) on its plane more than a rise over their top edge (see the module docs).
pub(super) fn face_goes_on_above(
    pts: &[(DVec2, f64)],
    p: &Profile,
    face_m: f64,
    min_points: usize,
) -> bool {
    let mut over = vec![0usize; p.steps as usize];
    for (q, z) in pts {
        if (p.dir.perp_dot(*q) - face_m).abs() > HALF_WIDTH_M {
            continue;
        }
        if let Some(k) = p.step_of(q.dot(p.dir)) {
            over[k] += usize::from(*z > (k as f64 + 2.0) * p.rise + MARGIN_M);
        }
    }
    over.iter().filter(|&&n| n >= min_points).count() >= TALLER_STEPS
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 4 steps of 0.2 m x 0.25 m climbing +X from 0, their side face at y = 0 sampled every
    /// 2 cm along and up to each step's top, with `over` returns added.
    fn face_with(over: &[(DVec2, f64)]) -> (Vec<(DVec2, f64)>, Profile) {
        let p = Profile {
            dir: DVec2::X,
            rise: 0.2,
            run: 0.25,
            front1: 0.0,
            steps: 4,
            found: 4,
            score: 4.0,
            fit_score: 0.0,
        };
        let mut pts = over.to_vec();
        for i in 0..50 {
            let x = 0.01 + 0.02 * f64::from(i);
            let top = 0.2 * ((x / 0.25).floor() + 1.0);
            let mut z = 0.02;
            while z <= top {
                pts.push((DVec2::new(x, 0.0), z));
                z += 0.02;
            }
        }
        (pts, p)
    }

    #[test]
    fn a_side_face_alone_and_one_crossed_by_a_person_end_at_their_edge() {
        let (pts, p) = face_with(&[]);
        assert!(!face_goes_on_above(&pts, &p, 0.0, 5));
        // A person crossing it over the second step: a column of returns 0.4-1.7 m up.
        let person: Vec<(DVec2, f64)> = (0..14)
            .map(|i| (DVec2::new(0.36, 0.02), 0.4 + 0.1 * f64::from(i)))
            .collect();
        let (pts, p) = face_with(&person);
        assert!(!face_goes_on_above(&pts, &p, 0.0, 5));
    }

    #[test]
    fn a_face_going_on_up_over_its_steps_is_something_taller() {
        // What survived of a dark cabinet's upper front: 6 returns 0.9-1.8 m up over each of
        // the first three steps, on the face's plane.
        let upper: Vec<(DVec2, f64)> = (0..3)
            .flat_map(|k| {
                (0..6).map(move |i| {
                    let x = 0.25 * f64::from(k) + 0.03 + 0.035 * f64::from(i);
                    (DVec2::new(x, -0.01), 0.9 + 0.15 * f64::from(i))
                })
            })
            .collect();
        let (pts, p) = face_with(&upper);
        assert!(face_goes_on_above(&pts, &p, 0.0, 5));
        // The same 0.3 m in front of the face (a chair's back, a person): not on its plane.
        let in_front: Vec<(DVec2, f64)> = upper
            .iter()
            .map(|&(q, z)| (q - DVec2::Y * 0.3, z))
            .collect();
        let (pts, p) = face_with(&in_front);
        assert!(!face_goes_on_above(&pts, &p, 0.0, 5));
    }
}
