//! Staircases (paper, Fig. 6: "the set of parallel lines in the same short distance between
//! each other can be a projection of stairs"; each step is "above & parallel" to the previous).
//!
//! A laser mounted below the upper treads sees a staircase as risers (short parallel lines
//! across it at equal spacing) and side faces with a stepped top edge. Both show in a height
//! map (`cell_m` pixels): each pixel's highest point between the floor and `max_height_m`, wall
//! slabs left out. Pixels within two pixels of each other form blobs (sparse scans leave gaps);
//! where only mixed pixels join a blob's surfaces (a chair in front of a flight's side face),
//! each surface is a part of its own (see `parts`).
//! For each part and each candidate direction of ascent (the walls' directions and normals, and
//! the part's own axes), the profile along the direction is examined:
//!
//! - levels: the highest point per 1 cm along the direction, kept as a running maximum from
//!   the foot (a few strays higher than a rise just in front of the first riser, a person
//!   walking past, are no part of the flight, nor is a spike narrower than a tread standing
//!   more than a rise over the profile either side of it: a person crossing a side face or
//!   standing on a landing), plateaus at the tops of the steps; the plateaus
//!   (histogram peaks) must sit at whole multiples of one rise above the floor, `min_steps` of
//!   them at least. The top level's index is the step count `n`;
//! - rise: the top level's height over `n` (the floor is at 0, and the top level, the landing,
//!   is the best sampled surface);
//! - run and start: the stair model `top(s) = rise * min(n, floor((s - s0) / run) + 1)` fitted
//!   by grid search to the profile (see `profile`);
//! - width: the extent across the direction (1 % to 99 % of the points); if that is under
//!   `min_width_m`, only a side face was seen and `default_width_m` is assumed, away from the
//!   side with floor in front of the face; landing: the top level's depth beyond one run.
//!
//! The direction with the most levels supported (then the best fit) wins; along a direction of
//! the part's own (no wall's), only where every level is seen (a staircase is built square to
//! the walls around it; furniture of assorted heights steps up along some direction with a
//! level missing). Along the direction chosen, every other step count in the range of rises is
//! fitted too, and wins where it fits better and finds as large a share of its levels (see
//! `profile::profile_other_count`); of the counts either side of the grid's, and the others
//! its levels point to, one replaces another only where it fits better and misses no more of
//! its levels (`profile`). A staircase must then
//! be one people could climb (clutter of boxes of assorted heights steps up and down too):
//! rise and run in the ranges of building codes, at least `min_steps` steps on the one rise,
//! every step supported by `min_step_points` points on its tread, riser or side face (and by a
//! `min_step_fill` fraction of what the local point density promises), at least
//! `min_width_m` wide; one seen from its side only gets `default_width_m` only where the floor
//! beside it is hidden (a staircase hides the floor under it; clutter beside a side face does
//! not), its returns on the steps lie on one vertical plane (clutter at step heights
//! along a line, such as a crate's edge and a person's streak crossing it, does not) and that
//! plane holds nothing more than a rise over its steps (a dark cabinet's front does: see
//! `taller_face`). A flight ends on a level: one whose top step has none beyond it, or is the
//! step let fall short of support, is read again without it (something standing at a
//! flight's top or over its landing, see `Search`).
//!
//! A flight whose top riser stands alone one run past its top step (its tread above the laser,
//! the side face unseen there, so the blobs part it from the flight) gets that step back (see
//! `extend`). An upper flight whose risers, seen from below with no tread or landing between
//! them, are parts of their own beyond a lone flight's top is read as the flight on its landing
//! (see `upper`). A flight from the floor where another flight's landing stands, climbing to
//! its top, is that landing's side face, dropped (see `landing_faces`).
//! A top landing seen from below, its side face parted from its blob (a person's shadow), is
//! read on past the blob while the highest return across it stays level (see `landing_reach`).
//!
//! The search over a part's directions is `search`. A part that shows no staircase, or one
//! climbing along a direction of the part's own, is tried again face by face: a flight seen
//! from its side only that clutter joins into one part with other things (a desk in front of
//! its side face, a person's streak of returns to parked cars) is still a straight, dense face
//! in plan (see `side_faces`), and a face's staircase square to the walls wins over the part's
//! own reading where it has as many flights and steps.

