//! Obstacles, columns and beams: what occupies space and is none of the floor, ceiling, walls,
//! doors or stairs (the "the robot collides with what the scans saw").
//!
//! 1. Unexplained points: those no other entity labels (see `labels`), above the floor by
//!    `min_above_floor_m` and below the ceiling by `below_ceiling_m`, off the walls' slabs and
//!    the door leaves' and staircases' boxes (grown by `wall_margin_m`: the faces' noise; a
//!    leaf's free edge is the leaf, not a post in its doorway).
//! 2. Two height bands split at `head_height_m`: below it, what a person or robot runs into;
//!    above it, what they pass under. Each band's points go into an XY grid (`cell_m`); a cell
//!    with `min_cell_points` is occupied (one stray return is not). Occupied cells up to two
//!    cells apart form a cluster ([`cluster`]) if their tops (highest points) differ by at most
//!    `max_top_step_m`: a surface's top changes little from cell to cell, while where one thing
//!    stands beside another (a chair's seat by a desk, a car by a pillar, a duct under a beam)
//!    the top steps. Clusters meeting along more than one thing's side are one thing whose
//!    parts step by more than that (a boxy cabin over a car's body, [`junctions`]).
//!    Two things side by side joined by a few cells in the gap between them (mixed pixels,
//!    a registration's smear) are cut apart at the neck ([`necks`]); things of different
//!    heights side by side whose tops the mixed pixels between them join by small steps (a
//!    seat by a desk, two cabinets) are split where their levels meet along a short junction
//!    ([`levels`]). Specks strung onto a cluster by the mixed pixels between it and a neighbour
//!    are dropped from it ([`fringe`]), so that its box does not reach over the neighbour.
//!    What stands at the edge of a raised top, its top at the top's height (a chair's backrest
//!    against a desk's edge), is cut off the top where its cells' returns reach down to the
//!    floor and the top's hang in a slab ([`tops`]).
//! 3. A low cluster's top climbs through the points above head height in its cells while they
//!    follow each other within `max_vertical_gap_m` (a shelf taller than head height, a column
//!    up to the ceiling; not the beam over a car). The high points it climbed through are its
//!    own; the rest cluster as the high band.
//!    A high cluster filling little of its box, wider than a member is, may be a frame of
//!    beams and the ducts under them, joined where they cross: split into its members
//!    ([`frames`]).
//!    A low cluster standing from the floor to the ceiling and longer than a column is across
//!    is cut at the gaps its returns show (a row of hollow pillars whose gaps the mixed pixels
//!    fill, [`pillar_rows`]), each part fitted on its own.
//! 4. Each cluster's box: the smallest-area rectangle around its footprint's convex hull
//!    ([`fit`]; along a wall instead if that is at most 15 % larger), z from its points; a
//!    bottom near the floor stands on it.
//! 5. Put together ([`merge`]): a low cluster lying mostly inside a larger one's box, at heights
//!    within `max_vertical_gap_m` of it (a chair's backrest over its seat, a car's cabin over
//!    its body), and, if lower or if standing beside it and higher (a cabinet behind a desk),
//!    inside its footprint's hull, is part of it; overhead pieces
//!    continuing each other along one line across gaps up to `column_max_across_m` (a duct cut
//!    where beams cross it) are one, and what lies within such a line's box at its height is
//!    its patches; thin clusters along a wall's face are its residue,
//!    dropped ([`residue`]; not beyond another wall crossing its line);
//!    two thin clusters side by side a thing's depth apart, of one height, are its faces (a
//!    seat seen along its front and back edges; or a backrest cut off a desk and the seat in
//!    front of it, [`faces`]); a thin cluster longer than a seat standing in line with a
//!    block's side, lower than its top, is that side seen past the top that hid it (a car's
//!    body side along and past its cabin, [`block_sides`]); a standing cluster along a wall
//!    whose floor between it and the wall was never seen (a cabinet seen from the room as its
//!    front face) reaches back to the wall ([`backing`]).
//! 6. Classes ([`classify`]): a low cluster standing on the floor, reaching the ceiling and at
//!    most `column_max_across_m` across is a `column`; a high cluster at least
//!    `beam_min_length_m` long and twice as long as wide is a `beam` (its bottom is above head
//!    height by construction: the robot passes under it); anything else is an `obstacle`.
//! 7. A thin, long cluster at least `partition_min_height_m` tall whose face is seen from the floor
//!    up to its top (where its face ends along most of it, not a few returns over an end) along
//!    most of its length, and divides space ([`divides`]), is a partial-height `wall`
//!    ([`partitions`]): a partition under the projection band the wall stage looks at. A cluster
//!    too thick for one may be one with a desk or a chair against it: the thin slab of its returns
//!    holding the most of them is looked at so ([`slabs`]), and what lies beside the slab is fitted
//!    again as obstacles. Thin pieces standing on one line across short gaps are looked at as one
//!    partition seen in pieces ([`pieces`]), a partition found on its own among them; a piece in a
//!    partition's line up to a cell thicker (a glass pane's) continues it ([`continuations`]). An
//!    end within the margin left round a wall's faces (and a cell), running square into it, meets
//!    its face ([`wall_ends`]). Thin clusters along a partition found here (a glass one's returns
//!    above head height) are its residue, dropped ([`residue`]).

