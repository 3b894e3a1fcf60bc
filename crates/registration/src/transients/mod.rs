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

mod range_image;
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
            (0..scan.len())
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
                .collect()
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
mod tests {
    use super::*;
    use glam::Vec3;

    /// A vertical cylinder standing on the floor: centre (XY), radius, height.
    type Cylinder = (Vec3, f32, f32);

    /// A room's walls (a 10 m square, 3 m high) sampled from `origin` along a regular angular
    /// grid, as a rotating laser would: every beam hits the nearest wall, or a cylinder first.
    fn scan_of_room(origin: Vec3, things: &[Cylinder]) -> PointCloud {
        let mut points = Vec::new();
        let step = 0.4f32.to_radians();
        for i in 0..900 {
            let az = i as f32 * step;
            for j in 0..200 {
                let el = -40f32.to_radians() + j as f32 * step;
                let d = Vec3::new(az.cos() * el.cos(), az.sin() * el.cos(), el.sin());
                let mut t = f32::INFINITY;
                for (axis, lo, hi) in [(0, -5.0f32, 5.0f32), (1, -5.0, 5.0), (2, 0.0, 3.0)] {
                    for plane in [lo, hi] {
                        let s = (plane - origin[axis]) / d[axis];
                        if s > 0.0 {
                            t = t.min(s);
                        }
                    }
                }
                for &(c, radius, height) in things {
                    let o = origin - c;
                    let a = d.x * d.x + d.y * d.y;
                    let b = 2.0 * (o.x * d.x + o.y * d.y);
                    let cc = o.x * o.x + o.y * o.y - radius * radius;
                    let disc = b * b - 4.0 * a * cc;
                    if disc >= 0.0 && a > 0.0 {
                        let s = (-b - disc.sqrt()) / (2.0 * a);
                        let z = origin.z + s * d.z;
                        if s > 0.0 && s < t && (0.0..height).contains(&z) {
                            t = s;
                        }
                    }
                }
                points.push(origin + d * t);
            }
        }
        let mut cloud = PointCloud::from_points(points);
        cloud.sensor_origin = origin;
        cloud
    }

    /// Points within `r` of the vertical axis through `c`, clear of the floor (whose points
    /// both scans see: a person's feet stay, the voxels round the floor are shared) and under
    /// the ceiling.
    fn near(points: &[Vec3], c: Vec3, r: f32) -> usize {
        points
            .iter()
            .filter(|p| {
                p.z > 0.45 && p.z < 2.5 && Vec3::new(p.x - c.x, p.y - c.y, 0.0).length() < r
            })
            .count()
    }

    #[test]
    fn a_person_seen_by_one_scan_is_dropped_and_a_pillar_seen_by_two_is_kept() {
        let (a0, b0) = (Vec3::new(-2.0, 0.0, 0.5), Vec3::new(2.0, -1.0, 0.5));
        let person = (Vec3::new(0.0, 2.0, 0.0), 0.25, 1.75);
        let pillar = (Vec3::new(0.5, -3.0, 0.0), 0.3, 3.0);
        // Scan a sees the person and the pillar; scan b sees the pillar and, where the person
        // stood, the wall behind.
        let a = scan_of_room(a0, &[person, pillar]);
        let b = scan_of_room(b0, &[pillar]);
        let on_person = near(&a.points, person.0, 0.3);
        assert!(on_person > 100, "{on_person}");
        let c = TransientConfig::default();
        let found = find_transients(&[a.clone(), b.clone()], &c);
        // Nothing else goes: none of the walls, floor and ceiling both scans saw.
        let elsewhere = found[0]
            .iter()
            .filter(|&&i| {
                let p = a.points[i];
                Vec3::new(p.x - person.0.x, p.y - person.0.y, 0.0).length() > 0.35
            })
            .count();
        assert_eq!(elsewhere, 0, "{} dropped", found[0].len());
        assert!(found[1].is_empty(), "{}", found[1].len());
        let (kept, _) = drop_transients(vec![a, b], &c);
        assert_eq!(near(&kept[0].points, person.0, 0.3), 0);
        for scan in &kept {
            assert!(near(&scan.points, pillar.0, 0.35) > 100);
        }
        // Off: nothing is dropped.
        let off = TransientConfig {
            enabled: false,
            ..c
        };
        let a = scan_of_room(a0, &[person, pillar]);
        let b = scan_of_room(b0, &[pillar]);
        assert!(find_transients(&[a, b], &off).iter().all(Vec::is_empty));
    }