use crate::image_frame::ImageFrame;
mod climbs_on;
mod config;
mod directions;
mod envelope;
mod extend;
mod fit;
mod flights;
mod floor;
mod landing;
mod landing_faces;
mod landing_reach;
mod levels;
mod oblique_face;
mod parts;
mod plateau;
mod plausible;
mod profile;
mod risers;
mod search;
mod side_faces;
mod surface;
mod taller_face;
mod top_end;
mod upper;

use crate::scene::Scene;
use crate::walls::WallFit;
pub use config::StairsConfig;
use glam::DVec2;
use rayon::prelude::*;
use search::Search;

/// A staircase found in the cloud.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct DetectedStairs {
    pub steps: u32,
    pub rise: f64,
    pub run: f64,
    pub width: f64,
    pub dir: DVec2,
    /// Centre of the first step's front edge (XY).
    pub start: DVec2,
    pub landing: f64,
    /// Height of the flight's foot above the floor (0, or the landing it starts from).
    pub base: f64,
    pub support: u64,
    pub confidence: f64,
    /// Its top step is the one step let fall short of support (see `plausible`): what stands
    /// on a landing can read as one more step (see `Search`).
    pub top_short: bool,
    pub rules: Vec<String>,
}

impl DetectedStairs {
    /// A flight for tests: `steps` of `rise` x `run` climbing +X from `(start_x, 0)` on the
    /// floor, 1 m wide, a 1 m landing, every level seen.
    #[cfg(test)]
    pub(super) fn straight(start_x: f64, steps: u32, rise: f64, run: f64) -> DetectedStairs {
        DetectedStairs {
            steps,
            rise,
            run,
            width: 1.0,
            dir: DVec2::X,
            start: DVec2::new(start_x, 0.0),
            landing: 1.0,
            base: 0.0,
            support: 100,
            confidence: 1.0,
            top_short: false,
            rules: Vec::new(),
        }
    }

    /// Footprint of step `k` (1-based; `k = steps + 1` is the landing): along range from the start.
    pub fn step_range(&self, k: u32) -> (f64, f64) {
        let a = (k - 1) as f64 * self.run;
        if k > self.steps {
            (
                self.steps as f64 * self.run,
                self.steps as f64 * self.run + self.landing,
            )
        } else {
            (a, a + self.run)
        }
    }
}

