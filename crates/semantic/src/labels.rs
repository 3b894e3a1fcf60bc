//! Per-point labels (paper, Fig. 5 left: "segmentation of 3D cloud of points, where different
//! walls will have different label"). Every finite point gets the entity it lies on, in this
//! order (a later rule only labels points still unlabelled):
//!
//! 1. floor and ceiling: within `surface_tolerance_m` of their heights;
//! 2. walls: within `tolerance_m` of the wall's slab (centre line +- half the thickness), over
//!    its extent and height; in an opening, points at or above the opening's top belong to its
//!    wall above door, points below it to no wall;
//! 3. doors: within `tolerance_m` of the leaf as it was seen (turned by its observed angle);
//! 4. stairs: inside a step's or the landing's box (grown by `tolerance_m`);
//! 5. obstacles, columns and beams (found from the points the rules above leave unlabelled):
//!    inside their box (grown by `tolerance_m`).
//!
//! Points on nothing identified (small clutter, noise) stay unknown (entity 0).

use crate::error::Result;
use crate::net::{Detections, Ids};
use crate::points::XyIndex;
use cloud::check_range;
use cloud::{EntityClass, Label};
use glam::{DVec2, Vec3};
use serde::{Deserialize, Serialize};

/// Configuration of per-point labelling.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LabelConfig {
    /// Points this near the floor or ceiling height are on them.
    pub surface_tolerance_m: f64,
    /// Points this near a wall's slab, a leaf or a step are on it.
    pub tolerance_m: f64,
}

impl Default for LabelConfig {
    fn default() -> Self {
        LabelConfig {
            surface_tolerance_m: 0.04,
            tolerance_m: 0.04,
        }
    }
}

impl LabelConfig {
    pub(crate) fn validate(&self) -> Result<()> {
        check_range(
            "labels.surface_tolerance_m",
            self.surface_tolerance_m,
            0.0,
            1.0,
            "within 0..1 m",
        )?;
        check_range(
            "labels.tolerance_m",
            self.tolerance_m,
            0.0,
            1.0,
            "within 0..1 m",
        )?;
        Ok(())
    }
}

/// Labels the map points (same order as `points`).
pub(crate) fn label_points(
    points: &[Vec3],
    index: &XyIndex,
    d: &Detections,
    ids: &Ids,
    c: &LabelConfig,
) -> Vec<Label> {
    let mut labels = vec![Label::default(); points.len()];
    let tol = c.tolerance_m;
    let set = |l: &mut Label, entity: u32, class: EntityClass| {
        if l.entity == 0 && entity != 0 {
            *l = Label { entity, class };
        }
    };
    for (p, l) in points.iter().zip(labels.iter_mut()) {
        let z = p.z as f64;
        if let Some((f, _)) = d.levels.floor {
            if (z - f).abs() <= c.surface_tolerance_m {
                set(l, ids.floor, EntityClass::Floor);
            }
        }
        if let Some((ce, _)) = d.levels.ceiling {
            if (z - ce).abs() <= c.surface_tolerance_m {
                set(l, ids.ceiling, EntityClass::Ceiling);
            }
        }
    }
    for (wi, w) in d.walls.iter().enumerate() {
        let openings: Vec<(usize, &crate::doors::Opening)> = d
            .openings
            .iter()
            .enumerate()
            .filter(|(_, o)| o.wall == wi)
            .collect();
        index.for_each_near_line(
            &w.line,
            -tol,
            w.length + tol,
            w.thickness / 2.0 + tol,
            |i, s, _, z| {
                if z < w.z_range.0 - tol || z > w.z_range.1 + tol {
                    return;
                }
                let mut entity = (ids.walls[wi], EntityClass::Wall);
                for &(k, o) in &openings {
                    if s > o.s0 + tol && s < o.s1 - tol {
                        let lintel = ids.openings[k].1;
                        entity = if z >= o.top_z - tol && lintel != 0 {
                            (lintel, EntityClass::WallAboveDoor)
                        } else {
                            (0, EntityClass::Unknown)
                        };
                    }
                }
                set(&mut labels[i], entity.0, entity.1);
            },
        );
    }
    for (k, (o, leaf)) in d.openings.iter().zip(&d.leaves).enumerate() {
        let Some(leaf) = leaf else { continue };
        let w = &d.walls[o.wall];
        let width = o.s1 - o.s0;
        let (hinge, into) = if leaf.hinge_start {
            (w.line.at(o.s0), w.line.dir)
        } else {
            (w.line.at(o.s1), -w.line.dir)
        };
        // The leaf's direction as seen: `into` turned towards its swing side.
        let left_of_into = leaf.swing_left == leaf.hinge_start;
        let a = leaf.open_deg.to_radians() * if left_of_into { 1.0 } else { -1.0 };
        let dir = DVec2::from_angle(a).rotate(into);
        let line = crate::points::Line2 { origin: hinge, dir };
        index.for_each_near_line(
            &line,
            -tol,
            width + tol,
            d.leaf_thickness / 2.0 + tol,
            |i, _, _, z| {
                if z > w.z_range.0 + tol && z <= o.top_z + tol {
                    set(&mut labels[i], ids.openings[k].2, EntityClass::Door);
                }
            },
        );
    }
    let floor = d.levels.floor_ref_m;
    for (s, &id) in d.stairs.iter().zip(&ids.stairs) {
        for k in 1..=s.steps + u32::from(s.landing > 0.0) {
            let (a, b) = s.step_range(k);
            let top = floor + s.base + s.rise * k.min(s.steps) as f64;
            let line = crate::points::Line2 {
                origin: s.start,
                dir: s.dir,
            };
            index.for_each_near_line(
                &line,
                a - tol,
                b + tol,
                s.width / 2.0 + tol,
                |i, _, _, z| {
                    if z > floor + tol && z <= top + tol {
                        set(&mut labels[i], id, EntityClass::Stairs);
                    }
                },
            );
        }
    }
    labels
}

/// Labels the points inside each obstacle's box (grown by `tolerance_m`) that no other entity
/// labelled with the obstacle's id and class.
pub(crate) fn label_obstacles(
    index: &XyIndex,
    obstacles: &[crate::obstacles::DetectedObstacle],
    ids: &[u32],
    labels: &mut [Label],
    c: &LabelConfig,
) {
    let tol = c.tolerance_m;
    for (o, &id) in obstacles.iter().zip(ids) {
        let line = crate::points::Line2 {
            origin: o.center,
            dir: o.dir,
        };
        let (half_len, half_w) = (o.size[0] / 2.0 + tol, o.size[1] / 2.0 + tol);
        index.for_each_near_line(&line, -half_len, half_len, half_w, |i, _, _, z| {
            let l = &mut labels[i];
            if l.entity == 0 && z >= o.z_range.0 - tol && z <= o.z_range.1 + tol {
                *l = Label {
                    entity: id,
                    class: o.class,
                };
            }
        });
    }
}
