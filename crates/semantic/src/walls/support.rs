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
//! - *bare*: the face seen above head height, and below head height neither the face nor
//!   anything in front of or behind it that could hide it: the space under the face is empty
//!   (under a beam, between two pillars), or its face would have been seen there;
//! - neither: the face seen above head height with something standing beside it below head
//!   height (clutter, parked cars in front of it hid it), or nothing at all (not seen).
//!
//! A face seen below head height only under 1.5 m with something standing right beside it
//! (a parked car's flank on a beam's face line) is not counted standing: that thing's own side
//! can be the face. Nor is one seen under 1.5 m and above head height where the face is almost
//! nowhere seen between: a wall's face seen from the floor up is seen between too, a parked
//! car's flank under a beam's face is not, and the car's body beside its flank, hollow to a
//! laser below its top, may hold no return.
//!
//! A candidate is dropped if more of its length is open or bare than standing (a door is open
//! or bare too, but a wall holds fewer and narrower doors than wall), or if no bin stands (it
//! rests on no points of its own). Occlusion by clutter makes bins neither standing nor open
//! nor bare, so a wall behind a row of parked cars stays a wall as long as its face is seen
//! somewhere below head height (above the cars, at its ends).

/// Bins along the wall.
pub(crate) const BIN_M: f64 = 0.1;
/// Points up to this height above the floor are what people and robots run into; a beam's
/// underside is above it. 1.95 m: above the stature of 99 % of adults (~1.90 m), under the
/// 2.0 m minimum headroom and door heights of building codes.
pub(crate) const HEAD_HEIGHT_M: f64 = 1.95;
/// The band beside a face where the wall's body would be: from 6 cm (beyond the face's own
/// noise: the faces' tolerance is 3 cm, a laser's range noise 1-2 cm) to 15 cm.
const BODY_BAND_M: (f64, f64) = (0.06, 0.15);
/// Between two faces nearer than twice the body band's start, the body is what lies more than
/// a quarter of their distance inside either (a thin partition's body is thin; its faces'
/// noise reaches about 2 cm in, and only bins where no face stands count as open anyway).
const THIN_BODY_FRACTION: f64 = 0.25;
/// Something standing this high above the floor (a car, a cabinet, a person) beside a face
/// may hide the face below head height; lower returns are the floor and its noise.
const CLUTTER_MIN_HEIGHT_M: f64 = 0.1;
/// Face points from this high up to head height show a wall's face above what commonly stands
/// beside one (parked cars, 1.4-1.6 m; desks, chairs, crates). A face seen only lower, with
/// something standing right beside it, may be that thing's own side: a parked car's flank along
/// a beam line reads as a face from the floor to 1.3 m under the beam's face (fresh garage-44).
pub(crate) const UPPER_FACE_M: f64 = 1.5;

/// A face seen under [`UPPER_FACE_M`] and above head height but between them in fewer than this
/// share of the bins where it is seen under head height is two things, a low one under a high
/// one (a parked car's flank under a beam's face: garage-73 of the blind seeds). A wall
/// seen from the floor up is seen between too: nothing standing on the floor hides a band of a
/// face and not the face under it. (Not none: a stray return, or a person crossing the face's
/// plane, can stand there; the real walls of the 3DTK corridor and small_gicp's outdoor pair have
/// such bins along at most 17 % of their length, and are seen between along more.)
const NEVER_BETWEEN_SHARE: f64 = 0.1;

/// The share of a candidate's length along which a high thing (a beam) is seen over a low
/// one (see [`SupportProfile::low_thing_under_a_high_one`]).
const HIGH_THING_SHARE: f64 = 1.0 / 3.0;
/// The share of the bins where a low thing's face is seen under head height in which it must
/// stand, nothing beside it, to be a wall under a high thing (see
/// [`SupportProfile::low_thing_under_a_high_one`]): a parked car's front or flank has its body
/// beside it wherever it is seen.
const LOW_STANDS_SHARE: f64 = 0.5;

