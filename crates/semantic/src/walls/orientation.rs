//! Face orientation: does the surface a candidate's face points lie on run along it?
//!
//! A wall's face is a plane along the candidate: its points, seen from above, form a thin
//! strip parallel to the line. The projection image also yields lines cut through the corner of
//! a pillar or a cabinet, across the end of a car or along a diagonal of clutter; their "face"
//! band holds points of surfaces that cross the line at an angle (the two sides of a corner, at
//! about 45 degrees), enough of them at every height to pass the other tests. So, below head
//! height, per stretch of [`BIN_M`] along the candidate, the points near the face (within
//! [`BAND_M`]) are reduced to their principal direction in the horizontal plane; a stretch whose
//! direction is within [`MAX_ANGLE_DEG`] of the line runs along it. A candidate on which fewer
//! than [`MIN_ALONG`] of the stretches with points run along it is no wall.
//!
//! A wall seen from one side keeps one of its faces; that face must run along it too. There, a
//! surface square to the line also tells, though it crosses the band within a few centimetres
//! along (too few to read a direction from): a stretch whose points cover the whole of
//! [`CROSS_M`] either side of the face holds a surface crossing it (a wall hides what is
//! behind its face). The projection draws a line through a row of pillars seen from both sides
//! between their two rows of faces, on the pillars' sides, and such a face is made of them.

/// Stretches along the candidate: twice the support bins (a corner's side must show its slope
/// across the 6 cm band, i.e. over at least 6 cm along).
const BIN_M: f64 = 0.2;
/// Points this far either side of a face: twice the faces' tolerance (3 cm), so that a crossing
/// surface's slope shows and a wall's face noise (1-2 cm) stays inside.
const BAND_M: f64 = 0.06;
/// Fewest points in a stretch to give a direction ...
const MIN_POINTS: usize = 5;
/// ... spread along it over at least this (half the stretch).
const MIN_SPREAD_M: f64 = 0.1;
/// A stretch whose points run within this of the line runs along it (a face's points along a
/// 20 cm stretch spread over its 20 cm along and a few centimetres across: a few degrees).
const MAX_ANGLE_DEG: f64 = 20.0;
/// ... and spread along it at least this many times more (variance) than across: a face's points
/// over 20 cm along and 1-2 cm across are some thirty times; a corner's two sides once or twice.
const MIN_ELONGATION: f64 = 4.0;
/// A stretch whose points cover every [`CROSS_BIN_M`] from this far in front of a face to as
/// far behind it holds a surface crossing the face: more than the face's noise and the depth
/// of what stands against a wall.
const CROSS_M: f64 = 0.12;
/// ... in bins of this.
const CROSS_BIN_M: f64 = 0.04;
/// The bins across `2 CROSS_M`.
const CROSS_BINS: u32 = 6;

/// Fewest stretches running along it, as a fraction of those with points: half (something
/// standing against a wall crosses its band in places; a corner's sides cross it everywhere).
pub(crate) const MIN_ALONG: f64 = 0.5;

/// Per face and stretch: count and sums for the points' covariance in (along, across).
#[derive(Clone, Copy)]
struct Moments {
    /// The [`CROSS_BIN_M`] bins across the face with points (bit k from `-CROSS_M + k bin`).
    across: u8,
    n: usize,
    s_min: f64,
    s_max: f64,
    s: f64,
    d: f64,
    ss: f64,
    dd: f64,
    sd: f64,
}

impl Default for Moments {
    fn default() -> Self {
        Moments {
            across: 0,
            n: 0,
            s_min: f64::INFINITY,
            s_max: f64::NEG_INFINITY,
            s: 0.0,
            d: 0.0,
            ss: 0.0,
            dd: 0.0,
            sd: 0.0,
        }
    }
}

impl Moments {
    /// True if the stretch's points tell a direction: enough of them, spread along at least
    /// half the stretch (a sparse scan's points on a far wall stand in one or two vertical
    /// columns per stretch, one beam each: no horizontal direction to read).
    fn tells(&self) -> bool {
        self.n >= MIN_POINTS && self.s_max - self.s_min >= MIN_SPREAD_M
    }

    /// True if the stretch's points cover the whole of [`CROSS_M`] either side of the face:
    /// a surface crossing it (see the module docs).
    fn crossed(&self) -> bool {
        self.across.count_ones() == CROSS_BINS
    }

    fn add(&mut self, s: f64, d: f64) {
        self.n += 1;
        self.s_min = self.s_min.min(s);
        self.s_max = self.s_max.max(s);
        self.s += s;
        self.d += d;
        self.ss += s * s;
        self.dd += d * d;
        self.sd += s * d;
    }

