//! Past a flight's top step nothing climbs on as a ramp does ([`surface_climbs_on`] reads the
//! treads' surface of a flight seen across its width; the rest of these docs, the side face of
//! one seen from its side).
//!
//! A flight seen from its side only ends level: its side face's top edge runs on at its top
//! step's height over the landing (or the floor above), for a landing's depth at least, before
//! anything beyond it (an upper flight, a wall) rises. A ramp's side face climbs on. Seen
//! sparsely, the top edge of a ramp's face is itself stepped (the laser's lines sample it a few
//! centimetres apart in height), and a stretch of it cut off from the rest (by a gap in the
//! returns, or by nothing joining it to the rest once its mixed pixels are gone) reads as a
//! short flight: garage-28's 9 degree ramp, its first 1.4 m read as 3 steps of 0.129 m x
//! 0.325 m.
//!
//! Past the flight's top step, along its face, the face's top edge (the highest return per
//! [`BIN_M`]) is read over [`REACH_M`] in three stretches. A sparsely seen face's top edge is
//! sampled low in some bins (no line of the laser met it there), so the edge is the running
//! maximum from the first stretch's median bin (a bin more than two rises over it is a stray,
//! passed over): it climbs on where it rises in every stretch by
//! [`MIN_STEP_M`] to a rise (a ramp climbs 1:5 at most, 0.1 m over a stretch; a flight's
//! rise is 0.1 m at least), and by half a rise over all three. A landing holds level: what
//! stands on it (mixed pixels over its edge, a person) lifts the running maximum once, in one
//! stretch; a landing read in two voxel layers steps once by a few centimetres; an upper
//! flight beyond it, or a wall, rises by more than a rise. (A landing whose face something
//! hid near the flight, read low there, climbs to its level in the first stretches: office-74's,
//! behind a desk; the upper flight beyond it climbs too steeply for a ramp.)

use crate::points::{median, Line2};
use crate::scene::Scene;
use glam::DVec2;

/// How far past the top step the face is read.
const REACH_M: f64 = 1.5;

/// The bins along the face.
const BIN_M: f64 = 0.1;

/// Returns this near the face's line (across it) are on it.
const HALF_WIDTH_M: f64 = 0.075;

/// Each stretch's edge stands at least this much over the one before it.
const MIN_STEP_M: f64 = 0.02;

/// Bins with returns a stretch needs (of its five) to be read.
const MIN_BINS: usize = 3;

/// Where a flight's top step ends, read past it.
#[derive(Debug, Clone, Copy)]
pub(super) struct PastTop {
    /// The flight's direction of ascent.
    pub dir: DVec2,
    /// Where it is read across the flight (`dir.perp_dot`): its side face's line, or its
    /// treads' middle.
    pub across_m: f64,
    /// The far edge of its top step along it (`dir.dot`).
    pub end_m: f64,
    /// The flight's rise.
    pub rise_m: f64,
}

/// True if the side face at `past` climbs on past the top step as a ramp's does (see the
/// module docs); `false` where it holds level, rises once, or too little of it was seen.
pub(super) fn face_climbs_on(sc: &Scene, past: PastTop) -> bool {
    let rise_m = past.rise_m;
    let tops = edge_tops(sc, past);
    // The running maximum from the first stretch's median bin (a stray return can top the
    // first bin), passing over a bin more than two rises over it (a stray, or something
    // standing there: it climbs as no ramp's face does).
    let mut first: Vec<f64> = tops[..BINS / 3]
        .iter()
        .copied()
        .filter(|z| z.is_finite())
        .collect();
    let Some(mut edge) = median(&mut first) else {
        return false;
    };
    let start = edge;
    let mut rises = Vec::with_capacity(3);
    for stretch in tops.chunks(BINS / 3) {
        if stretch.iter().filter(|z| z.is_finite()).count() < MIN_BINS {
            return false;
        }
        let before = edge;
        for &z in stretch {
            if z <= edge + 2.0 * rise_m {
                edge = edge.max(z);
            }
        }
        rises.push(edge - before);
    }
    rises.iter().all(|r| (MIN_STEP_M..=rise_m).contains(r)) && edge - start >= 0.5 * rise_m
}

/// The bins past the top step.
const BINS: usize = (REACH_M / BIN_M) as usize;

