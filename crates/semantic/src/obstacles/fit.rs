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

/// Rectangles with an area within this factor of the smallest are candidates: a hull seen
/// from some sides only (the back of a shelf against a wall is never seen) is sheared by
/// shadows, so the smallest rectangle may turn with the shear, or lie along the diagonal of a
/// thing seen on two faces.
const AREA_FACTOR: f64 = 1.15;

/// Of the candidates, one along a preferred direction (the walls': what stands in buildings
/// mostly stands along them) is taken if the footprint's points lie about as close to its sides
/// as to the closest candidate's: their mean distance to the nearest side at most this factor
/// of that (plus [`CLOSENESS_SLACK_M`]); otherwise the closest is taken. The laser sees a
/// thing's faces, which are its box's sides (the closeness criterion of Zhang et al. 2017,
/// L-shape fitting): a box turned 45 degrees from the walls and seen on two faces has a right
/// triangle for a hull, whose rectangle along the walls (along its hypotenuse) is as small as the
/// one along its faces, but the faces then run through that rectangle's middle.
const PREFERRED_CLOSENESS_FACTOR: f64 = 1.5;
/// The closeness slack: a footprint seen filled (a top seen from above) lies about equally far
/// from any rectangle's sides.
const CLOSENESS_SLACK_M: f64 = 0.01;

/// The rectangle around a convex hull that its footprint's points `pts` lie closest to the sides
/// of, among those within [`AREA_FACTOR`] of the smallest area, or one along a `preferred`
/// direction (the walls') among them about as close ([`PREFERRED_CLOSENESS_FACTOR`]); without
/// points, the smallest-area one or one along `preferred` within [`AREA_FACTOR`] of it: centre,
/// unit direction of its first axis, and its full size along that axis and across. A hull of
/// one or two points gives a line or a point (sizes 0).
pub(crate) fn min_area_rect(
    hull: &[DVec2],
    pts: &[DVec2],
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
    // Each rectangle with its points' closeness, of those within the factor of the smallest.
    let scored = |rects: Vec<Rect>, smallest: f64| -> Vec<(Rect, f64)> {
        rects
            .into_iter()
            .filter(|r| r.0 <= AREA_FACTOR * smallest + 1e-12)
            .map(|r| {
                let c = closeness(pts, &r);
                (r, c)
            })
            .collect()
    };
    let on_hull: Vec<Rect> = dirs.iter().filter_map(|&d| rect_along(hull, d)).collect();
    let smallest = on_hull.iter().map(|r| r.0).fold(f64::INFINITY, f64::min);
    let on_walls: Vec<Rect> = preferred
        .iter()
        .filter_map(|&d| rect_along(hull, d))
        .collect();
    let by_closeness =
        |a: &(Rect, f64), b: &(Rect, f64)| a.1.total_cmp(&b.1).then(a.0 .0.total_cmp(&b.0 .0));
    let free = scored(on_hull, smallest).into_iter().min_by(by_closeness)?;
    let along = scored(on_walls, smallest)
        .into_iter()
        .filter(|p| p.1 <= PREFERRED_CLOSENESS_FACTOR * free.1 + CLOSENESS_SLACK_M)
        .min_by(|a, b| a.0 .0.total_cmp(&b.0 .0));
    along.or(Some(free)).map(|((_, c, d, s), _)| {
        // The first axis is the longer one.
        if s[0] >= s[1] {
            (c, d, s)
        } else {
            (c, d.perp(), [s[1], s[0]])
        }
    })
}

/// A rectangle: area, centre, unit direction of its first axis, full size along it and across.
type Rect = (f64, DVec2, DVec2, [f64; 2]);

/// The mean distance of `pts` to the nearest side of the rectangle `(area, centre, direction,
/// size)` (0 for no points).
fn closeness(pts: &[DVec2], (_, c, d, s): &Rect) -> f64 {
    if pts.is_empty() {
        return 0.0;
    }
    let n = d.perp();
    let sum: f64 = pts
        .iter()
        .map(|q| {
            let r = *q - *c;
            let u = s[0] / 2.0 - r.dot(*d).abs();
            let v = s[1] / 2.0 - r.dot(n).abs();
            u.min(v).max(0.0)
        })
        .sum();
    sum / pts.len() as f64
}

