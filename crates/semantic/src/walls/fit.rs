//! Fitting one wall prerequisite: faces and plane, extent, heights, free sides, thickness (see
//! the `walls` module for the method).

use super::extent::find_extent;
use super::faces::refine_line;
use super::measure::{measure, FacePass};
use super::orientation::MIN_ALONG;
use super::support::BIN_M;
use super::{WallConfig, WallFit};
use crate::merge::Segment;
use crate::points::{quantile, Line2};
use crate::scene::Scene;
use glam::DVec2;

/// A wall's face has free space (floor, ceiling) right in front of it and its body behind it.
/// A face with the slab seen beside it on both sides alike (or on neither) bounds no free space;
/// it is a wall only if nothing is seen through it (a glass wall, a wall in clutter): open or
/// bare along this fraction of its length (a tenth: more than a stray return or two per
/// metre) and it is a plane through clutter, a beam or a door leaf.
const UNBOUNDED_FACE_MAX_THROUGH: f64 = 0.1;

/// A face is picked from the peaks of the projection band's distances (see `faces`); one that
/// holds fewer than this share of the face points over the wall's height that the strongest
/// holds is no face of the wall: a few returns in the band beside it (the glass partitions of
/// office-77 (seeds 76-80) and of office-7, seen from both rooms, neither face with free space of its
/// own: a veil of returns near the ceiling 0.2 m beside the glass held 2 and 1 face points for
/// the glass's 1280 and 1575, and the wall was placed on the veil, then dropped for resting on
/// no points of its own). A glass wall's two faces hold a fifth to all of each other's.
const MIN_FACE_SHARE: f64 = 0.1;

/// The least fraction of a wall's length along which its face reaches up to the ceiling.
const MIN_TOP_COVERAGE: f64 = 0.3;

/// A refitted line that turned by more than this in its last round has not settled on a face.
const SETTLED_ANGLE_DEG: f64 = 0.5;
/// An extent whose ends moved by less than this in its last round has settled.
const SETTLED_ENDS_M: f64 = 0.1;
/// The most rounds of refitting the line and the extent.
const MAX_FIT_ROUNDS: usize = 6;

/// Rounds of `round` (the line refitted over the extent between two ends, and the extent
/// found on it: the refitted line and the extent's ends along it) from `line` and `ends`,
/// until the line stops turning and the extent's ends stop moving, or `MAX_FIT_ROUNDS`; the
/// last round's line, extent and by-products. A short prerequisite may grow into a long wall,
/// and a segment through clutter may turn onto the face it touches over several rounds:
/// hall-30's turned by 65, 6.2 and 1.7 degrees, its extent settled in the third round, and
/// stopped there, 3.7 degrees across a row of pillars' faces, read as a wall (refitted on, it
/// turns by 3.2 and 0.5 degrees more, onto the faces).
fn settle<X>(
    mut line: Line2,
    mut ends: (DVec2, DVec2),
    mut round: impl FnMut(Line2, (DVec2, DVec2)) -> Option<(Line2, f64, f64, X)>,
) -> Option<(Line2, f64, f64, X)> {
    let mut fit = None;
    for _ in 0..MAX_FIT_ROUNDS {
        let (l, lo, hi, by) = round(line, ends)?;
        let turned = l.dir.dot(line.dir).abs() < SETTLED_ANGLE_DEG.to_radians().cos();
        let (a, b) = (l.coords(ends.0).0, l.coords(ends.1).0);
        let moved = (lo - a).abs() >= SETTLED_ENDS_M || (hi - b).abs() >= SETTLED_ENDS_M;
        ends = (l.at(lo), l.at(hi));
        line = l;
        fit = Some((lo, hi, by));
        if !turned && !moved {
            break;
        }
    }
    let (lo, hi, by) = fit?;
    Some((line, lo, hi, by))
}

/// Measures the wall along one prerequisite segment; `None` if it is no wall.
pub(crate) fn fit_wall(seg: &Segment, sc: &Scene, c: &WallConfig) -> Option<WallFit> {
    fit_wall_noting(seg, sc, c, &mut None)
}

/// Where a fit settled (see [`fit_wall_noting`]).
pub(super) struct Settled {
    /// The face line and the extent along it.
    pub line: Line2,
    pub lo: f64,
    pub hi: f64,
    /// How far across the line its faces reach (and their tolerance).
    pub half_width: f64,
    /// True if the fit was dropped as a beam: more of it seen through or bare below head
    /// height than standing.
    pub beam: bool,
}

