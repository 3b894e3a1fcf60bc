//! The oriented box of a cluster: the convex hull of its footprint and the smallest-area
//! rectangle around it (one side of that rectangle lies on a hull edge, so trying every edge's
//! direction finds it: rotating calipers, Freeman & Shapira 1975).

use glam::DVec2;

/// The convex hull of `pts` (Andrew's monotone chain), counter-clockwise, without repeated or
/// collinear points; fewer than three distinct points give what there is.
pub(crate) fn convex_hull(pts: &[DVec2]) -> Vec<DVec2> {
    let mut p: Vec<DVec2> = pts.iter().copied().filter(|q| q.is_finite()).collect();
    p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let cross = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o);
    let mut hull: Vec<DVec2> = Vec::with_capacity(2 * p.len());
    // Lower hull left to right, then the upper hull right to left (it may not pop the lower).
    for q in &p {
        while hull.len() >= 2 && cross(hull[hull.len() - 2], hull[hull.len() - 1], *q) <= 0.0 {
            hull.pop();
        }
        hull.push(*q);
    }
    let lower = hull.len() + 1;
    for q in p.iter().rev().skip(1) {
        while hull.len() >= lower && cross(hull[hull.len() - 2], hull[hull.len() - 1], *q) <= 0.0 {
            hull.pop();
        }
        hull.push(*q);
    }
    hull.pop();
    hull
}

/// A rectangle along a preferred direction is taken if its area is within this factor of the
/// smallest: a hull seen from some sides only (the back of a shelf against a wall is never
/// seen) is sheared by shadows, and its smallest rectangle turns with the shear, while what
/// stands in buildings mostly stands along their walls.
const PREFERRED_AREA_FACTOR: f64 = 1.15;

/// The smallest-area rectangle around a convex hull, or one along a `preferred` direction (the
/// walls') whose area is within [`PREFERRED_AREA_FACTOR`] of it: centre, unit direction of its
/// first axis, and its full size along that axis and across. A hull of one or two points gives
/// a line or a point (sizes 0).
pub(crate) fn min_area_rect(
    hull: &[DVec2],
    preferred: &[DVec2],
) -> Option<(DVec2, DVec2, [f64; 2])> {
    let mut dirs: Vec<DVec2> = hull
        .iter()
        .zip(hull.iter().cycle().skip(1))
        .filter_map(|(a, b)| (*b - *a).try_normalize())
        .collect();
    if dirs.is_empty() {
        dirs.push(DVec2::X);
    }
    let free = rect_along(hull, &dirs)?;
    let along = rect_along(hull, preferred).filter(|p| p.0 <= PREFERRED_AREA_FACTOR * free.0);
    along.or(Some(free)).map(|(_, c, d, s)| {
        // The first axis is the longer one.
        if s[0] >= s[1] {
            (c, d, s)
        } else {
            (c, d.perp(), [s[1], s[0]])
        }
    })
}