mod backing;
mod block_sides;
mod classify;
mod cluster;
mod config;
mod continuations;
mod divides;
mod faces;
mod fit;
mod frames;
mod fringe;
mod junctions;
mod keep_out;

pub(crate) use cluster::{components, BandGrid};
pub use fit::intersection_area as convex_intersection_area;
pub(crate) use fit::{convex_hull, min_area_rect, rect_corners};
pub(crate) use keep_out::{exclude_boxes, wall_cells};
mod levels;
mod merge;
mod necks;
mod overlaps;
mod partitions;
mod pieces;
mod pillar_rows;
mod residue;
mod slabs;
mod tops;
mod wall_ends;

use crate::image_frame::ImageFrame;
use crate::map::OrientedBox;
use crate::points::quantile;
use crate::walls::WallFit;
use backing::{back_onto_walls, floor_seen};
use block_sides::join_block_sides;
use classify::{classify, fit_cluster};
use cloud::EntityClass;
pub use config::ObstacleConfig;
use continuations::continue_partitions;
use faces::join_faces;
use frames::{split_frame, MAX_FRAME_FILL, MIN_FRAME_ACROSS_M};
use fringe::without_fringe;
use glam::{DVec2, Vec3};
use junctions::join_meeting;
use levels::split_levels;
use merge::{absorb_overhead_pieces, absorb_parts, join_collinear};
use necks::{split_at_gaps_in_returns, split_at_necks};
use partitions::classify_partition;
use pieces::join_partition_pieces;
use pillar_rows::{may_be_a_pillar_row, split_pillar_row};
use residue::{drop_partition_residue, drop_wall_slivers};
use tops::split_beside_tops;
use wall_ends::meet_walls;

/// A surface the laser saw of a thing is at least this large (m²): a seat 0.45 m square seen in
/// part, the front of a cabinet 0.35 m deep along 0.2-0.3 m. Smaller groups of cells are edges,
/// a backrest's top or mixed pixels (the levels' cores, [`levels`], and the surfaces a
/// cluster's fringe hangs off, [`fringe`]).
const MIN_SURFACE_M2: f64 = 0.06;

/// [`MIN_SURFACE_M2`] in cells `cell_m` wide.
fn min_surface_cells(cell_m: f64) -> usize {
    (MIN_SURFACE_M2 / (cell_m * cell_m)).ceil() as usize
}

/// An obstacle, column or beam found in the cloud.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct DetectedObstacle {
    pub class: EntityClass,
    /// Footprint centre, first axis (the longer side) and full size along and across it.
    pub center: DVec2,
    pub dir: DVec2,
    pub size: [f64; 2],
    pub z_range: (f64, f64),
    pub hull: Vec<DVec2>,
    pub fill: f64,
    pub support: u64,
    /// Found in the band above head height.
    pub overhead: bool,
    /// Cut off the edge of a raised top: something standing beside a table ([`tops`]).
    pub beside_top: bool,
    pub rules: Vec<String>,
}

/// Where the stage looks: floor and ceiling heights, the image's area and the walls.
pub(crate) struct ObstacleScene<'a> {
    pub points: &'a [Vec3],
    /// Per point: labelled by another entity.
    pub explained: &'a [bool],
    pub floor: f64,
    pub ceiling: f64,
    pub image: &'a ImageFrame,
    pub walls: &'a [WallFit],
    /// Boxes of entities that are no obstacle: door leaves and staircases.
    pub keep_out: &'a [OrientedBox],
}