/// Finds the staircases.
pub(crate) fn find_stairs(
    sc: &Scene,
    image: &ImageFrame,
    walls: &[WallFit],
    c: &StairsConfig,
    max_pixels: u64,
) -> Vec<DetectedStairs> {
    // The height map covers the projection image's area at its own resolution.
    let scale = image.resolution_m / c.cell_m;
    let own = ImageFrame {
        origin_m: image.origin_m,
        resolution_m: c.cell_m,
        width_px: (image.width_px as f64 * scale).ceil().max(1.0) as u32,
        height_px: (image.height_px as f64 * scale).ceil().max(1.0) as u32,
    };
    let frame = &if (own.len() as u64) <= max_pixels {
        own
    } else {
        *image
    };
    let (w, h) = (frame.width_px as usize, frame.height_px as usize);
    // Wall slabs (and a margin) are left out of the height map.
    let mut excluded = vec![false; w * h];
    for wall in walls {
        let half = wall.thickness / 2.0 + 0.05;
        let (a, b) = (wall.start(), wall.end());
        let lo = a.min(b) - DVec2::splat(half);
        let hi = a.max(b) + DVec2::splat(half);
        let Some((c0, c1, r0, r1)) = crate::image_frame::pixel_range(frame, lo, hi) else {
            continue;
        };
        for row in r0..=r1 {
            for col in c0..=c1 {
                let q = crate::image_frame::pixel_center(frame, col as f64, row as f64);
                let (s, d) = wall.line.coords(q);
                // (a pixel is left out if any of it is within the slab: its centre within half
                // a pixel more; the wall's face points, spread by the range noise, stay out)
                if d.abs() <= half + frame.resolution_m / 2.0
                    && s >= -0.05
                    && s <= wall.length + 0.05
                {
                    excluded[row * w + col] = true;
                }
            }
        }
    }
    let (z_lo, z_hi) = (
        sc.floor + 0.04,
        (sc.floor + c.max_height_m).min(sc.ceiling - 0.3),
    );
    let mut hmax = vec![f32::NAN; w * h];
    let mut pixel_of_point = vec![u32::MAX; sc.points.len()];
    for (i, p) in sc.points.iter().enumerate() {
        let z = p.z as f64;
        if z <= z_lo || z >= z_hi {
            continue;
        }
        let Some((col, row)) = frame.pixel_of(p.x as f64, p.y as f64) else {
            continue;
        };
        let k = row as usize * w + col as usize;
        if excluded[k] {
            continue;
        }
        pixel_of_point[i] = k as u32;
        if hmax[k].is_nan() || hmax[k] < p.z {
            hmax[k] = p.z;
        }
    }
    // Blobs: pixels of the height map within two pixels of each other.
    let mut blob_of = vec![u32::MAX; w * h];
    let mut blobs: Vec<Vec<usize>> = Vec::new();
    for start in 0..w * h {
        if hmax[start].is_nan() || blob_of[start] != u32::MAX {
            continue;
        }
        let id = blobs.len() as u32;
        blob_of[start] = id;
        let mut stack = vec![start];
        let mut pixels = Vec::new();
        while let Some(k) = stack.pop() {
            pixels.push(k);
            let (x, y) = ((k % w) as isize, (k / w) as isize);
            for dy in -2..=2isize {
                for dx in -2..=2isize {
                    let (nx, ny) = (x + dx, y + dy);
                    if nx < 0 || ny < 0 || nx >= w as isize || ny >= h as isize {
                        continue;
                    }
                    let n = ny as usize * w + nx as usize;
                    if blob_of[n] == u32::MAX && !hmax[n].is_nan() {
                        blob_of[n] = id;
                        stack.push(n);
                    }
                }
            }
        }
        blobs.push(pixels);
    }
    // The points of each blob.
    let mut blob_points: Vec<Vec<usize>> = vec![Vec::new(); blobs.len()];
    for (i, &px) in pixel_of_point.iter().enumerate() {
        if px != u32::MAX {
            blob_points[blob_of[px as usize] as usize].push(i);
        }
    }
    let families = directions::WallFamilies::new(walls.iter().map(|w| (w.start(), w.end())));
    // Each blob's parts (see `parts`): mixed pixels and stray returns are on no surface, and
    // are left out of the levels and the support (see `surface`); where only they join two
    // surfaces, each is a part of its own.
    let big_enough = |pixels: usize, members: usize| {
        pixels >= (c.min_steps as usize) * c.min_level_pixels && members >= 20
    };
    let blob_parts: Vec<parts::Part> = blobs
        .par_iter()
        .zip(&blob_points)
        .filter(|(pixels, members)| big_enough(pixels.len(), members.len()))
        .flat_map_iter(|(_, members)| {
            let on_surfaces = surface::on_surfaces(
                sc.points,
                members,
                c.min_surface_neighbours,
                c.surface_radius_spacings,
                3.0 * c.cell_m,
            );
            parts::parts(members, &on_surfaces, &pixel_of_point, w)
        })
        .collect();
    // Each part on its own (in parallel): the best profile over the candidate directions, then
    // the staircase if it is plausible.
    let mut found: Vec<Option<Vec<DetectedStairs>>> = blob_parts
        .par_iter()
        .map(|part| {
            if !big_enough(part.pixels, part.members.len()) {
                return None;
            }
            search_part(part, &families, sc, c)
        })
        .collect();
    // An upper flight parted from the flight below it (see `upper`).
    upper::join_upper_flights(&blob_parts, &mut found, sc, c);
    // A landing's side face read as a flight of its own (see `landing_faces`).
    landing_faces::drop_landing_faces(&mut found, c);
    // (the points the height map holds: in no wall's slab, between the floor and its top)
    let in_height_map = |i: usize| pixel_of_point[i] != u32::MAX;
    found
        .into_iter()
        .flatten()
        .flatten()
        .map(|mut st| {
            // A top riser the blobs parted from its flight (see `extend`).
            extend::extend_top(&mut st, sc, in_height_map, c);
            // Its landing read on past its blob (see `landing_reach`).
            landing_reach::reach_on(&mut st, sc, in_height_map, c);
            st
        })
        .collect()
}

