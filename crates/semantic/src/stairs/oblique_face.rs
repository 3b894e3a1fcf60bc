//! A side face read across its own line. A staircase seen from its side only shows one face,
//! a line in plan, and climbs along it. Read along a direction oblique to it, the stepped top
//! edge of any face (a ramp's slab edge among them) spaces its rises along the direction as
//! steps, and the face's oblique extent across the direction reads as the flight's width:
//! garage-255 of seeds 251-255, a ramp's side face read along the ramp's part's own axis 22
//! degrees off it as a 4-step flight 0.70 m wide, which `climbs_on`, reading only flights
//! seen from their side, never looked at.

use crate::points::fit_line;
use glam::DVec2;

/// A side face's returns lie this near its line in plan (the range noise and the registration's
/// error, a few centimetres; mixed pixels at its edges further).
const FACE_HALF_WIDTH_M: f64 = 0.1;

/// The share of a flight's returns on its steps within [`FACE_HALF_WIDTH_M`] of one line that
/// makes them one face (a flight's treads and risers spread across its width: a riser holds
/// a share of them, and a tread's run across the line less).
const FACE_SHARE: f64 = 0.9;

/// The angle in degrees (0 to 90) between `dir` and the line in plan that the returns `xy` lie
/// on, where they lie on one (see [`FACE_SHARE`]); `None` where they spread across it, or
/// there are fewer than two.
pub(super) fn one_face_off_deg(xy: &[DVec2], dir: DVec2) -> Option<f64> {
    let (centre, line) = fit_line(xy)?;
    let near = xy
        .iter()
        .filter(|q| line.perp_dot(**q - centre).abs() <= FACE_HALF_WIDTH_M)
        .count();
    if (near as f64) < FACE_SHARE * xy.len() as f64 {
        return None;
    }
    let deg = line.angle_to(dir).abs().to_degrees();
    Some(deg.min(180.0 - deg))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(deg: f64) -> DVec2 {
        DVec2::from_angle(deg.to_radians())
    }

    #[test]
    fn a_face_with_a_few_strays_is_one_line_at_its_angle() {
        // A face along +Y, 2 m, returns every 2 cm with 3 cm of noise, and 4 strays of 100
        // up to 0.6 m off it.
        let mut xy: Vec<DVec2> = (0..96)
            .map(|i| DVec2::new(0.03 * ((i % 3) as f64 - 1.0), 0.02 * i as f64))
            .collect();
        xy.extend([0.2, 0.25, 0.3, 0.6].map(|x| DVec2::new(x, 1.0)));
        let off = one_face_off_deg(&xy, at(68.0)).expect("one face");
        assert!((off - 22.0).abs() < 2.0, "{off}");
        let off = one_face_off_deg(&xy, at(-90.0)).expect("one face");
        assert!(off < 2.0, "{off}");
    }

    #[test]
    fn a_flights_treads_and_risers_are_no_one_line() {
        // 3 steps climbing +X of 0.2 m run, 1 m wide: whichever line fits them, most lie off it.
        let xy: Vec<DVec2> = (0..30)
            .flat_map(|i| (0..50).map(move |j| DVec2::new(0.02 * i as f64, 0.02 * j as f64)))
            .collect();
        assert_eq!(one_face_off_deg(&xy, DVec2::X), None);
        assert_eq!(one_face_off_deg(&xy[..1], DVec2::X), None);
    }
}