/// The highest return per bin past the top step at `past`, over [`REACH_M`] (`NEG_INFINITY`
/// where a bin holds none).
fn edge_tops(sc: &Scene, past: PastTop) -> [f64; BINS] {
    let line = Line2 {
        origin: past.dir * past.end_m + past.dir.perp() * past.across_m,
        dir: past.dir,
    };
    let mut tops = [f64::NEG_INFINITY; BINS];
    // (off the floor and the ceiling: over an unseen stretch of the face, the ceiling's
    // returns are the highest)
    sc.upright
        .for_each_near_line(&line, 0.0, REACH_M, HALF_WIDTH_M, |_, s, _, z| {
            if s >= 0.0 {
                let k = ((s / BIN_M) as usize).min(BINS - 1);
                tops[k] = tops[k].max(z);
            }
        });
    tops
}

/// A ramp climbs at least 1:30 (2 degrees; wheelchair ramps climb 1:12, car-park ramps up to
/// 1:5) and at most 1:4.
const RAMP_SLOPES: std::ops::RangeInclusive<f64> = (1.0 / 30.0)..=0.25;
/// A surface's bins within this of the line through them lie on it (the range noise, and a
/// laser's bands on a slope a few centimetres apart in height).
const ON_LINE_M: f64 = 0.03;
/// The share of a surface's read bins on its line where it is one slope.
const MIN_ON_LINE: f64 = 0.8;

