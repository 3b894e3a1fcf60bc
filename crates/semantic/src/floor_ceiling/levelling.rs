//! Levelling: the floor plane of the cloud, fitted robustly (see the `floor_ceiling` module).

use super::FloorCeilingConfig;
use crate::points::quantile;
use glam::{DAffine3, DQuat, DVec3, Vec3};
use rayon::prelude::*;

/// Fits the floor plane of the finite points (input frame). Returns `map_from_input` and the tilt.
pub(crate) fn level_transform(points: &[Vec3], c: &FloorCeilingConfig) -> (DAffine3, f64) {
    if !c.level {
        return (DAffine3::IDENTITY, 0.0);
    }
    // Third-lowest z per cell (robust against a couple of stray points below the floor), over
    // the cloud's robust XY extent (0.1 % to 99.9 %), at most 2048 cells a side.
    // (x and y on the two threads: each a copy of the cloud's coordinate, selected twice)
    let extent = |axis: fn(&Vec3) -> f32| {
        let mut v: Vec<f64> = points.iter().map(|p| axis(p) as f64).collect();
        (quantile(&mut v, 0.001), quantile(&mut v, 0.999))
    };
    let ((x0, x1), (y0, y1)) = rayon::join(|| extent(|p| p.x), || extent(|p| p.y));
    let (Some(x0), Some(x1), Some(y0), Some(y1)) = (x0, x1, y0, y1) else {
        return (DAffine3::IDENTITY, 0.0);
    };
    let cell = c.level_cell_m.max((x1 - x0).max(y1 - y0) / 2048.0);
    let cols = ((x1 - x0) / cell) as usize + 1;
    let rows = ((y1 - y0) / cell) as usize + 1;
    let mut cells = vec![([f32::INFINITY; 3], 0u32, 0.0f64, 0.0f64); cols * rows];
    for p in points {
        let (u, v) = ((p.x as f64 - x0) / cell, (p.y as f64 - y0) / cell);
        if !(u >= 0.0 && v >= 0.0 && (u as usize) < cols && (v as usize) < rows) {
            continue;
        }
        let e = &mut cells[v as usize * cols + u as usize];
        e.1 += 1;
        e.2 += p.x as f64;
        e.3 += p.y as f64;
        let z = p.z;
        if z < e.0[2] {
            e.0[2] = z;
            e.0.sort_by(f32::total_cmp);
        }
    }
    let samples: Vec<DVec3> = cells
        .iter()
        .filter(|e| e.1 >= 10)
        .map(|e| DVec3::new(e.2 / e.1 as f64, e.3 / e.1 as f64, e.0[2] as f64))
        .collect();
    if samples.len() < 10 {
        return (DAffine3::IDENTITY, 0.0);
    }
    let max_slope = c.max_tilt_deg.to_radians().tan();
    let mut rng = cloud::Rng::new(0x5eed_f100);
    // The 400 random triples drawn in order, their planes' inliers counted in parallel, the
    // first of the most inliers kept.
    let pick = |r: &mut cloud::Rng| samples[r.int(0, samples.len() as i64 - 1) as usize];
    let triples: Vec<[DVec3; 3]> = (0..400)
        .map(|_| [pick(&mut rng), pick(&mut rng), pick(&mut rng)])
        .collect();
    let counted: Vec<Option<(usize, [f64; 3])>> = triples
        .par_iter()
        .map(|&[a, b, d]| {
            let plane = plane_through(a, b, d)?;
            if plane[0].hypot(plane[1]) > max_slope {
                return None;
            }
            let inliers = samples
                .iter()
                .filter(|s| (s.z - eval(plane, **s)).abs() < c.plane_tolerance_m)
                .count();
            Some((inliers, plane))
        })
        .collect();
    let mut best: Option<(usize, [f64; 3])> = None;
    for (inliers, plane) in counted.into_iter().flatten() {
        if best.is_none_or(|(n, _)| inliers > n) {
            best = Some((inliers, plane));
        }
    }
    let Some((n, mut plane)) = best else {
        return (DAffine3::IDENTITY, 0.0);
    };
    if n < 3 {
        return (DAffine3::IDENTITY, 0.0);
    }
    for _ in 0..2 {
        let inliers: Vec<DVec3> = samples
            .iter()
            .copied()
            .filter(|s| (s.z - eval(plane, *s)).abs() < c.plane_tolerance_m)
            .collect();
        if let Some(p) = least_squares_plane(&inliers) {
            plane = p;
        }
    }
    // Refine the slope on the floor points themselves: the plane that puts the most of them
    // within 1 cm (a sharp floor), searched around the fit, coarse then fine.
    let step = (points.len() / 100_000).max(1);
    let near: Vec<DVec3> = points
        .iter()
        .step_by(step)
        .map(|p| p.as_dvec3())
        .filter(|p| (p.z - eval(plane, *p)).abs() < 0.1)
        .collect();
    if near.len() >= 100 {
        for (span, d) in [(0.01, 0.002), (0.002, 0.0004)] {
            let (a0, b0) = (plane[0], plane[1]);
            let mut best = (sharpness(&near, a0, b0), a0, b0);
            let k = (span / d) as i32;
            // (the grid's slopes scored in parallel, then taken in order: the first sharpest)
            let grid: Vec<(f64, f64)> = (-k..=k)
                .flat_map(|i| (-k..=k).map(move |j| (a0 + i as f64 * d, b0 + j as f64 * d)))
                .filter(|(a, b)| a.hypot(*b) <= max_slope)
                .collect();
            let scored: Vec<(usize, f64)> = grid
                .par_iter()
                .map(|&(a, b)| sharpness(&near, a, b))
                .collect();
            for (v, &(a, b)) in scored.into_iter().zip(&grid) {
                if v.0 > best.0 .0 {
                    best = (v, a, b);
                }
            }
            let ((_, c), a, b) = best;
            plane = [a, b, c];
        }
    }
    let normal = DVec3::new(-plane[0], -plane[1], 1.0).normalize();
    let tilt_deg = normal.angle_between(DVec3::Z).to_degrees();
    if tilt_deg < c.min_tilt_deg || tilt_deg > c.max_tilt_deg {
        return (DAffine3::IDENTITY, tilt_deg);
    }
    (
        DAffine3::from_quat(DQuat::from_rotation_arc(normal, DVec3::Z)),
        tilt_deg,
    )
}

