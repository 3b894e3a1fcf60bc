//! Fitting one wall prerequisite: faces and plane, extent, heights, free sides, thickness (see
//! the `walls` module for the method).

use super::extent::find_extent;
use super::faces::refine_line;
use super::orientation::{FaceOrientation, MIN_ALONG};
use super::support::{SupportProfile, BIN_M, HEAD_HEIGHT_M};
use super::top::TopReach;
use super::{WallConfig, WallFit};
use crate::merge::Segment;
use crate::points::{quantile, Line2};
use crate::scene::Scene;

/// A wall's face has free space (floor, ceiling) right in front of it and its body behind it.
/// A face with the slab seen beside it on both sides alike (or on neither) bounds no free space;
/// it is a wall only if nothing is seen through it (a glass wall, a wall in clutter): open or
/// bare along this fraction of its length (a tenth: more than a stray return or two per
/// metre) and it is a plane through clutter, a beam or a door leaf.
const UNBOUNDED_FACE_MAX_THROUGH: f64 = 0.1;

/// The least fraction of a wall's length along which its face reaches up to the ceiling.
const MIN_TOP_COVERAGE: f64 = 0.3;

/// Measures the wall along one prerequisite segment; `None` if it is no wall.
pub(crate) fn fit_wall(seg: &Segment, sc: &Scene, c: &WallConfig) -> Option<WallFit> {
    let len0 = seg.length_m();
    let hw = c.search_half_width_m;
    // Refit the line on the faces over the extent found, and the extent on the refitted line,
    // until the extent settles (a short prerequisite may grow into a long wall).
    let mut line = seg.line();
    let (mut ends_a, mut ends_b) = (seg.a(), seg.b());
    let mut fit = None;
    for _ in 0..3 {
        let (a, b) = (line.coords(ends_a).0, line.coords(ends_b).0);
        let (l, faces) = refine_line(line, a, b, sc, c)?;
        line = l;
        let (a, b) = (line.coords(ends_a).0, line.coords(ends_b).0);
        let (lo, hi, crossing) = find_extent(&line, &faces, a, b, sc, c)?;
        let settled = (lo - a).abs() < 0.1 && (hi - b).abs() < 0.1;
        ends_a = line.at(lo);
        ends_b = line.at(hi);
        fit = Some((faces, lo, hi, crossing));
        if settled {
            break;
        }
    }
    let (faces, lo, hi, crossing) = fit?;
    let tol = c.face_tolerance_m;
    let on_face = |d: f64, faces: &[f64]| faces.iter().any(|f| (d - f).abs() <= tol);
    let (z_lo, z_hi) = (sc.floor + 0.05, sc.ceiling - 0.05);
    let crossed = |s: f64, z: f64| crossing.hides(s, z);
    // Face points over the final extent (corners left out): support, coverage, heights, free sides.
    let mut zs = Vec::new();
    let mut bins = vec![false; (((hi - lo) / 0.1).ceil() as usize).clamp(1, 1_000_000)];
    let mut reach = TopReach::new(bins.len(), z_lo, sc.ceiling - c.max_top_below_ceiling_m);
    let mut front = vec![[0usize; 2]; faces.len()];
    let strip = (0.02, 0.10);
    let mut profile = SupportProfile::new(
        ((hi - lo) / BIN_M).ceil().max(1.0) as usize,
        &faces,
        sc.floor,
    );
    let mut orientation = FaceOrientation::new(hi - lo, &faces);
    sc.index
        .for_each_near_line(sc.points, &line, lo, hi, hw + strip.1, |i, s, d| {
            let z = sc.z(i);
            if !crossed(s, z) {
                let face = z >= z_lo && z <= z_hi && on_face(d, &faces);
                profile.add(((s - lo) / BIN_M) as usize, d, z, face);
                if z > sc.floor + 0.1 && z < sc.floor + HEAD_HEIGHT_M {
                    orientation.add(s - lo, d);
                }
            }
            if z >= z_lo && z <= z_hi && on_face(d, &faces) && !crossed(s, z) {
                zs.push(z);
                let b = (((s - lo) / 0.1) as usize).min(bins.len() - 1);
                bins[b] = true;
                reach.add(b, z);
            }
            if sc.on_slab(i, 0.04) {
                for (k, f) in faces.iter().enumerate() {
                    let off = d - f;
                    if off.abs() >= strip.0 && off.abs() <= strip.1 {
                        front[k][usize::from(off > 0.0)] += 1;
                    }
                }
            }
        });
    if zs.len() < c.min_face_points {
        return None;
    }
    // A wall stands on the floor and hides what is behind it (see `support`): not a beam, a
    // row of pillars or a beam over them.
    let (standing, open, bare) = profile.fractions();
    if standing == 0.0 || open + bare > standing {
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
    let start = line.at(lo);
    let mut rules = vec![format!(
        "vertical plane through a {len0:.2} m projection segment; face points over {:.2} m ({:.0} % covered)",
        hi - lo,
        coverage * 100.0
    ), format!(
        "face seen below head height along {:.0} % of it, seen through below head height along {:.0} %, seen above head height only with nothing below along {:.0} % (a beam or pillars would be open or bare more than standing)",
        standing * 100.0,
        open * 100.0,
        bare * 100.0
    ), match along {
        Some(f) => format!("face points below head height run along it in {:.0} % of its 20 cm stretches (the sides of a corner cut through would not)", f * 100.0),
        None => "too few face points below head height to tell their direction".into(),
    }];
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
    if let [f1, f2] = faces[..] {
        let (s1, s2) = (side(0), side(1));
        if s1 <= 0.0 && s2 >= 0.0 && s1 != s2 {
            let mid = (f1 + f2) / 2.0;
            fit.line = fit.line.shifted(mid);
            fit.thickness = f2 - f1;
            fit.measured = true;
            fit.faces = vec![f1 - mid, f2 - mid];
            rules.push(format!(
                "two faces {:.3} m apart with free space outside both: thickness measured",
                f2 - f1
            ));
        }
    }
    if !fit.measured {
        // One face: the one with free space in front of it (else the first, the strongest).
        let k = (0..faces.len()).find(|&k| side(k) != 0.0).unwrap_or(0);
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