/// True if the surface over a flight's treads, read at `past` (their middle), climbs on past
/// its top step as a ramp's does: its
/// highest return per bin, read in two thirds of the bins at least, lies on one line (the
/// median of the bins' pairwise slopes: a person or a stray lifts a bin or two off it) rising
/// as a ramp does, by half a rise at least over the reach. A flight's treads end level (a
/// landing, the floor above) or at what rises beyond them by a riser or a wall at once: off
/// any ramp's line. (A ramp's surface seen in bands, where the laser's lines cross it, reads as
/// a flight across its whole width: blind garage-434's, 4 steps of 0.108 m x 0.447 m.)
pub(super) fn surface_climbs_on(sc: &Scene, past: PastTop) -> bool {
    let tops = edge_tops(sc, past);
    let bins: Vec<DVec2> = tops
        .iter()
        .enumerate()
        .filter(|(_, z)| z.is_finite())
        .map(|(k, &z)| DVec2::new((k as f64 + 0.5) * BIN_M, z))
        .collect();
    if 3 * bins.len() < 2 * BINS {
        return false;
    }
    let mut slopes: Vec<f64> = bins
        .iter()
        .enumerate()
        .flat_map(|(i, a)| bins[i + 1..].iter().map(move |b| (b.y - a.y) / (b.x - a.x)))
        .collect();
    let Some(slope) = median(&mut slopes) else {
        return false;
    };
    let mut offsets: Vec<f64> = bins.iter().map(|b| b.y - slope * b.x).collect();
    let Some(offset) = median(&mut offsets) else {
        return false;
    };
    let on_line = bins
        .iter()
        .filter(|b| (b.y - offset - slope * b.x).abs() <= ON_LINE_M)
        .count();
    RAMP_SLOPES.contains(&slope)
        && on_line as f64 >= MIN_ON_LINE * bins.len() as f64
        && slope * REACH_M >= 0.5 * past.rise_m
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::points::XyIndex;
    use glam::Vec3;

    /// A flight's top step along +X at y = 0, ending at `end_m`, of `rise_m`.
    fn along_x(end_m: f64, rise_m: f64) -> PastTop {
        PastTop {
            dir: DVec2::X,
            across_m: 0.0,
            end_m,
            rise_m,
        }
    }

    /// True if the face of `pts` climbs on past `end_m` (a flight's top of `rise_m`).
    fn climbs(pts: &[Vec3], end_m: f64, rise_m: f64) -> bool {
        let index = XyIndex::new(pts, DVec2::splat(-1.0), DVec2::new(5.0, 1.0), 0.25);
        let sc = Scene::with_one_index(pts, &index, 0.0, 3.0);
        face_climbs_on(&sc, along_x(end_m, rise_m))
    }

    /// True if the surface of `pts` climbs on past `end_m` (a flight's top of `rise_m`).
    fn surface_climbs(pts: &[Vec3], end_m: f64, rise_m: f64) -> bool {
        let index = XyIndex::new(pts, DVec2::splat(-1.0), DVec2::new(5.0, 1.0), 0.25);
        let sc = Scene::with_one_index(pts, &index, 0.0, 3.0);
        surface_climbs_on(&sc, along_x(end_m, rise_m))
    }

    /// Treads seen along x from 0 to `length` at y = 0, a return per 2 cm at `top(x)` with 1 cm
    /// of noise.
    fn surface(length: f64, top: impl Fn(f64) -> f64) -> Vec<Vec3> {
        (0..(length / 0.02) as usize)
            .map(|i| {
                let x = i as f64 * 0.02;
                let noise = 0.01 * ((i * 7) % 3) as f64 - 0.01;
                Vec3::new(x as f32, 0.0, (top(x) + noise) as f32)
            })
            .collect()
    }

    #[test]
    fn a_ramps_surface_climbs_on_a_landing_a_wall_or_an_upper_flight_do_not() {
        // A 7 degree ramp, its first 1.2 m read as steps of 0.1 m.
        assert!(surface_climbs(&surface(3.0, |x| 0.123 * x), 1.2, 0.1));
        // A flight of 0.17 m x 0.28 m steps (4 of them to 1.12 m), then ...
        let flight = |x: f64| 0.17 * ((x / 0.28).floor() + 1.0).min(4.0);
        // ... a level landing;
        assert!(!surface_climbs(&surface(2.7, flight), 1.12, 0.17));
        // ... a wall 0.6 m on;
        let wall = |x: f64| if x > 1.72 { 2.0 } else { flight(x) };
        assert!(!surface_climbs(&surface(2.7, wall), 1.12, 0.17));
        // ... an upper flight from a landing 0.4 m deep.
        let upper = |x: f64| {
            if x < 1.52 {
                flight(x)
            } else {
                0.68 + 0.17 * (((x - 1.52) / 0.28).floor() + 1.0)
            }
        };
        assert!(!surface_climbs(&surface(2.7, upper), 1.12, 0.17));
        // A ramp too shallow to be read (1:50) is no ramp here either.
        assert!(!surface_climbs(&surface(3.0, |x| 0.02 * x), 1.2, 0.1));
    }

    /// A side face along x from 0 to `length` at y = 0, 8 returns per 10 cm up to `top(x)`.
    fn face(length: f64, top: impl Fn(f64) -> f64) -> Vec<Vec3> {
        let mut pts = Vec::new();
        for i in 0..(length / 0.0125) as usize {
            let x = i as f64 * 0.0125;
            let h = top(x);
            pts.push(Vec3::new(x as f32, 0.0, h as f32));
            pts.push(Vec3::new(x as f32, 0.0, (h * 0.5) as f32));
        }
        pts
    }

    #[test]
    fn a_ramps_face_climbs_on_a_landings_holds_level() {
        // A 9 degree ramp's face, its first metre read as the flight.
        let ramp = face(3.0, |x| 0.158 * x);
        assert!(climbs(&ramp, 1.0, 0.13));
        // A flight of 0.17 m x 0.28 m, its landing 1.2 m deep, an upper flight beyond it.
        let stairs = |x: f64| {
            let steps = |s: f64| 0.17 * ((s / 0.28).floor() + 1.0).min(4.0);
            if x < 1.12 {
                steps(x)
            } else if x < 2.32 {
                0.68
            } else {
                0.68 + steps(x - 2.32)
            }
        };
        let flight = face(4.0, stairs);
        assert!(!climbs(&flight, 1.12, 0.17));
        // ... with mixed pixels 0.3 m over 0.3 m of the landing, and read in two layers 5 cm
        // apart.
        let mut strays = flight.clone();
        strays.extend((0..24).map(|i| Vec3::new(1.5 + i as f32 * 0.0125, 0.0, 0.98)));
        assert!(!climbs(&strays, 1.12, 0.17));
        let layered = face(4.0, |x| {
            if (1.6..2.32).contains(&x) {
                0.73
            } else {
                stairs(x)
            }
        });
        assert!(!climbs(&layered, 1.12, 0.17));
        // A wall 0.6 m past the top step.
        let mut walled = face(1.72, stairs);
        walled.extend(face(0.2, |_| 3.0).iter().map(|p| *p + Vec3::X * 1.72));
        assert!(!climbs(&walled, 1.12, 0.17));
        // Nothing seen past the top step.
        let alone = face(1.12, stairs);
        assert!(!climbs(&alone, 1.12, 0.17));
    }

    /// Regression: garage-28 (the bench's scans of 2026-12-04): without the mixed pixels that
    /// had joined it to the rest, 1.4 m of its 9 degree ramp's side face, sampled sparsely, was
    /// a part of its own (69 returns) and read as 3 steps of 0.129 m x 0.325 m seen from their
    /// side (one false staircase; the ramp, its foot taken, was not found). Past them the
    /// face climbs on. (The part, and the face's returns in the map past it, turned to climb
    /// along +X.)
    #[test]
    fn a_ramps_side_face_cut_off_from_the_rest_is_no_flight() {
        use crate::stairs::search::Search;
        use crate::stairs::tests::{over_floor, returns_by_part};
        use crate::stairs::StairsConfig;
        let (returns, kind) =
            returns_by_part(include_str!("../../tests/data/garage28_face_cut_off.txt"));
        let of_kind = |k: usize| -> Vec<(DVec2, f64)> {
            returns
                .iter()
                .zip(&kind)
                .filter(|(_, &j)| j == k)
                .map(|(r, _)| *r)
                .collect()
        };
        let (part, past) = (of_kind(0), of_kind(1));
        assert_eq!((part.len(), past.len()), (69, 138));
        // The part in a scene over a floor hidden under the ramp (Y 0-2.94 m), with or without
        // the face past it.
        let search = |with_past: bool| {
            let mut points = over_floor(
                &part,
                DVec2::new(-1.5, -2.0),
                (200, 150),
                DVec2::new(6.0, 2.94),
            );
            if with_past {
                points.extend(
                    past.iter()
                        .map(|(q, z)| Vec3::new(q.x as f32, q.y as f32, *z as f32)),
                );
            }
            let index = XyIndex::new(&points, DVec2::splat(-3.0), DVec2::splat(9.0), 0.25);
            let sc = Scene::with_one_index(&points, &index, 0.0, 2.6);
            let cands = [DVec2::X, DVec2::Y, -DVec2::X, -DVec2::Y];
            Search {
                pts: &part,
                all: &part,
                cands: &cands,
                walls_cands: cands.len(),
                sc: &sc,
                c: &StairsConfig::default(),
            }
            .stairs()
        };
        let alone = search(false).expect("alone, the stretch reads as a flight");
        assert_eq!(alone.iter().map(|f| f.steps).collect::<Vec<_>>(), [3]);
        assert_eq!(search(true), None);
    }

    /// Regression: blind garage-434 (seeds 431-435): a car-park ramp (7.7 degrees, 2.85 m wide),
    /// its surface seen in bands where the laser's lines cross it, read as 4 steps of 0.108 m x
    /// 0.447 m across its whole width (from 0.26 m along it to 2.05 m) ending on a "landing"; the
    /// ramp, its foot taken, was not found (one false staircase). Past a flight's top step its
    /// treads end level or at what rises beyond them; along the ramp's middle its surface climbs
    /// on. (The part's returns the map's stairs stage took, from the bench's map; the flights of
    /// the stage's other tests, read from real maps, pass the check.)
    #[test]
    fn a_ramps_surface_past_the_steps_read_on_it_climbs_on() {
        use crate::stairs::tests::returns_and_surface;
        let (all, _) =
            returns_and_surface(include_str!("../../tests/data/garage434_ramp_surface.txt"));
        assert_eq!(all.len(), 4541);
        let points: Vec<Vec3> = all
            .iter()
            .map(|(q, z)| Vec3::new(q.x as f32, q.y as f32, *z as f32))
            .collect();
        let index = XyIndex::new(&points, DVec2::splat(-1.0), DVec2::new(9.0, 4.0), 0.25);
        let sc = Scene::with_one_index(&points, &index, 0.0, 2.6);
        let past = |end_m: f64| PastTop {
            dir: DVec2::X,
            across_m: 1.5,
            end_m,
            rise_m: 0.108,
        };
        assert!(surface_climbs_on(&sc, past(2.05)));
        // Past the ramp's head nothing was seen: it does not climb on there.
        assert!(!surface_climbs_on(&sc, past(7.3)));
    }
}