/// How many of `pts` lie within 1 cm of the best plane of slopes `(a, b)`, and its offset:
/// the residuals `z - a x - b y` in 1 cm bins, the best pair of neighbouring bins.
fn sharpness(pts: &[DVec3], a: f64, b: f64) -> (usize, f64) {
    let r: Vec<f64> = pts.iter().map(|p| p.z - a * p.x - b * p.y).collect();
    let lo = r.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = r.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let n = (((hi - lo) / 0.01) as usize + 2).min(1_000_000);
    let mut h = vec![0usize; n];
    for v in &r {
        h[(((v - lo) / 0.01) as usize).min(n - 1)] += 1;
    }
    let (i, count) = (0..n - 1)
        .map(|i| (i, h[i] + h[i + 1]))
        .max_by_key(|x| x.1)
        .unwrap_or((0, 0));
    (count, lo + (i + 1) as f64 * 0.01)
}

fn eval(p: [f64; 3], s: DVec3) -> f64 {
    p[0] * s.x + p[1] * s.y + p[2]
}

/// The plane z = a x + b y + c through three points.
fn plane_through(p: DVec3, q: DVec3, r: DVec3) -> Option<[f64; 3]> {
    let n = (q - p).cross(r - p);
    if n.z.abs() < 1e-9 {
        return None;
    }
    let (a, b) = (-n.x / n.z, -n.y / n.z);
    Some([a, b, p.z - a * p.x - b * p.y])
}

fn least_squares_plane(pts: &[DVec3]) -> Option<[f64; 3]> {
    if pts.len() < 3 {
        return None;
    }
    let n = pts.len() as f64;
    let m = pts.iter().copied().sum::<DVec3>() / n;
    let (mut sxx, mut sxy, mut syy, mut sxz, mut syz) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for p in pts {
        let d = *p - m;
        sxx += d.x * d.x;
        sxy += d.x * d.y;
        syy += d.y * d.y;
        sxz += d.x * d.z;
        syz += d.y * d.z;
    }
    let det = sxx * syy - sxy * sxy;
    if det.abs() < 1e-12 {
        return None;
    }
    let a = (sxz * syy - syz * sxy) / det;
    let b = (syz * sxx - sxz * sxy) / det;
    Some([a, b, m.z - a * m.x - b * m.y])
}
