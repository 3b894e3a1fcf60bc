//! Wall support: is a candidate a wall, or a beam, a row of pillars, a beam over pillars?
//!
//! A wall stands on the floor: where nothing hides it, its face is seen from near the floor
//! up, and nothing is seen through it. A beam (or a duct, a sign) is seen above head height
//! only and the floor is seen under it; a row of pillars (or a beam over them) shows a face
//! below head height at the pillars only, and the floor in between. So, per 10 cm of the
//! candidate's length:
//!
//! - *standing*: face points below head height (`HEAD_HEIGHT_M` above the floor);
//! - *open*: points at standing heights (the floor included) where the wall's body would be:
//!   between its two faces, or (one face seen) on both sides of the face right next to it.
//!   A wall hides what is behind its face; under a beam or between pillars the floor and what
//!   stands there are seen;
//! - neither: the face seen above head height only with nothing seen below (clutter, parked
//!   cars in front of it hid it), or nothing at all (not seen).
//!
//! A candidate is dropped if more of its length is open than standing (a door is open too, but
//! a wall holds fewer and narrower doors than wall), or if no bin stands (it rests on no points
//! of its own). Occlusion by clutter makes bins neither standing nor open, so a wall behind a
//! row of parked cars stays a wall as long as its face is seen somewhere below head height
//! (above the cars, at its ends).

/// Bins along the wall.
pub(crate) const BIN_M: f64 = 0.1;
/// Points up to this height above the floor are what people and robots run into; a beam's
/// underside is above it. 1.95 m: above the stature of 99 % of adults (~1.90 m), under the
/// 2.0 m minimum headroom and door heights of building codes.
pub(crate) const HEAD_HEIGHT_M: f64 = 1.95;
/// The band beside a face where the wall's body would be: from 6 cm (beyond the face's own
/// noise: the faces' tolerance is 3 cm, a laser's range noise 1-2 cm) to 15 cm.
const BODY_BAND_M: (f64, f64) = (0.06, 0.15);

/// Per bin: bit 0 standing, bit 1 seen left of the face, bit 2 right of it, bit 3 between two
/// faces.
pub(crate) struct SupportProfile {
    bins: Vec<u8>,
    faces: (f64, f64),
    two: bool,
    floor: f64,
}

impl SupportProfile {
    /// An empty profile of `n` bins for a candidate with these face offsets (one or two).
    pub fn new(n: usize, faces: &[f64], floor: f64) -> SupportProfile {
        let lo = faces.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = faces.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        SupportProfile {
            bins: vec![0; n.max(1)],
            faces: (lo, hi),
            two: faces.len() >= 2,
            floor,
        }
    }

    /// Adds a point in bin `k`, `d` off the line, at height `z`; `face`: it is a face point.
    pub fn add(&mut self, k: usize, d: f64, z: f64, face: bool) {
        let Some(bin) = self.bins.get_mut(k) else {
            return;
        };
        let above_floor = z - self.floor;
        if above_floor > HEAD_HEIGHT_M {
            return;
        }
        if face {
            if above_floor > 0.05 {
                *bin |= 1;
            }
            return;
        }
        if above_floor < -0.05 {
            return;
        }
        let (lo, hi) = self.faces;
        let (b0, b1) = BODY_BAND_M;
        if self.two {
            if d > lo + b0 && d < hi - b0 {
                *bin |= 8;
            }
        } else if d - hi >= b0 && d - hi <= b1 {
            *bin |= 2;
        } else if lo - d >= b0 && lo - d <= b1 {
            *bin |= 4;
        }
    }

    /// (standing, open) fractions of the length.
    pub fn fractions(&self) -> (f64, f64) {
        let n = self.bins.len() as f64;
        let standing = self.bins.iter().filter(|&&b| b & 1 != 0).count() as f64;
        let open = self
            .bins
            .iter()
            .filter(|&&b| b & 1 == 0 && (b & 8 != 0 || b & 6 == 6))
            .count() as f64;
        (standing / n, open / n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_beam_over_pillars_is_open_between_them_and_a_wall_is_not() {
        // Two faces 0.4 m apart (offsets -0.2 and 0.2), 100 bins; pillars at bins 10, 50, 90.
        let mut beam = SupportProfile::new(100, &[-0.2, 0.2], 0.0);
        let mut wall = SupportProfile::new(100, &[-0.2, 0.2], 0.0);
        for k in 0..100 {
            let pillar = k % 40 == 10;
            beam.add(k, 0.2, 2.7, true);
            wall.add(k, 0.2, 2.7, true);
            beam.add(k, 0.2, 1.0, pillar);
            wall.add(k, -0.2, 1.0, true);
            if !pillar {
                beam.add(k, 0.0, 0.0, false); // the floor under the beam
            }
            wall.add(k, 0.3, 0.0, false); // the floor in front of the wall
        }
        let (s, o) = beam.fractions();
        assert!(s < 0.05 && o > 0.9, "{s} {o}");
        assert_eq!(wall.fractions(), (1.0, 0.0));
    }
}