/// The smallest-area rectangle around `hull` with a side along one of `dirs`: area, centre,
/// direction, size.
fn rect_along(hull: &[DVec2], dirs: &[DVec2]) -> Option<(f64, DVec2, DVec2, [f64; 2])> {
    let first = *hull.first()?;
    let mut best: Option<(f64, DVec2, DVec2, [f64; 2])> = None;
    for &d in dirs {
        let n = d.perp();
        let (mut u0, mut u1, mut v0, mut v1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for q in hull {
            let r = *q - first;
            let (u, v) = (r.dot(d), r.dot(n));
            u0 = u0.min(u);
            u1 = u1.max(u);
            v0 = v0.min(v);
            v1 = v1.max(v);
        }
        let area = (u1 - u0) * (v1 - v0);
        if best.as_ref().is_none_or(|b| area < b.0 - 1e-12) {
            let centre = first + d * ((u0 + u1) / 2.0) + n * ((v0 + v1) / 2.0);
            best = Some((area, centre, d, [u1 - u0, v1 - v0]));
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hull_of_a_square_with_inner_points() {
        let mut pts = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(0.0, 1.0),
        ];
        pts.push(DVec2::new(0.5, 0.5));
        pts.push(DVec2::new(0.5, 0.0));
        let h = convex_hull(&pts);
        assert_eq!(h.len(), 4, "{h:?}");
    }

    #[test]
    fn min_area_rect_finds_a_turned_box() {
        // A 2 x 0.5 box turned by 30 degrees, sampled on its outline.
        let d = DVec2::from_angle(30f64.to_radians());
        let n = d.perp();
        let c = DVec2::new(3.0, -1.0);
        let mut pts = Vec::new();
        for k in 0..=20 {
            let t = k as f64 / 20.0;
            for (u, v) in [
                (-1.0 + 2.0 * t, -0.25),
                (-1.0 + 2.0 * t, 0.25),
                (-1.0, -0.25 + 0.5 * t),
                (1.0, -0.25 + 0.5 * t),
            ] {
                pts.push(c + d * u + n * v);
            }
        }
        let (centre, dir, size) = min_area_rect(&convex_hull(&pts), &[DVec2::X]).expect("rect");
        assert!((centre - c).length() < 1e-9, "{centre}");
        assert!(
            (size[0] - 2.0).abs() < 1e-9 && (size[1] - 0.5).abs() < 1e-9,
            "{size:?}"
        );
        assert!(dir.dot(d).abs() > 1.0 - 1e-9, "{dir}");
    }
}

/// The corners of the rectangle with centre `c`, unit first axis `d` and full `size`,
/// counter-clockwise.
pub(crate) fn rect_corners(c: DVec2, d: DVec2, size: [f64; 2]) -> [DVec2; 4] {
    let (u, v) = (d * (size[0] / 2.0), d.perp() * (size[1] / 2.0));
    [c - u - v, c + u - v, c + u + v, c - u + v]
}

/// The area of a polygon (absolute).
pub(crate) fn polygon_area(p: &[DVec2]) -> f64 {
    (0..p.len())
        .map(|k| p[k].perp_dot(p[(k + 1) % p.len()]))
        .sum::<f64>()
        .abs()
        / 2.0
}

/// The area of the intersection of two convex counter-clockwise polygons (Sutherland-Hodgman),
/// e.g. two boxes' footprints (m² for corners in metres).
pub fn intersection_area(a: &[DVec2], b: &[DVec2]) -> f64 {
    let mut poly: Vec<DVec2> = a.to_vec();
    for k in 0..b.len() {
        let (e0, e1) = (b[k], b[(k + 1) % b.len()]);
        let side = |q: DVec2| (e1 - e0).perp_dot(q - e0);
        let mut next = Vec::with_capacity(poly.len() + 2);
        for m in 0..poly.len() {
            let (p, q) = (poly[m], poly[(m + 1) % poly.len()]);
            let (sp, sq) = (side(p), side(q));
            if sp >= 0.0 {
                next.push(p);
            }
            if (sp >= 0.0) != (sq >= 0.0) {
                next.push(p + (q - p) * (sp / (sp - sq)));
            }
        }
        poly = next;
        if poly.is_empty() {
            return 0.0;
        }
    }
    polygon_area(&poly)
}

#[cfg(test)]
mod area_tests {
    use super::*;

    #[test]
    fn intersection_of_overlapping_rectangles() {
        let a = rect_corners(DVec2::ZERO, DVec2::X, [2.0, 2.0]);
        let b = rect_corners(DVec2::new(1.0, 1.0), DVec2::X, [2.0, 2.0]);
        assert!((intersection_area(&a, &b) - 1.0).abs() < 1e-9);
        let far = rect_corners(DVec2::new(5.0, 0.0), DVec2::Y, [1.0, 1.0]);
        assert_eq!(intersection_area(&a, &far), 0.0);
        assert!((polygon_area(&a) - 4.0).abs() < 1e-9);
    }
}