    /// True if the points run along the line: their principal direction within
    /// [`MAX_ANGLE_DEG`] of it, and their spread along that direction at least [`MIN_ELONGATION`]
    /// times the spread across (the two sides of a corner meeting in the band spread both ways).
    fn runs_along(&self) -> bool {
        let n = self.n as f64;
        let (ms, md) = (self.s / n, self.d / n);
        let (css, cdd, csd) = (
            self.ss / n - ms * ms,
            self.dd / n - md * md,
            self.sd / n - ms * md,
        );
        // Principal axis of a 2x2 covariance: half the angle of (css - cdd, 2 csd).
        let angle = (0.5 * (2.0 * csd).atan2(css - cdd)).to_degrees().abs();
        let (mean, half) = ((css + cdd) / 2.0, ((css - cdd) / 2.0).hypot(csd));
        angle <= MAX_ANGLE_DEG && mean + half >= MIN_ELONGATION * (mean - half)
    }
}

/// The points near a candidate's faces below head height, by stretch.
pub(crate) struct FaceOrientation {
    faces: Vec<f64>,
    /// `bins[face][stretch]`.
    bins: Vec<Vec<Moments>>,
}

impl FaceOrientation {
    /// For a candidate `length_m` long with these face offsets.
    pub fn new(length_m: f64, faces: &[f64]) -> FaceOrientation {
        let n = ((length_m / BIN_M).ceil() as usize).clamp(1, 1_000_000);
        FaceOrientation {
            faces: faces.to_vec(),
            bins: vec![vec![Moments::default(); n]; faces.len()],
        }
    }

    /// Adds a point `s` along the candidate (from its start) and `d` off its line, which lies
    /// below head height and above the floor.
    pub fn add(&mut self, s: f64, d: f64) {
        if s < 0.0 {
            return;
        }
        let k = (s / BIN_M) as usize;
        for (f, bins) in self.faces.iter().zip(&mut self.bins) {
            let Some(m) = bins.get_mut(k) else {
                continue;
            };
            if (d - f).abs() <= BAND_M {
                m.add(s - k as f64 * BIN_M, d - f);
            }
            let bin = (d - f + CROSS_M) / CROSS_BIN_M;
            if (0.0..f64::from(CROSS_BINS)).contains(&bin) {
                m.across |= 1 << bin as u8;
            }
        }
    }

    /// The fraction of the stretches with points that run along the line, on the face seen
    /// along most of it (the most stretches that tell a direction; then the most points);
    /// `None` where no stretch has enough points to tell.
    ///
    /// (Not the face with the most points: a row of pillars 0.3 m in front of a corridor's
    /// wall, near the laser, gave 3DTK's corridor a second "face" on the pillars' sides with
    /// as many points as the wall's face along four times as many stretches, and which of the
    /// two won turned on a 0.7 degree change of one scan's pitch.)
    pub fn along_fraction(&self) -> Option<f64> {
        let face = self.bins.iter().max_by_key(|bins| {
            let telling = bins.iter().filter(|m| m.tells()).count();
            (telling, bins.iter().map(|m| m.n).sum::<usize>())
        })?;
        fraction_along(face, false)
    }

    /// For the face a one-sided wall keeps (index `k` into the faces): the fraction of its
    /// stretches that tell a direction or hold a crossing surface (see the module docs) that
    /// run along the line; `None` where none does.
    pub fn kept_face_along_fraction(&self, k: usize) -> Option<f64> {
        fraction_along(self.bins.get(k)?, true)
    }
}

