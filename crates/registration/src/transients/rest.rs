//! The rest of a transient (see the `transients` module): the returns of a moving thing that
//! the first votes keep, vouched for by a surface close by that other scans saw, or never seen
//! through.
//!
//! The votes of [`super::find_transients`] keep a point that another scan's point lies within
//! `persist_m` of, and a point no other scan saw past. A person walking close by a staircase's
//! side face leaves the streak's returns within 15 cm of the face (the face vouches for them),
//! and the returns a little over the floor (another scan's ray through them meets the floor
//! just beyond, within the margin): office-465 of seeds 461-465, 343 returns of a person 0.1-0.6
//! m high beside a flight's lowest steps, which set its levels at a 0.22 m rise for 0.16 m and
//! read both flights of the staircase as 3 steps for 4.
//!
//! Such a return lies next to the streak's dropped returns in its own scan, and no other scan
//! saw a surface through it: the nearest return another scan left lies farther than
//! `same_surface_m` (the registration's residue and the range noise, a few centimetres). A
//! return of the face itself, or of the floor under the person's feet, has another scan's
//! return within that distance and stays.

use super::voxels::Voxels;
use cloud::PointCloud;
use glam::Vec3;
use std::collections::{HashMap, HashSet};

/// Scan `k`'s returns (indices, ascending, none of `gone`) within `reach_m` of one of its
/// transient returns `gone` (ascending) that no other scan left a return within
/// `same_surface_m` of.
pub(crate) fn rest_of_transients(
    scan: &PointCloud,
    k: usize,
    gone: &[usize],
    voxels: &Voxels,
    reach_m: f32,
    same_surface_m: f32,
) -> Vec<usize> {
    if gone.is_empty() {
        return Vec::new();
    }
    // 1. The transient returns by cell of `reach_m`.
    let cell = |p: Vec3| (p / reach_m).floor().as_ivec3().to_array();
    let mut dropped: HashMap<[i32; 3], Vec<Vec3>> = HashMap::new();
    for &i in gone {
        let p = scan.points[i];
        dropped.entry(cell(p)).or_default().push(p);
    }
    // (the cells next to them: most returns are in none, and one look settles them)
    let near: HashSet<[i32; 3]> = dropped
        .keys()
        .flat_map(|&[x, y, z]| {
            (-1..=1).flat_map(move |dx| {
                (-1..=1).flat_map(move |dy| (-1..=1).map(move |dz| [x + dx, y + dy, z + dz]))
            })
        })
        .collect();
    let next_to_dropped = |p: Vec3| {
        let [x, y, z] = cell(p);
        if !near.contains(&[x, y, z]) {
            return false;
        }
        (-1..=1).any(|dx| {
            (-1..=1).any(|dy| {
                (-1..=1).any(|dz| {
                    dropped.get(&[x + dx, y + dy, z + dz]).is_some_and(|qs| {
                        qs.iter()
                            .any(|q| q.distance_squared(p) <= reach_m * reach_m)
                    })
                })
            })
        })
    };
    // 2. The other returns next to them that no other scan saw a surface through.
    let mut gone = gone.iter().peekable();
    (0..scan.len())
        .filter(|&i| {
            if gone.peek() == Some(&&i) {
                gone.next();
                return false;
            }
            let p = scan.points[i];
            p.is_finite()
                && next_to_dropped(p)
                && !voxels.seen_by_other_within(p, k, same_surface_m)
        })
        .collect()
}