    #[test]
    fn two_people_at_one_spot_in_two_scans_go_where_two_others_saw_it_empty() {
        // Regression (garage-9, seeds 1-10): two people crossed one spot in scans 21 and 22;
        // each streak was "seen by another scan" (the other's), so both stayed, a phantom
        // obstacle 1.76 m tall. Here scans a and b each see a person there, c and d see the
        // spot empty.
        let person = (Vec3::new(0.0, 2.0, 0.0), 0.25, 1.75);
        let (a0, b0) = (Vec3::new(-2.0, 0.0, 0.5), Vec3::new(1.5, 0.0, 0.5));
        let (c0, d0) = (Vec3::new(0.5, -2.5, 0.5), Vec3::new(-3.0, -3.0, 0.5));
        let a = scan_of_room(a0, &[person]);
        let b = scan_of_room(b0, &[person]);
        let (c, d) = (scan_of_room(c0, &[]), scan_of_room(d0, &[]));
        let seen = [
            near(&a.points, person.0, 0.3),
            near(&b.points, person.0, 0.3),
        ];
        let cfg = TransientConfig::default();
        let scans = vec![a.clone(), b.clone(), c.clone(), d];
        // Nothing else goes: the room's every point is seen by three other scans.
        let found = find_transients(&scans, &cfg);
        for (scan, gone) in scans.iter().zip(&found) {
            let elsewhere = gone.iter().filter(|&&i| {
                let p = scan.points[i];
                Vec3::new(p.x - person.0.x, p.y - person.0.y, 0.0).length() > 0.35
            });
            assert_eq!(elsewhere.count(), 0, "{} dropped", gone.len());
        }
        let (kept, _) = drop_transients(scans, &cfg);
        for (scan, seen) in kept.iter().zip(seen) {
            let left = near(&scan.points, person.0, 0.3);
            assert!(seen > 100 && left * 10 < seen, "{left} of {seen} left");
        }
        // With only c to see the spot empty, one scan against one that saw each streak, the
        // part each streak shares with the other stays (a short sequence's real surface, seen
        // by one other scan and seen past by a third where the registration tilts it, must).
        let (kept, _) = drop_transients(vec![a, b, c], &cfg);
        let left = near(&kept[0].points, person.0, 0.3);
        assert!(left * 4 > seen[0], "{left} of {} left", seen[0]);
    }

    #[test]
    fn a_persons_legs_go_with_the_person_down_to_the_floor() {
        // Regression (garage-64, seeds 61-65): the floor both scans saw lies within reach of
        // a person's lowest returns, which stayed as a kerb-high obstacle.
        let (a0, b0) = (Vec3::new(-2.0, 0.0, 0.5), Vec3::new(2.0, -1.0, 0.5));
        let person = (Vec3::new(0.0, 2.0, 0.0), 0.25, 1.75);
        let a = scan_of_room(a0, &[person]);
        let b = scan_of_room(b0, &[]);
        let legs = |points: &[Vec3]| {
            points
                .iter()
                .filter(|p| {
                    (0.1..0.45).contains(&p.z)
                        && Vec3::new(p.x - person.0.x, p.y - person.0.y, 0.0).length() < 0.3
                })
                .count()
        };
        let seen = legs(&a.points);
        let (kept, _) = drop_transients(vec![a, b], &TransientConfig::default());
        let left = legs(&kept[0].points);
        assert!(seen > 20 && left * 10 < seen, "{left} of {seen} left");
    }

    #[test]
    fn a_thing_hidden_from_the_other_scan_is_kept() {
        // The thing stands where scan b's view is blocked by a wide pillar: b never saw the
        // space it occupies, so it stays although b saw nothing there.
        let (a0, b0) = (Vec3::new(-3.0, 2.0, 0.5), Vec3::new(3.0, 3.0, 0.5));
        let thing = (Vec3::new(-3.0, -3.0, 0.0), 0.3, 1.0);
        let pillar = (Vec3::new(0.0, 0.0, 0.0), 0.8, 3.0);
        let a = scan_of_room(a0, &[thing, pillar]);
        let b = scan_of_room(b0, &[pillar]);
        let seen = near(&a.points, thing.0, 0.35);
        assert!(seen > 100, "{seen}");
        let found = find_transients(&[a.clone(), b], &TransientConfig::default());
        let gone = found[0]
            .iter()
            .filter(|&&i| near(&[a.points[i]], thing.0, 0.35) == 1)
            .count();
        assert_eq!(gone, 0, "{gone} of the thing's {seen} points dropped");
        // Where b does see the thing's place (no pillar), it is dropped.
        let b = scan_of_room(b0, &[]);
        let found = find_transients(&[a.clone(), b], &TransientConfig::default());
        let gone = found[0]
            .iter()
            .filter(|&&i| near(&[a.points[i]], thing.0, 0.35) == 1)
            .count();
        assert!(gone > seen / 2, "{gone} of {seen}");
    }

    #[test]
    fn a_person_between_two_pillars_both_scans_saw_is_dropped() {
        // The person stands in the 0.6 m gap between two pillars, 5 cm from each: much of
        // what scan a (north) sees of them lies within two voxels' reach of the pillars'
        // sides that scan b (south) saw too, and b sees past where the person stood. (At
        // y 2.05 b's last points on the pillars' sides and a's on the person fall in
        // neighbouring 15 cm voxels, 0.15-0.35 m apart: a voxel test alone kept 31 %.)
        let (a0, b0) = (Vec3::new(0.0, 4.0, 0.5), Vec3::new(0.0, -1.0, 0.5));
        let pillars = [
            (Vec3::new(-0.6, 2.05, 0.0), 0.3, 3.0),
            (Vec3::new(0.6, 2.05, 0.0), 0.3, 3.0),
        ];
        let person = (Vec3::new(0.0, 2.05, 0.0), 0.25, 1.75);
        let a = scan_of_room(a0, &[pillars[0], pillars[1], person]);
        let b = scan_of_room(b0, &pillars);
        let on_person = near(&a.points, person.0, 0.27);
        let (kept, _) = drop_transients(vec![a, b], &TransientConfig::default());
        let left = near(&kept[0].points, person.0, 0.27);
        assert!(
            on_person > 100 && left * 4 < on_person,
            "{left} of {on_person} left"
        );
        // The pillars stay in both.
        for scan in &kept {
            for pillar in pillars {
                assert!(near(&scan.points, pillar.0, 0.35) > 100);
            }
        }
    }
}