/// A part's staircase: its best profile over the walls' directions (those of the walls
/// nearest it standing for those a few degrees off: see `directions`) and its own, then the
/// staircase if it is plausible.
fn search_part(
    part: &parts::Part,
    families: &directions::WallFamilies,
    sc: &Scene,
    c: &StairsConfig,
) -> Option<Vec<DetectedStairs>> {
    let all = part_points(sc, &part.members);
    let xy: Vec<DVec2> = all.iter().map(|p| p.0).collect();
    let centre = xy.iter().copied().sum::<DVec2>() / xy.len().max(1) as f64;
    let mut cands = families.directions_near(centre, c.snap_direction_deg);
    // (the first `walls_cands` are the walls' directions)
    let mut walls_cands = cands.len();
    if let Some((_, d)) = crate::points::fit_line(&xy) {
        // A staircase seen from its side only is one face, a line in plan: it climbs along
        // that line (its stepped top edge reads as a staircase along any direction not
        // square to it, with the run shortened).
        if across(&xy, d) < c.min_width_m {
            cands.retain(|e| {
                e.angle_to(d).abs().to_degrees() < c.snap_direction_deg
                    || e.angle_to(-d).abs().to_degrees() < c.snap_direction_deg
            });
        }
        walls_cands = cands.len();
        for cand in [d, d.perp(), -d, -d.perp()] {
            if !cands
                .iter()
                .any(|e| e.angle_to(cand).abs().to_degrees() < c.snap_direction_deg)
            {
                cands.push(cand);
            }
        }
    }
    // The part's returns on surfaces: its levels and support.
    let pts = part_points(sc, &part.surface);
    Search {
        pts: &pts,
        all: &all,
        cands: &cands,
        walls_cands,
        sc,
        c,
    }
    .stairs()
}

/// The points `(xy, height above the floor)` of these indices, highest first (a profile's
/// envelope takes each bin's points in that order, and binned in order they need no sorting
/// per bin).
fn part_points(sc: &Scene, indices: &[usize]) -> Vec<(DVec2, f64)> {
    let pts = indices
        .iter()
        .map(|&i| {
            let p = sc.points[i];
            (DVec2::new(p.x as f64, p.y as f64), p.z as f64 - sc.floor)
        })
        .collect();
    highest_first(pts)
}

/// The extent of points across a direction (1 % to 99 %).
fn across(xy: &[DVec2], dir: DVec2) -> f64 {
    let mut t: Vec<f64> = xy.iter().map(|q| dir.perp_dot(*q)).collect();
    let lo = crate::points::quantile(&mut t, 0.01).unwrap_or(0.0);
    crate::points::quantile(&mut t, 0.99).unwrap_or(0.0) - lo
}

/// The points `(xy, height)` sorted by height, highest first.
fn highest_first(mut pts: Vec<(DVec2, f64)>) -> Vec<(DVec2, f64)> {
    pts.sort_by(|a, b| b.1.total_cmp(&a.1));
    pts
}

#[cfg(test)]
mod landing_tests;
#[cfg(test)]
mod standing_tests;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod upper_tests;
