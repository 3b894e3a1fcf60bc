//! The box and class of one cluster (see the `obstacles` module, steps 4 and 6): its footprint's
//! smallest rectangle, its z range, and whether it is a column, a beam or an obstacle.

use super::fit::{convex_hull, min_area_rect};
use super::{DetectedObstacle, ObstacleConfig, ObstacleScene};
use crate::image_frame::ImageFrame;
use cloud::EntityClass;
use glam::DVec2;

/// The box and class of one cluster: its points `members`, occupying `cells` cells of `frame`,
/// from `bottom` to `top`, found above head height if `overhead`.
pub(super) fn fit_cluster(
    sc: &ObstacleScene,
    members: &[u32],
    cells: usize,
    (bottom, top): (f64, f64),
    overhead: bool,
    frame: &ImageFrame,
    c: &ObstacleConfig,
) -> Option<DetectedObstacle> {
    let xy: Vec<DVec2> = members
        .iter()
        .map(|&i| {
            let p = sc.points[i as usize];
            DVec2::new(p.x as f64, p.y as f64)
        })
        .collect();
    let hull = convex_hull(&xy);
    let preferred: Vec<DVec2> = sc.walls.iter().map(|w| w.line.dir).collect();
    let (center, dir, mut size) = min_area_rect(&hull, &xy, &preferred)?;
    // The points are samples of the surface: the box reaches half a cell beyond them at least.
    let pad = frame.resolution_m / 2.0;
    size = [size[0].max(pad), size[1].max(pad)];
    let fill =
        (cells as f64 * frame.resolution_m.powi(2) / ((size[0] + pad) * (size[1] + pad))).min(1.0);
    let mut o = DetectedObstacle {
        class: EntityClass::Obstacle,
        center,
        dir,
        size,
        z_range: (bottom, top),
        hull,
        fill,
        support: members.len() as u64,
        overhead,
        beside_top: false,
        rules: vec![
            format!(
                "{} points explained by no floor, ceiling, wall, door or stairs, {} occupied {:.2} m cells {}",
                members.len(),
                cells,
                frame.resolution_m,
                if overhead { "above head height" } else { "below head height" }
            ),
            "box: the smallest-area rectangle around the footprint's convex hull".into(),
        ],
    };
    classify(&mut o, sc.floor, sc.ceiling, frame.resolution_m, c);
    Some(o)
}

/// Whether `o` stands on the floor (a low cluster whose bottom is near it) and whether it
/// reaches the ceiling, each within `full_height_margin_m`.
pub(super) fn reaches(
    o: &DetectedObstacle,
    floor: f64,
    ceiling: f64,
    c: &ObstacleConfig,
) -> (bool, bool) {
    let (bottom, top) = o.z_range;
    let near = c.full_height_margin_m;
    let on_floor = !o.overhead && bottom - floor <= c.min_above_floor_m + near;
    (on_floor, ceiling - top <= near)
}

/// Sets the class of `o` from its box (its z range is the measured one or one set by an
/// earlier call: a bottom near the floor stands on it, a top near the ceiling reaches it), and
/// its last rule to why: a low cluster standing on the floor, reaching the ceiling and at most
/// `column_max_across_m` across is a column; a high one at least `beam_min_length_m` long and
/// twice as long as wide is a beam; anything else is an obstacle.
pub(super) fn classify(
    o: &mut DetectedObstacle,
    floor: f64,
    ceiling: f64,
    cell_m: f64,
    c: &ObstacleConfig,
) {
    let (bottom, top) = o.z_range;
    let (on_floor, to_ceiling) = reaches(o, floor, ceiling, c);
    let z0 = if on_floor { floor } else { bottom };
    // A cluster of one height (a ledge seen edge-on) still has a box: half a cell tall at least.
    let z1 = if to_ceiling { ceiling } else { top }.max(z0 + cell_m / 2.0);
    o.z_range = (z0, z1);
    let size = o.size;
    let (class, why) = if !o.overhead && on_floor && to_ceiling && size[0] <= c.column_max_across_m
    {
        (
                EntityClass::Column,
                format!(
                    "stands from the floor to the ceiling, {:.2} m across at most (a column is at most {:.2} m)",
                    size[0], c.column_max_across_m
                ),
            )
    } else if o.overhead && size[0] >= c.beam_min_length_m && size[0] >= 2.0 * size[1] {
        (
                EntityClass::Beam,
                format!(
                    "{:.2} m long and {:.2} m wide above head height: its underside {:.2} m above the floor",
                    size[0],
                    size[1],
                    z0 - floor
                ),
            )
    } else {
        (
            EntityClass::Obstacle,
            format!(
                "occupies {:.2} x {:.2} m from {:.2} to {:.2} m above the floor",
                size[0],
                size[1],
                z0 - floor,
                z1 - floor
            ),
        )
    };
    o.class = class;
    o.rules.truncate(2);
    o.rules.push(why);
}

/// Replaces the rule that says how `o`'s box was fitted (its second: [`classify`] keeps the
/// first two rules, the points and the box, and adds the class's).
pub(super) fn set_box_rule(o: &mut DetectedObstacle, why: String) {
    match o.rules.get_mut(1) {
        Some(r) => *r = why,
        None => o.rules.push(why),
    }
}