/// The rectangle around `hull` with a side along the unit direction `d` (`None` for no hull).
fn rect_along(hull: &[DVec2], d: DVec2) -> Option<Rect> {
    let first = *hull.first()?;
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
    let centre = first + d * ((u0 + u1) / 2.0) + n * ((v0 + v1) / 2.0);
    Some(((u1 - u0) * (v1 - v0), centre, d, [u1 - u0, v1 - v0]))
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
        let (centre, dir, size) =
            min_area_rect(&convex_hull(&pts), &pts, &[DVec2::X]).expect("rect");
        assert!((centre - c).length() < 1e-9, "{centre}");
        assert!(
            (size[0] - 2.0).abs() < 1e-9 && (size[1] - 0.5).abs() < 1e-9,
            "{size:?}"
        );
        assert!(dir.dot(d).abs() > 1.0 - 1e-9, "{dir}");
    }

    /// A deterministic jitter of up to `amp_m` (a registration's smear).
    fn jitter(k: usize, amp_m: f64) -> f64 {
        amp_m * (((k * 7919) % 101) as f64 / 50.0 - 1.0)
    }

    /// Regression (office-41 of seeds 41-45): a 0.37 x 0.41 m box turned 44 degrees from the
    /// walls, seen on its two faces towards the laser, has a right triangle for a footprint;
    /// its rectangle along the walls is the smallest, and covered 0.45 of the box.
    #[test]
    fn a_box_turned_from_the_walls_and_seen_on_two_faces_is_boxed_along_its_faces() {
        let d = DVec2::from_angle(44f64.to_radians());
        let n = d.perp();
        let c = DVec2::new(6.6, -1.9);
        let half = [0.185, 0.205];
        let mut pts = Vec::new();
        for k in 0..=40 {
            let t = k as f64 / 40.0;
            // The face at +half[0] along `d`, and the one at -half[1] across it.
            pts.push(c + d * (half[0] + jitter(k, 0.01)) + n * (-half[1] + 2.0 * half[1] * t));
            pts.push(c + d * (-half[0] + 2.0 * half[0] * t) + n * (-half[1] + jitter(k + 1, 0.01)));
        }
        let (_, dir, size) = min_area_rect(&convex_hull(&pts), &pts, &[DVec2::X]).expect("rect");
        let turned = dir.dot(d).abs().max(dir.dot(n).abs());
        assert!(turned > 5f64.to_radians().cos(), "{dir} for {d}");
        assert!(
            (size[0] - 0.41).abs() < 0.03 && (size[1] - 0.37).abs() < 0.03,
            "{size:?}"
        );
    }

    /// A footprint seen filled (a top seen from above) 3 degrees off the walls lies as close to
    /// the walls' rectangle's sides as to its own: it is boxed along the walls.
    #[test]
    fn a_filled_footprint_a_few_degrees_off_the_walls_is_boxed_along_them() {
        let d = DVec2::from_angle(3f64.to_radians());
        let mut pts = Vec::new();
        for i in 0..=20 {
            for j in 0..=10 {
                let (u, v) = (i as f64 / 20.0 - 0.5, (j as f64 / 10.0 - 0.5) * 0.5);
                pts.push(d * u + d.perp() * v);
            }
        }
        let (_, dir, _) = min_area_rect(&convex_hull(&pts), &pts, &[DVec2::X]).expect("rect");
        assert!(dir.dot(DVec2::X).abs() > 1.0 - 1e-9, "{dir}");
    }
}

/// The corners of the rectangle with centre `c`, unit first axis `d` and full `size`,
/// counter-clockwise.
pub(crate) fn rect_corners(c: DVec2, d: DVec2, size: [f64; 2]) -> [DVec2; 4] {
    let (u, v) = (d * (size[0] / 2.0), d.perp() * (size[1] / 2.0));
    [c - u - v, c + u - v, c + u + v, c - u + v]
}

/// Half the length that the rectangle with unit first axis `d` and full `size` covers along
/// the unit vector `along` (its corners' spread projected on `along`, halved).
pub(crate) fn half_extent_along(d: DVec2, size: [f64; 2], along: DVec2) -> f64 {
    (d.dot(along).abs() * size[0] + d.perp_dot(along).abs() * size[1]) / 2.0
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
