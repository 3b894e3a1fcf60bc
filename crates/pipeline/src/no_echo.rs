//! No-echo readings: where a beam comes back with nothing, many scanners write a reading at a
//! fixed range (3DTK's SICK scans: 32.767 m, the largest 16-bit millimetre count) instead of
//! leaving the cell empty. Kept, they are a sphere of phantom points around the sensor that
//! dominates the map's extent and pulls registration.
//!
//! They are found from the scan itself, with no knowledge of the sensor: a real surface never
//! puts a large share of a scan's points within a centimetre of its farthest range, while a
//! no-echo value puts every missing return there. So the readings within
//! [`NO_ECHO_BAND_M`] of the farthest one are no-echo readings when they are at least
//! [`NO_ECHO_MIN_SHARE`] of the scan (and at least [`NO_ECHO_MIN_POINTS`]).

use cloud::PointCloud;

/// How close to the farthest reading a no-echo reading lies (the value's own rounding: 3DTK
/// writes centimetres with two decimals, so 32.767 m reads back between 32.763 and 32.767 m).
pub const NO_ECHO_BAND_M: f32 = 0.01;
/// The least share of a scan's points at the farthest range that makes them no-echo readings.
pub const NO_ECHO_MIN_SHARE: f64 = 0.002;
/// The least number of such points.
pub const NO_ECHO_MIN_POINTS: usize = 20;

/// The no-echo readings found in a scan.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NoEcho {
    /// The range the sensor writes for no echo (the farthest reading), metres.
    pub range_m: f32,
    /// How many readings lie within [`NO_ECHO_BAND_M`] of it.
    pub count: usize,
}

/// The scan's no-echo readings, if it has a pile-up at its farthest range (see the module
/// docs). Ranges are measured from the scan's sensor; non-finite points are ignored.
pub fn find_no_echo(scan: &PointCloud) -> Option<NoEcho> {
    let ranges = || {
        scan.points
            .iter()
            .filter(|p| p.is_finite())
            .map(|p| p.distance(scan.sensor_origin))
    };
    let farthest = ranges().fold(f32::NEG_INFINITY, f32::max);
    if !farthest.is_finite() {
        return None;
    }
    let total = ranges().count();
    let count = ranges().filter(|&r| r >= farthest - NO_ECHO_BAND_M).count();
    let enough = count >= NO_ECHO_MIN_POINTS && count as f64 >= NO_ECHO_MIN_SHARE * total as f64;
    enough.then_some(NoEcho {
        range_m: farthest,
        count,
    })
}

/// The scan without its no-echo readings, and what was dropped. An organised scan keeps its
/// shape: they become NaN (the missing-return convention); from other scans they are deleted.
pub fn drop_no_echo(scan: &PointCloud) -> (PointCloud, Option<NoEcho>) {
    let Some(found) = find_no_echo(scan) else {
        return (scan.clone(), None);
    };
    let limit = found.range_m - NO_ECHO_BAND_M;
    if scan.organized.is_some() {
        let mut out = scan.clone();
        for p in &mut out.points {
            if p.is_finite() && p.distance(scan.sensor_origin) >= limit {
                *p = glam::Vec3::NAN;
            }
        }
        return (out, Some(found));
    }
    let keep: Vec<usize> = (0..scan.len())
        .filter(|&i| {
            let p = scan.points[i];
            !p.is_finite() || p.distance(scan.sensor_origin) < limit
        })
        .collect();
    (scan.select(&keep), Some(found))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// A box room 8 x 6 x 3 m around the sensor, sampled on a grid of its walls.
    fn room() -> Vec<Vec3> {
        let mut points = Vec::new();
        for i in 0..80 {
            for k in 0..30 {
                let (x, z) = (i as f32 * 0.1 - 4.0, k as f32 * 0.1 - 1.0);
                points.push(Vec3::new(x, 3.0, z));
                points.push(Vec3::new(x, -3.0, z));
            }
        }
        points
    }

    #[test]
    fn a_pile_up_at_the_farthest_range_is_found_and_dropped() {
        let mut points = room();
        let real = points.len();
        // 2 % of the readings at 32.767 m in many directions, rounded as 3DTK writes them.
        for i in 0..(real / 50) {
            let a = i as f32 * 0.37;
            let r = 32.767 - (i % 5) as f32 * 0.001;
            points.push(Vec3::new(a.cos() * r, a.sin() * r, 0.0));
        }
        let scan = PointCloud::from_points(points);
        let found = find_no_echo(&scan).expect("found");
        assert!((found.range_m - 32.767).abs() < 1e-3, "{found:?}");
        assert_eq!(found.count, real / 50);
        let (kept, dropped) = drop_no_echo(&scan);
        assert_eq!(dropped, Some(found));
        assert_eq!(kept.len(), real);
        assert!(kept.points.iter().all(|p| p.length() < 6.0));
    }

    #[test]
    fn a_real_far_wall_is_no_no_echo_value() {
        // The room alone: its farthest corners hold a handful of points, not a pile-up.
        let scan = PointCloud::from_points(room());
        assert_eq!(find_no_echo(&scan), None);
        let (kept, dropped) = drop_no_echo(&scan);
        assert_eq!((kept.len(), dropped), (scan.len(), None));
        // A few stray far readings are not enough either.
        let mut points = room();
        points.extend((0..5).map(|i| Vec3::new(30.0, i as f32 * 0.001, 0.0)));
        assert_eq!(find_no_echo(&PointCloud::from_points(points)), None);
        assert_eq!(find_no_echo(&PointCloud::from_points(Vec::new())), None);
    }
}
