//! What moved between the scans of a stop-and-scan survey: a person walking past one scan is a
//! streak in it, a wall of points that no other scan saw. Left in the map it is a thin tall
//! obstacle the robot collides with where the building is open, or a wall.
//!
//! The scans, placed in one frame with their sensor origins, vote on each other's points:
//!
//! 1. Seen by another scan: a point with another scan's point within `persist_m` (a voxel grid
//!    of that edge, the 27 voxels around the point's) is of something that stayed; it is kept.
//!    Glass, which a beam passes through, stays for this reason: it returns some beams from
//!    every scan that looks at it.
//! 2. Seen through by another scan: every other scan looks along the direction of the point
//!    from its own sensor in its range image (bins of `bin_deg` in azimuth and elevation, the
//!    nearest return of each). If the bin of the point and each of its eight neighbours with a
//!    return hold returns farther than the point by `margin_m + margin_per_m` x its range (at
//!    least `min_bins_seen` of the nine with a return), that scan saw the space where the point
//!    is empty: the thing was not there when it looked.
//!
//! A point seen by no other scan and seen through by one is a transient: dropped. The nine
//! bins must all agree so that a point at a depth edge (where the bin holds the foreground
//! and its neighbours the background) or on a surface seen at grazing incidence by the other
//! scan is never taken for one; a thing that only one scan could see (behind a corner, under
//! a table) is kept because nobody saw through it.

use cloud::{check_range, PointCloud};
use glam::Vec3;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// Removal of moving things seen by one scan (`[transients]` of the configuration).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TransientConfig {
    /// Whether the scans of a sequence vote their transients out when they are merged.
    pub enabled: bool,
    /// Another scan's point within this (a voxel of this edge and its neighbours) sees the
    /// same thing. 0.15 m: the registration's residue (1-3 cm) and a 0.5 degree laser's sample
    /// spacing out to ~15 m are well within it; a person walks 0.15 m in 0.1 s.
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
    // 1. Which scans left points in each voxel.
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
                    p.is_finite()
                        && !voxels.seen_by_another(p, k)
                        && images
                            .iter()
                            .enumerate()
                            .any(|(j, im)| j != k && im.sees_through(p, c))
                })
                .collect()
        })
        .collect()
}

/// The scans that left points in a voxel: one scan's index, or `MANY`.
struct Voxels {
    edge_m: f32,
    cells: HashMap<[i32; 3], u32, BuildHasherDefault<KeyHasher>>,
}

const MANY: u32 = u32::MAX;

impl Voxels {
    fn build(scans: &[PointCloud], edge_m: f32) -> Voxels {
        let mut cells: HashMap<[i32; 3], u32, BuildHasherDefault<KeyHasher>> = HashMap::default();
        for (k, scan) in scans.iter().enumerate() {
            for p in scan.points.iter().filter(|p| p.is_finite()) {
                let e = cells.entry(key(*p, edge_m)).or_insert(k as u32);
                if *e != k as u32 {
                    *e = MANY;
                }
            }
        }
        Voxels { edge_m, cells }
    }

    /// Whether a scan other than `k` left a point in the voxel of `p` or one beside it.
    fn seen_by_another(&self, p: Vec3, k: usize) -> bool {
        let [x, y, z] = key(p, self.edge_m);
        (-1..=1).any(|dx| {
            (-1..=1).any(|dy| {
                (-1..=1).any(|dz| {
                    self.cells
                        .get(&[x + dx, y + dy, z + dz])
                        .is_some_and(|&s| s != k as u32)
                })
            })
        })
    }
}

fn key(p: Vec3, edge_m: f32) -> [i32; 3] {
    // Saturating casts: a coordinate beyond i32's range lands in the edge voxel.
    [
        (p.x / edge_m).floor() as i32,
        (p.y / edge_m).floor() as i32,
        (p.z / edge_m).floor() as i32,
    ]
}

/// A cheap hash of voxel keys (the standard one costs more than the lookups it serves).
#[derive(Default)]
struct KeyHasher(u64);

impl Hasher for KeyHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for b in bytes {
            self.0 = (self.0.rotate_left(8) ^ u64::from(*b)).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        }
    }

    fn write_i32(&mut self, v: i32) {
        self.0 = (self.0.rotate_left(21) ^ v as u32 as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    }
}

/// A scan's nearest return per direction bin around its sensor (`INFINITY`: no return).
struct RangeImage {
    origin: Vec3,
    bin_rad: f32,
    cols: usize,
    rows: usize,
    range: Vec<f32>,
}

impl RangeImage {
    fn build(scan: &PointCloud, bin_deg: f64) -> RangeImage {
        let bin_rad = (bin_deg.to_radians()) as f32;
        let cols = (std::f32::consts::TAU / bin_rad).ceil() as usize;
        let rows = (std::f32::consts::PI / bin_rad).ceil() as usize + 1;
        let mut im = RangeImage {
            origin: scan.sensor_origin,
            bin_rad,
            cols,
            rows,
            range: vec![f32::INFINITY; cols * rows],
        };
        for p in scan.points.iter().filter(|p| p.is_finite()) {
            if let Some((col, row, r)) = im.bin_of(*p) {
                let cell = &mut im.range[row * cols + col];
                *cell = cell.min(r);
            }
        }
        im
    }

    /// The bin of the direction of `p` from the sensor, and its range.
    fn bin_of(&self, p: Vec3) -> Option<(usize, usize, f32)> {
        let d = p - self.origin;
        let r = d.length();
        // At the sensor (or NaN): no direction.
        if r.is_nan() || r <= 1e-3 {
            return None;
        }
        let az = d.y.atan2(d.x) + std::f32::consts::PI;
        let el = (d.z / r).clamp(-1.0, 1.0).asin() + std::f32::consts::FRAC_PI_2;
        let col = ((az / self.bin_rad) as usize).min(self.cols - 1);
        let row = ((el / self.bin_rad) as usize).min(self.rows - 1);
        Some((col, row, r))
    }

    /// Whether this scan saw past `p`: the point's bin and its neighbours with a return (at
    /// least `min_bins_seen` of them) all hold returns beyond it by the margin.
    fn sees_through(&self, p: Vec3, c: &TransientConfig) -> bool {
        let Some((col, row, r)) = self.bin_of(p) else {
            return false;
        };
        let beyond = r + (c.margin_m + c.margin_per_m * r as f64) as f32;
        let mut seen = 0;
        for dr in -1i64..=1 {
            let rr = row as i64 + dr;
            if rr < 0 || rr >= self.rows as i64 {
                continue;
            }
            for dc in -1i64..=1 {
                // Azimuth wraps round.
                let cc = (col as i64 + dc).rem_euclid(self.cols as i64) as usize;
                let v = self.range[rr as usize * self.cols + cc];
                if v.is_finite() {
                    if v <= beyond {
                        return false;
                    }
                    seen += 1;
                }
            }
        }
        seen >= c.min_bins_seen
    }
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
}