/// A stretch at a wall's end seen through for this long, its face seen below head height in
/// stray bins only, is no part of the wall (see [`SupportProfile::seen_through_ends`]): three bins,
/// more than a stray return or a person's shadow leaves.
const THROUGH_END_M: f64 = 0.3;
/// ... with a standing bin in at most one of this many (stray returns).
const MAX_STRAYS: usize = 5;
/// ... up to where the face stands in two bins running with at least this many face points
/// below head height each: fewer are stray returns too (one or two returns a bin, off a beam's
/// side face or a mixed pixel; a face seen from the floor up puts dozens in a bin, and a
/// sparse one 20 m away still about ten).
const MIN_FIRM_POINTS: u16 = 3;

const STANDING: u8 = 1;
const LEFT: u8 = 2;
const RIGHT: u8 = 4;
const BETWEEN: u8 = 8;
const ABOVE_HEAD: u8 = 16;
const CLUTTER: u8 = 32;
const STANDING_HIGH: u8 = 64;

/// Per bin: standing, seen left of the face, right of it, between two faces, the face seen
/// above head height, something standing beside the face below head height.
pub(crate) struct SupportProfile {
    bins: Vec<u8>,
    /// Per bin, its face points below head height (saturating).
    standing_points: Vec<u16>,
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
            standing_points: vec![0; n.max(1)],
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
            if face {
                *bin |= ABOVE_HEAD;
            }
            return;
        }
        if face {
            if above_floor > 0.05 {
                *bin |= STANDING;
                if let Some(n) = self.standing_points.get_mut(k) {
                    *n = n.saturating_add(1);
                }
            }
            if above_floor >= UPPER_FACE_M {
                *bin |= STANDING_HIGH;
            }
            return;
        }
        if above_floor < -0.05 {
            return;
        }
        let (lo, hi) = self.faces;
        let (b0, b1) = BODY_BAND_M;
        if self.two {
            let inset = b0.min((hi - lo) * THIN_BODY_FRACTION);
            if d > lo + inset && d < hi - inset {
                *bin |= BETWEEN;
            } else if above_floor >= CLUTTER_MIN_HEIGHT_M && (d - hi >= b0 || lo - d >= b0) {
                *bin |= CLUTTER;
            }
        } else if d - hi >= b0 && d - hi <= b1 {
            *bin |= LEFT;
        } else if lo - d >= b0 && lo - d <= b1 {
            *bin |= RIGHT;
        }
        if !self.two && above_floor >= CLUTTER_MIN_HEIGHT_M && (d - hi >= b0 || lo - d >= b0) {
            *bin |= CLUTTER;
        }
    }

    /// (standing, open, bare) fractions of the length. A bin whose face is seen only under
    /// [`UPPER_FACE_M`] with something standing beside it is not counted standing (nor open or
    /// bare: the face may be hidden there); nor, where the face is almost nowhere seen from
    /// [`UPPER_FACE_M`] up to head height (see [`NEVER_BETWEEN_SHARE`]), a bin where it is
    /// seen under it and above head height.
    pub fn fractions(&self) -> (f64, f64, f64) {
        let share = |f: &dyn Fn(u8) -> bool| self.share(f);
        let open =
            |b: u8| b & STANDING == 0 && (b & BETWEEN != 0 || b & (LEFT | RIGHT) == LEFT | RIGHT);
        let never_between = self.never_between();
        let hidden_between = |b: u8| never_between && b & ABOVE_HEAD != 0;
        (
            share(&|b| {
                b & STANDING != 0
                    && (b & STANDING_HIGH != 0 || b & CLUTTER == 0 && !hidden_between(b))
            }),
            share(&open),
            share(&|b| b & (STANDING | CLUTTER) == 0 && b & ABOVE_HEAD != 0 && !open(b)),
        )
    }

    /// True if the candidate is a low thing under a high one, the low one no wall: its face
    /// is almost nowhere seen between [`UPPER_FACE_M`] and head height (see
    /// [`NEVER_BETWEEN_SHARE`]), it is seen above head height along at least
    /// [`HIGH_THING_SHARE`] of its length, and under head height it stands (nothing beside it,
    /// see [`Self::fractions`]) in under [`LOW_STANDS_SHARE`] of the bins where it is seen
    /// there. Two parked cars' fronts in line under a beam crossing them obliquely (garage-109
    /// of seeds 106-110: seen under 1.0 m along 93 % of a 1.46 m line, the car bodies beside it
    /// in all but 7 %, the beam above along 60 %) make such a line; a wall's face, seen from
    /// the floor up, is seen between too, and a partial-height wall has nothing above it.
    pub fn low_thing_under_a_high_one(&self) -> bool {
        let low = self.share(&|b| b & STANDING != 0);
        let high = self.share(&|b| b & ABOVE_HEAD != 0);
        self.never_between()
            && high >= HIGH_THING_SHARE
            && self.fractions().0 < LOW_STANDS_SHARE * low
    }

    /// The share of the bins for which `f` holds.
    fn share(&self, f: &dyn Fn(u8) -> bool) -> f64 {
        self.bins.iter().filter(|&&b| f(b)).count() as f64 / self.bins.len() as f64
    }

    /// True if the face is seen from [`UPPER_FACE_M`] up to head height in fewer than
    /// [`NEVER_BETWEEN_SHARE`] of the bins where it is seen under head height.
    fn never_between(&self) -> bool {
        self.share(&|b| b & STANDING_HIGH != 0)
            < NEVER_BETWEEN_SHARE * self.share(&|b| b & STANDING != 0)
    }

    /// The bins to cut off at the start and at the end: a run of at least [`THROUGH_END_M`]
    /// from an end up to where the face is seen below head height in two bins running (with
    /// [`MIN_FIRM_POINTS`] returns each: garage-283 of seeds 281-285, the lobby's east wall ran
    /// on 1.64 m past its corner along a beam, one stray return in each of two bins there), seen
    /// through (open, or the body seen through and fewer face returns: garage-204 of seeds
    /// 201-205, 0.72 m past the lobby's corner, strays in three bins of seven) along half of it
    /// or more and the face seen below head height (as many returns) in at most one bin in
    /// [`MAX_STRAYS`] of it (stray returns), unless that end is a corner (`corners`: at the
    /// start, at the end; the face of a wall it meets is there). A wall's face seen from a room
    /// runs on along a beam's underside over the wall it meets and out over the floor beyond
    /// (garage-81 of seeds 81-85: 1.47 m past the lobby's corner, along a beam). A doorway
    /// next to a corner is open too, but it ends at that corner (at a free end a doorway is no
    /// doorway: the wall just ends). Bare bins are not enough: a
    /// wall's end whose face was hidden below head height from afar, nothing standing beside
    /// it, is bare (office-69 of seeds 66-70: the last 0.6 m of an outer wall); nor is a wall's
    /// end hidden by what stands before it, which is neither open nor bare.
    pub fn seen_through_ends(&self, corners: (bool, bool)) -> (usize, usize) {
        let n = self.bins.len();
        let min_bins = (THROUGH_END_M / BIN_M).round() as usize;
        let firm = |k: usize| self.standing_points[k] >= MIN_FIRM_POINTS;
        // (a return or two of the face where its body is seen through are strays too)
        let through = |k: usize| {
            let b = self.bins[k];
            !firm(k) && (b & BETWEEN != 0 || b & (LEFT | RIGHT) == LEFT | RIGHT)
        };
        // The bins from an end up to where the face stands firmly in two bins running (one is
        // a stray return: a person's head passing, a mixed pixel; so are a return or two a
        // bin).
        // (`bin(i)`: the `i`-th bin from the end looked at)
        let cut = |bin: &dyn Fn(usize) -> usize| -> usize {
            let len = (0..n)
                .find(|&i| firm(bin(i)) && (i + 1 == n || firm(bin(i + 1))))
                .unwrap_or(n);
            // (bins with a return or two below head height are strays however many)
            let strays = (0..len).filter(|&i| firm(bin(i))).count();
            let seen_through = (0..len).filter(|&i| through(bin(i))).count();
            if len >= min_bins && 2 * seen_through >= len && MAX_STRAYS * strays <= len {
                len
            } else {
                0
            }
        };
        let start = if corners.0 { 0 } else { cut(&|i| i) };
        let end = if corners.1 { 0 } else { cut(&|i| n - 1 - i) };
        if start + end >= n {
            return (0, 0);
        }
        (start, end)
    }
}

#[cfg(test)]
#[path = "support_tests.rs"]
mod tests;
