//! What moved between the scans of a stop-and-scan survey: a person walking past one scan is a
//! streak in it, a wall of points that no other scan saw. Left in the map it is a thin tall
//! obstacle the robot collides with where the building is open, or a wall.
//!
//! The scans, placed in one frame with their sensor origins, vote on each other's points:
//!
//! 1. Seen by another scan: a point with another scan's point within `persist_m` is of
//!    something that stayed; it is kept. Where either scan's returns are sparse there (fewer
//!    than 8 of its own within `persist_m`), within twice that: glass, which a beam passes
//!    through, stays for this reason; it returns a few of the beams of every scan that looks
//!    at it, too few to lie within `persist_m` of each other.
//! 2. Seen through by another scan: every other scan looks along the direction of the point
//!    from its own sensor in its range image (bins of `bin_deg` in azimuth and elevation, the
//!    nearest return of each). If the bin of the point and each of its eight neighbours with a
//!    return hold returns farther than the point by `margin_m + margin_per_m` x its range (at
//!    least `min_bins_seen` of the nine with a return), that scan saw the space where the point
//!    is empty: the thing was not there when it looked.
//!
//! A point seen by no other scan and seen through by one is a transient: dropped. So is a
//! point of dense returns (not glass) seen by one other scan only and seen through by two
//! more ([`OUTVOTE`]): two people who crossed one spot in two scans leave streaks that see
//! each other (13 of the 30 phantoms taller than 1 m on the bench's garages, seeds 1-10), and
//! the scans that saw the spot empty outvote them. One scan seeing through is not enough
//! against one that saw the point: on a short real sequence (3DTK's corridor, 3 scans) most
//! surfaces are seen by one other scan only, and the third saw past about 3000 returns of a
//! real wall's lower face (its registration's tilt, or the wall changed between the scans:
//! not traced). The nine bins must all agree so that a point at a depth edge (where the bin
//! holds the foreground and its neighbours the background) or on a surface seen at grazing
//! incidence by the other scan is never taken for one; a thing that only one scan could see
//! (behind a corner, under a table) is kept because nobody saw through it.
//!
//! 3. The rest of a transient: a return of the same scan within `persist_m` of a dropped
//!    one, with no other scan's return within `same_surface_m`, goes with it (see `rest`): a
//!    person brushing past a staircase's side face, or a return a little over the floor that
//!    no ray could see past, is neither vouched for nor seen through by the first two votes.

mod range_image;
mod rest;
mod voxels;

use cloud::{check_range, PointCloud};
use range_image::RangeImage;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use voxels::{Vouch, Voxels};

/// Scans that must see through a point which one other scan saw (its returns dense) to drop it
/// (see the module docs): more than the one that saw it, so that a surface of a short sequence
/// which one scan saw and one saw past (a registration's tilt) stays.
const OUTVOTE: usize = 2;

/// Removal of moving things seen by one scan (`[transients]` of the configuration).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TransientConfig {
    /// Whether the scans of a sequence vote their transients out when they are merged.
    pub enabled: bool,
    /// Another scan's point within this distance sees the same thing (twice it where the
    /// returns are sparse, see the module docs). 0.15 m: the registration's residue (1-3 cm)
    /// and a 0.5 degree laser's sample spacing out to ~15 m are well within it; a person walks
    /// 0.15 m in 0.1 s.
    pub persist_m: f64,
    /// The range images' bins, degrees in azimuth and elevation: at least a rotating laser's
    /// angular step (0.25-1 degree), so that most bins hold a return (with finer bins than the
    /// sampling, too few of the nine round a point hold one and nothing is ever seen through).
    pub bin_deg: f64,
    /// Another scan's returns must lie this far beyond the point at least ...
    pub margin_m: f64,
    /// ... plus this much per metre of the point's range from that scan (range noise and the
    /// bin's width grow with range).
    pub margin_per_m: f64,
    /// Fewest of the nine bins around the point's direction that hold a return.
    pub min_bins_seen: usize,
    /// A return of a transient's own scan within `persist_m` of it goes with it unless another
    /// scan left a return within this distance (the surface that scan saw passes there; see
    /// the module docs). 0.05 m: the registration's residue and the range noise.
    pub same_surface_m: f64,
}