/// What the partition rules look at (step 7 on): the scene, its low and high band grids, the
/// floor seen per image cell, the image's frame and the stage's configuration.
#[derive(Clone, Copy)]
pub(crate) struct PartitionScene<'a> {
    pub sc: &'a ObstacleScene<'a>,
    pub grids: [&'a BandGrid; 2],
    pub floor_seen: &'a [bool],
    pub frame: &'a ImageFrame,
    pub c: &'a ObstacleConfig,
}

/// Finds the obstacles, columns and beams (see the module docs).
pub(crate) fn find_obstacles(
    sc: &ObstacleScene,
    c: &ObstacleConfig,
    max_pixels: u64,
) -> Vec<DetectedObstacle> {
    // The grid covers the projection image's area at `cell_m`.
    let frame = sc.image.at_cell(c.cell_m, max_pixels);
    // 1. The unexplained points of each band, by cell.
    let mut excluded = wall_cells(&frame, sc.walls, c.wall_margin_m);
    exclude_boxes(&frame, sc.keep_out, c.wall_margin_m, &mut excluded);
    let (z_lo, z_head, z_hi) = (
        sc.floor + c.min_above_floor_m,
        sc.floor + c.head_height_m,
        sc.ceiling - c.below_ceiling_m,
    );
    let mut cell_of = vec![u32::MAX; sc.points.len()];
    let (mut low, mut high) = (Vec::new(), Vec::new());
    for (i, p) in sc.points.iter().enumerate() {
        let z = p.z as f64;
        if sc.explained[i] || z < z_lo || z > z_hi {
            continue;
        }
        let Some((col, row)) = frame.pixel_of(p.x as f64, p.y as f64) else {
            continue;
        };
        let k = row as usize * frame.width_px as usize + col as usize;
        if excluded[k] {
            continue;
        }
        cell_of[i] = k as u32;
        if z < z_head {
            low.push(i as u32);
        } else {
            high.push(i as u32);
        }
    }
    let wall_dirs: Vec<DVec2> = sc.walls.iter().map(|w| w.line.dir).collect();
    let low_grid = BandGrid::new(&frame, &low, &cell_of);
    let high_grid = BandGrid::new(&frame, &high, &cell_of);
    let (w, h) = (low_grid.width, low_grid.height);
    let z_of = |i: u32| sc.points[i as usize].z;
    let step = c.max_top_step_m as f32;
    let mut consumed = vec![false; sc.points.len()];
    let mut out = Vec::new();
    // 2-3. Low clusters, their tops climbing into the high band.
    let tops = low_grid.tops(z_of);
    let occupied = |k: usize| low_grid.count(k) >= c.min_cell_points;
    let joined_tops = components(w, h, 2, occupied, |a, b| (tops[a] - tops[b]).abs() <= step);
    let low_clusters = join_meeting(joined_tops, &frame)
        .into_iter()
        .flat_map(|cells| split_at_necks(cells, &frame))
        .flat_map(|cells| split_at_gaps_in_returns(cells, &frame, &|k| low_grid.count(k)))
        .flat_map(|cells| split_levels(cells, &tops, &frame, c.max_top_step_m))
        .map(|cells| without_fringe(cells, w, frame.resolution_m))
        .flat_map(|cells| {
            split_beside_tops(cells, &low_grid, (z_of, sc.floor), &frame, &wall_dirs)
        });
    let mut fit_low = |cells: &[usize]| -> Option<DetectedObstacle> {
        let members: Vec<u32> = cells
            .iter()
            .flat_map(|&k| low_grid.points(k).iter().copied())
            .collect();
        if members.len() < c.min_points {
            return None;
        }
        let mut zs: Vec<f64> = members
            .iter()
            .map(|&i| sc.points[i as usize].z as f64)
            .collect();
        let mut top = zs.iter().copied().fold(f64::MIN, f64::max);
        let mut above: Vec<(f64, u32)> = cells
            .iter()
            .flat_map(|&k| high_grid.points(k).iter())
            .map(|&i| (sc.points[i as usize].z as f64, i))
            .collect();
        above.sort_by(|a, b| a.0.total_cmp(&b.0));
        for &(z, i) in &above {
            if z - top > c.max_vertical_gap_m {
                break;
            }
            top = top.max(z);
            consumed[i as usize] = true;
        }
        // The footprint is the low points' (the cells of a column also hold the beam it
        // carries); the climbed points are labelled by the box.
        let bottom = quantile(&mut zs, 0.01).unwrap_or(top);
        fit_cluster(sc, &members, cells.len(), (bottom, top), false, &frame, c)
    };
    for part in low_clusters {
        let cells = part.cells;
        let Some(mut o) = fit_low(&cells) else {
            continue;
        };
        o.beside_top = part.beside_top;
        // A row of pillars is its pillars (see `pillar_rows`), each fitted on its own.
        let pillars = may_be_a_pillar_row(&o, sc.floor, sc.ceiling, c)
            .then(|| split_pillar_row(cells, &low_grid, &frame))
            .filter(|parts| parts.len() > 1);
        match pillars {
            Some(parts) => out.extend(parts.iter().filter_map(|p| fit_low(p))),
            None => out.push(o),
        }
    }
    // 3. High clusters: what is left above head height. Cells a column climbed through still
    //    connect (a beam carried by pillars is one beam), but their points are the column's.
    let tops = high_grid.tops(z_of);
    let occupied = |k: usize| high_grid.count(k) >= c.min_cell_points;
    let fit_high = |cells: &[usize]| -> Option<DetectedObstacle> {
        let members: Vec<u32> = cells
            .iter()
            .flat_map(|&k| high_grid.points(k).iter().copied())
            .filter(|&i| !consumed[i as usize])
            .collect();
        if members.len() < c.min_points {
            return None;
        }
        let mut zs: Vec<f64> = members
            .iter()
            .map(|&i| sc.points[i as usize].z as f64)
            .collect();
        let bottom = quantile(&mut zs, 0.02).unwrap_or(z_head);
        let top = zs.iter().copied().fold(f64::MIN, f64::max);
        fit_cluster(sc, &members, cells.len(), (bottom, top), true, &frame, c)
    };
    for cells in components(w, h, 2, occupied, |a, b| (tops[a] - tops[b]).abs() <= step) {
        let Some(o) = fit_high(&cells) else {
            continue;
        };
        // A frame of beams and the ducts under them is its members (see `frames`).
        let frame_members = (o.fill <= MAX_FRAME_FILL && o.size[1] >= MIN_FRAME_ACROSS_M)
            .then(|| split_frame(&cells, o.dir, &tops, &frame))
            .flatten();
        match frame_members {
            Some(groups) => out.extend(groups.iter().filter_map(|g| fit_high(g))),
            None => out.push(o),
        }
    }
    // 5-6. Put together, then classed.
    let out = absorb_parts(out, frame.resolution_m, c);
    let out = join_collinear(out, c.column_max_across_m);
    let out = absorb_overhead_pieces(out, frame.resolution_m);
    let out = drop_wall_slivers(
        out,
        sc.walls,
        c.sliver_max_across_m,
        c.wall_margin_m + c.sliver_max_across_m,
    );
    let out = join_faces(out, c);
    let mut out = join_block_sides(out, frame.resolution_m, c);
    let seen = floor_seen(&frame, sc.points, sc.floor, c.min_above_floor_m);
    back_onto_walls(&mut out, sc.walls, &frame, &seen, sc.floor);
    let ps = PartitionScene {
        sc,
        grids: [&low_grid, &high_grid],
        floor_seen: &seen,
        frame: &frame,
        c,
    };
    let mut stood_against = Vec::new();
    for o in &mut out {
        classify(o, sc.floor, sc.ceiling, frame.resolution_m, c);
        // 7. A thin slab standing on the floor along its length: a partial-height wall (and
        //    what stands against it, fitted on its own).
        stood_against.extend(classify_partition(o, ps));
    }
    out.extend(stood_against);
    // A partition seen in pieces along one line is one wall.
    let out = join_partition_pieces(out, ps);
    // A thin piece in a partition's line, a cell thicker at most (a glass pane's), continues it.
    let out = continue_partitions(out, ps);
    // Two partitions overlapping along one line are one found twice.
    let mut out = overlaps::join_overlapping_partitions(out, ps);
    // A partition ending within the margin left round a wall's face meets it there.
    meet_walls(&mut out, sc.walls, c);
    // What a partition found here left along its top is its residue.
    drop_partition_residue(
        out,
        c.sliver_max_across_m,
        c.wall_margin_m + c.sliver_max_across_m,
    )
}

#[cfg(test)]
mod fixtures;
#[cfg(test)]
pub(crate) use fixtures::{
    test_car_top, test_cluster, test_grid, test_points, test_scene, test_shifted_frame,
};
