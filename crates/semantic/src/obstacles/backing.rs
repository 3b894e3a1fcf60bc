//! Things standing against a wall (see the `obstacles` module, step 5): a cabinet or shelf in
//! front of a wall is seen from the room only, as its front face (and perhaps a side at a
//! grazing angle); its body and the floor under it, between that face and the wall, are never
//! seen. A box fitted to the seen face alone is a sliver straddling the front face, half of it
//! in the room. Where a standing cluster runs along a wall, no deeper than furniture is, and
//! the floor between it and the wall was seen nowhere, its box reaches back to the wall's face.
//! A floor seen there (under a desk or table, behind a free-standing panel, in a gap a robot
//! could use) leaves the box as fitted.

use super::classify::set_box_rule;
use super::fit::{convex_hull, rect_corners};
use super::merge::PARALLEL_COS;
use super::DetectedObstacle;
use crate::image_frame::ImageFrame;
use crate::walls::WallFit;
use glam::{DVec2, Vec3};

/// The deepest thing that stands against a wall: wardrobes, shelving and kitchen counters are
/// 0.3-0.65 m deep, desks against a wall up to 0.9 m (their floor is seen between the legs).
pub(super) const MAX_DEPTH_M: f64 = 0.9;

/// At most this share of the gap's cells may hold floor returns for the gap to count as unseen:
/// registration error and mixed pixels at the front edge put a few floor points under its rim.
const SEEN_FLOOR_SHARE: f64 = 0.2;

/// Per cell of `frame`: whether a return within `floor_band_m` above the floor (`floor`) falls
/// in it, i.e. whether the floor there was seen.
pub(super) fn floor_seen(
    frame: &ImageFrame,
    points: &[Vec3],
    floor: f64,
    floor_band_m: f64,
) -> Vec<bool> {
    let mut seen = vec![false; frame.len()];
    let w = frame.width_px as usize;
    for p in points {
        if (p.z as f64 - floor).abs() > floor_band_m {
            continue;
        }
        if let Some((col, row)) = frame.pixel_of(p.x as f64, p.y as f64) {
            seen[row as usize * w + col as usize] = true;
        }
    }
    seen
}

/// Grows the box of each standing, non-overhead cluster in `found` that runs along a wall of
/// `walls` (parallel, wholly on one side, within the wall's length) and lies within
/// [`MAX_DEPTH_M`] of its face, back to that face, if the floor between (cells of `frame`,
/// `floor_seen`) was not seen. `floor`: the floor's height (a standing cluster's bottom).
pub(super) fn back_onto_walls(
    found: &mut [DetectedObstacle],
    walls: &[WallFit],
    frame: &ImageFrame,
    floor_seen: &[bool],
    floor: f64,
) {
    for o in found.iter_mut() {
        if o.overhead || o.z_range.0 > floor + 1e-9 {
            continue;
        }
        let nearest = walls
            .iter()
            .filter_map(|w| facing(o, w))
            .min_by(|a, b| a.1.abs().total_cmp(&b.1.abs()));
        let Some((wall, near, far, s)) = nearest else {
            continue;
        };
        let side = near.signum();
        let face = wall.thickness / 2.0;
        if far.abs() - face > MAX_DEPTH_M || near.abs() <= face {
            continue;
        }
        // The gap between the cluster's back and the wall's face, one cell in from its ends.
        let inset = frame.resolution_m;
        let gap = (s[0] + inset, s[1] - inset, face, near.abs());
        if gap.1 <= gap.0 || !unseen(wall, side, gap, frame, floor_seen) {
            continue;
        }
        let n = wall.line.normal();
        let (d0, d1) = (face, far.abs());
        let centre =
            wall.line.origin + wall.line.dir * ((s[0] + s[1]) / 2.0) + n * (side * (d0 + d1) / 2.0);
        let size = [s[1] - s[0], d1 - d0];
        let old_area = o.size[0] * o.size[1];
        (o.center, o.dir, o.size) = if size[0] >= size[1] {
            (centre, wall.line.dir, size)
        } else {
            (centre, n, [size[1], size[0]])
        };
        let mut hull = o.hull.clone();
        hull.extend(rect_corners(o.center, o.dir, o.size));
        o.hull = convex_hull(&hull);
        o.fill = (o.fill * old_area / (o.size[0] * o.size[1]).max(1e-9)).clamp(0.0, 1.0);
        let why = format!(
            "box: along the wall it stands against, from its seen front back to the wall's face {:.2} m behind (the floor between was never seen)",
            d1 - d0
        );
        set_box_rule(o, why);
    }
}

/// If `o` runs along `w` (parallel, on one side of it, within its length): the wall, the
/// offsets from its centre line of the cluster's nearest and farthest corners (signed, on the
/// cluster's side) and the cluster's extent along it.
fn facing<'w>(o: &DetectedObstacle, w: &'w WallFit) -> Option<(&'w WallFit, f64, f64, [f64; 2])> {
    if w.line.dir.dot(o.dir).abs() < PARALLEL_COS {
        return None;
    }
    let corners = rect_corners(o.center, o.dir, o.size);
    let (mut s, mut near, mut far) = ([f64::MAX, f64::MIN], f64::MAX, 0.0f64);
    let side = w.line.coords(o.center).1.signum();
    for q in corners {
        let (sq, dq) = w.line.coords(q);
        if dq.signum() != side {
            return None;
        }
        s = [s[0].min(sq), s[1].max(sq)];
        near = near.min(dq.abs());
        far = far.max(dq.abs());
    }
    (s[0] >= 0.0 && s[1] <= w.length).then_some((w, side * near, side * far, s))
}