impl Default for TransientConfig {
    fn default() -> Self {
        TransientConfig {
            enabled: true,
            persist_m: 0.15,
            bin_deg: 1.0,
            margin_m: 0.15,
            margin_per_m: 0.02,
            min_bins_seen: 5,
            same_surface_m: 0.05,
        }
    }
}

impl TransientConfig {
    /// Checks the parameters.
    pub fn validate(&self) -> Result<(), cloud::InvalidParameter> {
        check_range("persist_m", self.persist_m, 0.01, 2.0, "within 0.01..2 m")?;
        check_range(
            "bin_deg",
            self.bin_deg,
            0.05,
            10.0,
            "within 0.05..10 degrees",
        )?;
        check_range("margin_m", self.margin_m, 0.0, 5.0, "within 0..5 m")?;
        check_range("margin_per_m", self.margin_per_m, 0.0, 1.0, "within 0..1")?;
        check_range(
            "min_bins_seen",
            self.min_bins_seen as f64,
            1.0,
            9.0,
            "1..9 of the nine bins",
        )?;
        check_range(
            "same_surface_m",
            self.same_surface_m,
            0.01,
            self.persist_m,
            "within 0.01 m..persist_m",
        )?;
        Ok(())
    }
}

/// Per scan, the indices (ascending) of its transient points (see the module docs). `scans`
/// are placed in one frame, each with its `sensor_origin` in that frame; fewer than two scans,
/// or removal disabled, find none.
pub fn find_transients(scans: &[PointCloud], c: &TransientConfig) -> Vec<Vec<usize>> {
    if !c.enabled || scans.len() < 2 {
        return vec![Vec::new(); scans.len()];
    }
    // 1. Every scan's points by voxel of `persist_m`.
    let voxels = Voxels::build(scans, c.persist_m as f32);
    // 2. Each scan's range image around its sensor.
    let images: Vec<RangeImage> = scans
        .par_iter()
        .map(|s| RangeImage::build(s, c.bin_deg))
        .collect();
    // 3. The points seen by no other scan that another scan saw through.
    scans
        .par_iter()
        .enumerate()
        .map(|(k, scan)| {
            let seen_through: Vec<usize> = (0..scan.len())
                .filter(|&i| {
                    let p = scan.points[i];
                    if !p.is_finite() {
                        return false;
                    }
                    let through = |j: usize| j != k && images[j].sees_through(p, c);
                    match voxels.vouchers(p, k) {
                        Vouch::None => (0..images.len()).any(through),
                        Vouch::One(v) => {
                            let others = (0..images.len()).filter(|&j| j != v as usize);
                            others.filter(|&j| through(j)).nth(OUTVOTE - 1).is_some()
                        }
                        Vouch::Many => false,
                    }
                })
                .collect();
            // 4. The rest of each transient (see `rest`).
            let (reach, surface) = (c.persist_m as f32, c.same_surface_m as f32);
            let rest = rest::rest_of_transients(scan, k, &seen_through, &voxels, reach, surface);
            let mut all = seen_through;
            all.extend(rest);
            all.sort_unstable();
            all
        })
        .collect()
}

/// Drops each scan's transients ([`find_transients`]) and returns the scans with how many
/// points each lost.
pub fn drop_transients(
    scans: Vec<PointCloud>,
    c: &TransientConfig,
) -> (Vec<PointCloud>, Vec<usize>) {
    let found = find_transients(&scans, c);
    let counts = found.iter().map(Vec::len).collect();
    let kept = scans
        .into_iter()
        .zip(&found)
        .map(|(scan, gone)| {
            if gone.is_empty() {
                return scan;
            }
            let mut drop = gone.iter().peekable();
            let keep: Vec<usize> = (0..scan.len())
                .filter(|i| {
                    if drop.peek() == Some(&i) {
                        drop.next();
                        false
                    } else {
                        true
                    }
                })
                .collect();
            scan.select(&keep)
        })
        .collect();
    (kept, counts)
}

#[cfg(test)]
mod tests;