/// [`fit_wall`], noting in `settled` the line and extent its fit settled on, if it did, and
/// whether it was dropped as a beam.
pub(super) fn fit_wall_noting(
    seg: &Segment,
    sc: &Scene,
    c: &WallConfig,
    settled: &mut Option<Settled>,
) -> Option<WallFit> {
    let len0 = seg.length_m();
    // Refit the line on the faces over the extent found, and the extent on the refitted line,
    // until both settle.
    let (line, lo, hi, (faces, crossing)) =
        settle(seg.line(), (seg.a(), seg.b()), |line, ends| {
            let (a, b) = (line.coords(ends.0).0, line.coords(ends.1).0);
            let (l, faces) = refine_line(line, a, b, sc, c)?;
            let (a, b) = (l.coords(ends.0).0, l.coords(ends.1).0);
            let (lo, hi, crossing) = find_extent(&l, &faces, a, b, sc, c)?;
            Some((l, lo, hi, (faces, crossing)))
        })?;
    let noted = settled.insert(Settled {
        line,
        lo,
        hi,
        half_width: faces.iter().fold(0.0, |m: f64, f| m.max(f.abs())) + c.face_tolerance_m,
        beam: false,
    });
    // Face points over the final extent (corners left out): support, coverage, heights, free
    // sides.
    let FacePass {
        mut zs,
        covered: bins,
        reach,
        front,
        on_each,
        profile,
        orientation,
    } = measure(&line, (lo, hi), &faces, &crossing, sc, c);
    if zs.len() < c.min_face_points {
        return None;
    }
    // A wall stands on the floor and hides what is behind it (see `support`): not a beam, a
    // row of pillars or a beam over them.
    let (standing, open, bare) = profile.fractions();
    if standing == 0.0 || open + bare > standing || profile.low_thing_under_a_high_one() {
        // (a wall in line with the beam can stand past its end: see `rests`)
        noted.beam = open + bare > standing;
        return None;
    }
    // Its face is a plane along it, not the sides of a corner it cuts through.
    let along = orientation.along_fraction();
    if along.is_some_and(|f| f < MIN_ALONG) {
        return None;
    }
    let support = zs.len() as u64;
    let bottom = quantile(&mut zs, 0.01)?;
    let top = quantile(&mut zs, 0.995)?;
    let top_coverage = reach.any_fraction();
    if bottom > sc.floor + c.max_bottom_above_floor_m
        || top < sc.ceiling - c.max_top_below_ceiling_m
        || top_coverage < MIN_TOP_COVERAGE
    {
        return None;
    }
    let snap = |v: f64, to: f64| if (v - to).abs() <= c.snap_m { to } else { v };
    let z_range = (snap(bottom, sc.floor), snap(top, sc.ceiling));
    let coverage = bins.iter().filter(|&&b| b).count() as f64 / bins.len() as f64;
    // Free side of each face: +1 if the free space is to its left, -1 right, 0 unknown.
    let side = |k: usize| -> f64 {
        let [right, left] = front[k];
        if left >= 2 * right + 3 {
            1.0
        } else if right >= 2 * left + 3 {
            -1.0
        } else {
            0.0
        }
    };
    // A wall that stands: an end seen through, its face seen below head height in stray returns
    // only, is cut off and the rest measured again (see `SupportProfile::seen_through_ends`).
    // What judged it a wall is the whole extent's (a cut never turns a beam into a wall).
    let corners = (
        crossing.corner_near(lo).is_some(),
        crossing.corner_near(hi).is_some(),
    );
    let (cut0, cut1) = profile.seen_through_ends(corners);
    let (lo, hi) = (lo + cut0 as f64 * BIN_M, hi - cut1 as f64 * BIN_M);
    let (support, coverage) = if cut0 + cut1 > 0 {
        let cut = measure(&line, (lo, hi), &faces, &crossing, sc, c);
        let covered = cut.covered.iter().filter(|&&b| b).count();
        (
            cut.zs.len() as u64,
            covered as f64 / cut.covered.len() as f64,
        )
    } else {
        (support, coverage)
    };
    let start = line.at(lo);
    let mut rules = vec![format!(
        "vertical plane through a {len0:.2} m projection segment; face points over {:.2} m ({:.0} % covered)",
        hi - lo,
        coverage * 100.0
    ), format!(
        "face seen below head height along {:.0} % of it (above 1.5 m where something stands beside it, or where it is seen above head height and almost nowhere between), seen through below head height along {:.0} %, seen above head height only with nothing below along {:.0} % (a beam or pillars would be open or bare more than standing)",
        standing * 100.0,
        open * 100.0,
        bare * 100.0
    ), match along {
        Some(f) => format!("face points below head height run along it in {:.0} % of its 20 cm stretches (the sides of a corner cut through would not)", f * 100.0),
        None => "too few face points below head height to tell their direction".into(),
    }];
    if cut0 + cut1 > 0 {
        rules.push(format!(
            "cut {:.1} m at its start and {:.1} m at its end: seen through there below head height, its face not seen there but in stray returns",
            cut0 as f64 * BIN_M,
            cut1 as f64 * BIN_M
        ));
    }
    let mut fit = WallFit {
        line: Line2 {
            origin: start,
            dir: line.dir,
        },
        length: hi - lo,
        thickness: 0.0,
        measured: false,
        faces: Vec::new(),
        free_side: 0.0,
        z_range,
        support,
        coverage,
        rules: Vec::new(),
    };
    let most = on_each.iter().copied().max().unwrap_or(0);
    let holds_face_points = |k: usize| on_each[k] as f64 >= MIN_FACE_SHARE * most as f64;
    if let [f1, f2] = faces[..] {
        let (s1, s2) = (side(0), side(1));
        // Free space outside both faces; or beside neither apart from the other, both holding
        // face points over its height: a glass wall seen from both sides, the floor and the
        // ceiling seen through its body as beside it. (Taking one face, its free side towards
        // the cloud's middle, put office-513's and office-514's 0.15 m glass partitions of
        // seeds 511-515 a thickness off, on the far side of the face; in office-514 a door leaf
        // was then read in the glass.)
        let outside = s1 <= 0.0 && s2 >= 0.0 && s1 != s2;
        let glass = s1 == 0.0 && s2 == 0.0 && holds_face_points(0) && holds_face_points(1);
        if outside || glass {
            let mid = (f1 + f2) / 2.0;
            fit.line = fit.line.shifted(mid);
            fit.thickness = f2 - f1;
            fit.measured = true;
            fit.faces = vec![f1 - mid, f2 - mid];
            rules.push(if outside {
                format!(
                    "two faces {:.3} m apart with free space outside both: thickness measured",
                    f2 - f1
                )
            } else {
                format!(
                    "two faces {:.3} m apart, each holding face points over its height, the floor or ceiling seen beside both alike (a glass wall seen from both sides): thickness measured",
                    f2 - f1
                )
            });
        }
    }
    if !fit.measured {
        // One face: the one with free space in front of it, else the first (across the wall)
        // of those that hold face points over its height (see `MIN_FACE_SHARE`).
        let k = (0..faces.len())
            .find(|&k| side(k) != 0.0)
            .or_else(|| (0..faces.len()).find(|&k| holds_face_points(k)))
            .unwrap_or(0);
        let mut s = side(k);
        if s == 0.0 && open + bare >= UNBOUNDED_FACE_MAX_THROUGH {
            // No side of the face is free space with a body behind it, and the scans saw
            // through it: a plane through clutter, a beam, a door leaf; not a wall.
            return None;
        }
        if s == 0.0 && reach.dense_fraction() < MIN_TOP_COVERAGE {
            // Nor does its face reach the ceiling but through a few returns over its top (the
            // mixed pixels over a door leaf's or a cupboard's top edge, see `top`): not a wall.
            // (A wall with free space in front keeps the test above: a duct in front of its top
            // hides that from the laser just as sparsely.)
            return None;
        }
        if s == 0.0 {
            // No floor or ceiling seen beside it: the free space faces the cloud's middle.
            s = if (sc.middle - line.at((lo + hi) / 2.0)).dot(line.normal()) >= 0.0 {
                1.0
            } else {
                -1.0
            };
            rules.push("free side unknown (no floor or ceiling beside the face): taken towards the middle of the cloud".into());
        }
        // The face it keeps runs along it (not the sides of pillars it was drawn across).
        if orientation
            .kept_face_along_fraction(k)
            .is_some_and(|f| f < MIN_ALONG)
        {
            return None;
        }
        fit.line = fit.line.shifted(faces[k]);
        fit.free_side = s;
    }
    rules.push(format!(
        "stands from z {:.2} to {:.2} m (floor {:.2}, ceiling {:.2})",
        z_range.0, z_range.1, sc.floor, sc.ceiling
    ));
    fit.rules = rules;
    Some(fit)
}

#[cfg(test)]
#[path = "fit_tests.rs"]
mod tests;
