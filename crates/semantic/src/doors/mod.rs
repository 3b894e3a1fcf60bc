//! Doors: the openings of each wall with their lintels ([`openings`]), the leaf in or near
//! each opening ([`leaves`]), and the wall prerequisites that turn out to be open leaves
//! dropped from the walls.

mod leaves;
mod opening_bins;
mod opening_config;
mod openings;

pub use leaves::DoorConfig;
pub(crate) use leaves::Leaf;
pub use opening_config::OpeningConfig;
pub(crate) use openings::Opening;

use crate::points::{undirected_angle_deg, Line2};
use crate::scene::Scene;
use crate::walls::WallFit;
use glam::DVec2;
use leaves::find_leaf;
use openings::find_openings;
use rayon::prelude::*;

/// A wall prerequisite within this angle of a found leaf's direction may be that leaf.
const LEAF_WALL_MAX_ANGLE_DEG: f64 = 10.0;
/// ... if both its ends lie within this distance of the leaf's line ...
const LEAF_WALL_MAX_OFFSET_M: f64 = 0.15;
/// ... and it is no longer than the opening plus this.
const LEAF_WALL_EXTRA_LENGTH_M: f64 = 0.3;

/// The walls (open leaves taken for walls dropped), their openings and each opening's leaf.
pub(crate) struct Doorways {
    /// The walls, without the open leaves that were taken for walls.
    pub walls: Vec<WallFit>,
    /// The openings; `Opening::wall` indexes `walls`.
    pub openings: Vec<Opening>,
    /// The leaf of each opening, if one was found.
    pub leaves: Vec<Option<Leaf>>,
}

/// Finds the openings of every wall and their leaves (in parallel), then drops the wall
/// prerequisites that are leaves found in an opening.
pub(crate) fn find_doors(
    walls: Vec<WallFit>,
    sc: &Scene,
    openings_config: &OpeningConfig,
    doors_config: &DoorConfig,
    face_tol: f64,
) -> Doorways {
    let openings: Vec<_> = walls
        .par_iter()
        .enumerate()
        .flat_map_iter(|(i, w)| find_openings(i, w, sc, openings_config, face_tol))
        .collect();
    let leaves: Vec<_> = openings
        .par_iter()
        .map(|o| find_leaf(o, &walls[o.wall], sc, doors_config, face_tol))
        .collect();
    drop_leaf_walls(Doorways {
        walls,
        openings,
        leaves,
    })
}

/// Drops the wall prerequisites that are door leaves found in an opening (an open leaf stands
/// as tall as a wall in the projection band when the door is nearly as high as the ceiling):
/// those within [`LEAF_WALL_MAX_ANGLE_DEG`] of the leaf's direction, both ends within
/// [`LEAF_WALL_MAX_OFFSET_M`] of its line and no longer than the opening plus
/// [`LEAF_WALL_EXTRA_LENGTH_M`]. Openings are re-indexed.
fn drop_leaf_walls(d: Doorways) -> Doorways {
    let Doorways {
        walls,
        openings,
        leaves,
    } = d;
    let mut drop = vec![false; walls.len()];
    for (o, leaf) in openings.iter().zip(&leaves) {
        let Some(leaf) = leaf else { continue };
        let w = &walls[o.wall];
        let (hinge, into) = if leaf.hinge_start {
            (w.line.at(o.s0), w.line.dir)
        } else {
            (w.line.at(o.s1), -w.line.dir)
        };
        let left = leaf.swing_left == leaf.hinge_start;
        let dir = DVec2::from_angle(leaf.open_deg.to_radians() * if left { 1.0 } else { -1.0 })
            .rotate(into);
        let line = Line2 { origin: hinge, dir };
        let width = o.s1 - o.s0;
        for (k, v) in walls.iter().enumerate() {
            let near = [v.start(), v.end()]
                .iter()
                .all(|p| line.coords(*p).1.abs() <= LEAF_WALL_MAX_OFFSET_M);
            if k != o.wall
                && near
                && undirected_angle_deg(v.line.dir, dir) <= LEAF_WALL_MAX_ANGLE_DEG
                && v.length <= width + LEAF_WALL_EXTRA_LENGTH_M
            {
                drop[k] = true;
            }
        }
    }
    if !drop.iter().any(|&d| d) {
        return Doorways {
            walls,
            openings,
            leaves,
        };
    }
    let mut new_index = vec![usize::MAX; walls.len()];
    let mut kept = Vec::new();
    for (k, w) in walls.into_iter().enumerate() {
        if !drop[k] {
            new_index[k] = kept.len();
            kept.push(w);
        }
    }
    let (openings, leaves): (Vec<_>, Vec<_>) = openings
        .into_iter()
        .zip(leaves)
        .filter(|(o, _)| new_index[o.wall] != usize::MAX)
        .map(|(mut o, l)| {
            o.wall = new_index[o.wall];
            (o, l)
        })
        .unzip();
    Doorways {
        walls: kept,
        openings,
        leaves,
    }
}