/// Of a face's stretches that tell a direction (or, with `crossings`, hold a surface crossing
/// the face), the fraction that run along the line; `None` where none does.
fn fraction_along(stretches: &[Moments], crossings: bool) -> Option<f64> {
    let seen: Vec<&Moments> = stretches
        .iter()
        .filter(|m| m.tells() || (crossings && m.crossed()))
        .collect();
    if seen.is_empty() {
        return None;
    }
    let along = seen.iter().filter(|m| m.tells() && m.runs_along()).count();
    Some(along as f64 / seen.len() as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_face_runs_along_and_a_pillar_cut_diagonally_does_not() {
        // A wall's face at offset 0.1: points every 2 cm along, 1 cm of noise across.
        let mut wall = FaceOrientation::new(2.0, &[0.1]);
        for i in 0..100 {
            let s = i as f64 * 0.02;
            wall.add(s, 0.1 + 0.01 * ((i % 3) as f64 - 1.0));
        }
        assert_eq!(wall.along_fraction(), Some(1.0));
        // The line cut diagonally through a pillar: the side of the pillar crosses the band at
        // 45 degrees (points on it every 1 cm); and where a line cuts a corner at about 60
        // degrees to both sides, the corner's two sides meet in the band (a V).
        let mut side = FaceOrientation::new(1.0, &[0.0]);
        let mut corner = FaceOrientation::new(1.0, &[0.0]);
        for i in 0..100 {
            let t = i as f64 * 0.01;
            for k in 0..5 {
                let s = 0.2 * k as f64 + t * 0.2;
                side.add(s, t * 0.2 - 0.1);
            }
            corner.add(t, 2.0 * (t - 0.5).abs() - 0.05);
        }
        assert_eq!(side.along_fraction(), Some(0.0));
        assert_eq!(corner.along_fraction(), Some(0.0));
        // A far wall in a sparse scan: one column of returns per stretch (many heights, one
        // place along, 1 cm of noise across): no direction to read, no verdict.
        let mut far = FaceOrientation::new(1.0, &[0.0]);
        for k in 0..5 {
            for i in 0..20 {
                far.add(0.2 * k as f64 + 0.1, 0.01 * ((i % 3) as f64 - 1.0));
            }
        }
        assert_eq!(far.along_fraction(), None);
        // Nothing near the face, or too few points: no verdict.
        let mut empty = FaceOrientation::new(1.0, &[0.0]);
        empty.add(0.5, 0.5);
        empty.add(0.5, 0.0);
        assert_eq!(empty.along_fraction(), None);
    }

    #[test]
    fn the_face_seen_along_most_of_the_candidate_decides() {
        // Two faces 0.2 m apart: the left one seen along its length, the right one only by
        // a few points of something crossing it.
        let mut w = FaceOrientation::new(1.0, &[-0.1, 0.1]);
        for i in 0..50 {
            w.add(i as f64 * 0.02, -0.1);
        }
        for i in 0..8 {
            w.add(0.5 + i as f64 * 0.01, 0.06 + i as f64 * 0.01);
        }
        assert_eq!(w.along_fraction(), Some(1.0));
        // Regression (3DTK's corridor): pillars' sides near the laser, crossing the band of a
        // "face" 0.3 m in front of the wall at 45 degrees in two stretches with 150 returns
        // each (they tell a direction, across), against the wall's face seen along eight
        // stretches with 12 returns each (96 in all).
        let mut w = FaceOrientation::new(1.6, &[-0.15, 0.15]);
        for k in [1, 5] {
            for j in 0..150 {
                w.add(
                    0.2 * k as f64 + 0.04 + 0.0008 * j as f64,
                    -0.21 + 0.0008 * j as f64,
                );
            }
        }
        for k in 0..8 {
            for i in 0..12 {
                w.add(
                    0.2 * k as f64 + 0.015 * i as f64,
                    0.15 + 0.005 * ((i % 3) as f64 - 1.0),
                );
            }
        }
        assert_eq!(w.along_fraction(), Some(1.0));
    }

    /// Regression: hall-10's row of pillars (0.52 m wide, 0.28 m apart, seen from both sides)
    /// was a wall: the projection drew a line between its two rows of faces, and the face the
    /// one-sided wall kept was made of the pillars' sides, square to it. Those cross the whole
    /// band either side of the face and run along nothing; a wall's face with a door jamb
    /// crossing it in one place still runs along it.
    #[test]
    fn a_kept_face_made_of_pillars_sides_does_not_run_along() {
        // The sides: at the pillars' edges (every 0.4 m along, alternately 0.52 and 0.28 m
        // apart), from 0.26 m in front of the face to 0.26 m behind it, a return every 2 cm.
        let mut row = FaceOrientation::new(3.4, &[0.0]);
        for pillar in 0..4 {
            for edge in [0.0, 0.52] {
                let s = 0.1 + 0.8 * pillar as f64 + edge;
                for j in 0..27 {
                    row.add(s, -0.26 + 0.02 * j as f64);
                }
            }
        }
        assert_eq!(row.kept_face_along_fraction(0), Some(0.0));
        // (the most-points verdict has none: no stretch's band tells a direction)
        assert_eq!(row.along_fraction(), None);
        // A wall's face every 2 cm along 3.4 m with a door jamb crossing it at 1.5 m (the
        // reveal from the face 0.15 m back, and the leaf standing open 0.3 m in front).
        let mut wall = FaceOrientation::new(3.4, &[0.0]);
        for i in 0..170 {
            wall.add(0.02 * i as f64, 0.01 * ((i % 3) as f64 - 1.0));
        }
        for j in 0..23 {
            wall.add(1.5, -0.15 + 0.02 * j as f64);
        }
        assert!(wall
            .kept_face_along_fraction(0)
            .is_some_and(|f| f >= MIN_ALONG));
    }
}