/// Whether the floor was seen in at most [`SEEN_FLOOR_SHARE`] of the cells of the gap
/// `(s0, s1, d0, d1)` (along the wall, and from its centre line on `side`).
fn unseen(
    w: &WallFit,
    side: f64,
    (s0, s1, d0, d1): (f64, f64, f64, f64),
    frame: &ImageFrame,
    floor_seen: &[bool],
) -> bool {
    let step = frame.resolution_m;
    let n = w.line.normal() * side;
    let (mut cells, mut seen) = (0usize, 0usize);
    let mut s = s0;
    while s <= s1 {
        let mut d = d0 + step / 2.0;
        while d < d1 {
            let q: DVec2 = w.line.origin + w.line.dir * s + n * d;
            if let Some((col, row)) = frame.pixel_of(q.x, q.y) {
                cells += 1;
                seen +=
                    usize::from(floor_seen[row as usize * frame.width_px as usize + col as usize]);
            }
            d += step;
        }
        s += step;
    }
    // A gap thinner than a cell holds no cell centre: nothing there to see.
    (seen as f64) <= SEEN_FLOOR_SHARE * cells as f64
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::points::Line2;
    use cloud::EntityClass;

    fn wall() -> WallFit {
        WallFit {
            line: Line2 {
                origin: DVec2::ZERO,
                dir: DVec2::X,
            },
            length: 8.0,
            thickness: 0.2,
            measured: true,
            faces: vec![0.1, -0.1],
            free_side: -1.0,
            z_range: (0.0, 2.5),
            support: 1000,
            coverage: 1.0,
            rules: Vec::new(),
        }
    }

    /// A cabinet's front face seen 0.5 m in front of the wall's face (y = -0.6).
    fn face() -> DetectedObstacle {
        let c = DVec2::new(3.0, -0.6);
        DetectedObstacle {
            class: EntityClass::Obstacle,
            center: c,
            dir: DVec2::X,
            size: [1.5, 0.05],
            z_range: (0.0, 1.9),
            hull: rect_corners(c, DVec2::X, [1.5, 0.05]).to_vec(),
            fill: 1.0,
            support: 500,
            overhead: false,
            beside_top: false,
            rules: Vec::new(),
        }
    }

    fn frame() -> ImageFrame {
        ImageFrame {
            origin_m: [-1.0, 1.0],
            resolution_m: 0.1,
            width_px: 100,
            height_px: 60,
        }
    }

    #[test]
    fn a_face_before_a_wall_with_its_floor_unseen_reaches_back_to_the_wall() {
        let f = frame();
        // The floor seen in front of the face only.
        let floor: Vec<Vec3> = (0..40)
            .flat_map(|i| {
                (0..20).map(move |j| Vec3::new(1.0 + 0.1 * i as f32, -0.7 - 0.1 * j as f32, 0.0))
            })
            .collect();
        let seen = floor_seen(&f, &floor, 0.0, 0.08);
        let mut found = vec![face()];
        back_onto_walls(&mut found, &[wall()], &f, &seen, 0.0);
        let o = &found[0];
        let ys: Vec<f64> = rect_corners(o.center, o.dir, o.size)
            .iter()
            .map(|q| q.y)
            .collect();
        let (lo, hi) = ys
            .iter()
            .fold((f64::MAX, f64::MIN), |a, y| (a.0.min(*y), a.1.max(*y)));
        assert!(
            (hi + 0.1).abs() < 1e-9 && (lo + 0.625).abs() < 1e-9,
            "{o:?}"
        );
        assert!((o.size[0] - 1.5).abs() < 1e-9, "{o:?}");
    }

    #[test]
    fn a_face_before_a_wall_with_its_floor_seen_behind_it_stays_as_fitted() {
        let f = frame();
        // The floor seen behind the face too: a free-standing panel, or a desk's open knee space.
        let floor: Vec<Vec3> = (0..40)
            .flat_map(|i| {
                (0..25).map(move |j| Vec3::new(1.0 + 0.1 * i as f32, -0.15 - 0.1 * j as f32, 0.0))
            })
            .collect();
        let seen = floor_seen(&f, &floor, 0.0, 0.08);
        let mut found = vec![face()];
        back_onto_walls(&mut found, &[wall()], &f, &seen, 0.0);
        assert_eq!(found[0], face());
        // Too deep for furniture: left as fitted as well.
        let mut far = face();
        far.center.y = -1.3;
        let mut found = vec![far.clone()];
        back_onto_walls(&mut found, &[wall()], &f, &vec![false; f.len()], 0.0);
        assert_eq!(found[0], far);
    }
}
