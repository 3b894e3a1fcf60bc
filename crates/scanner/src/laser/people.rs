//! People walking past during a stop-and-scan. The laser rotates its scan plane step by step,
//! so every rotation step sees them where they are at that moment: a walking person becomes a
//! smeared streak rather than a body. They are vertical cylinders walking in straight lines at
//! a steady pace, seeded per scan; they are not part of the building, so their returns carry
//! the `unknown` label (entity 0), like every return that no building entity explains.

use crate::geometry::BuildingGeometry;
use cloud::{check_range, Rng};
use glam::{Vec2, Vec3};
use serde::{Deserialize, Serialize};

/// Walking people during the scan.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct People {
    /// How many people walk about during each scan (0: none).
    pub count: usize,
    /// Walking speed, metres per second.
    pub speed_m_s: f64,
    /// Radius of a person's cylinder, metres.
    pub radius_m: f64,
    /// Height of a person, metres.
    pub height_m: f64,
    /// How long one scan takes (all rotation steps), seconds.
    pub scan_duration_s: f64,
    /// The nearest a person starts from the sensor (horizontally), metres.
    pub min_distance_m: f64,
    /// The farthest a person starts from the sensor (horizontally), metres.
    pub max_distance_m: f64,
}

impl Default for People {
    fn default() -> Self {
        People::off()
    }
}

/// Tries to place each person outside every solid of the building before giving up on them.
const PLACEMENT_TRIES: usize = 64;

impl People {
    /// Nobody walks by.
    pub fn off() -> People {
        People {
            count: 0,
            ..People::real()
        }
    }

    /// The preset: two people at 1.3 m/s (a typical walking pace is 1.2-1.4 m/s), 0.25 m
    /// radius and 1.75 m tall (adult shoulders and height), starting 1-6 m from the sensor, in
    /// a scan of 8 s (301 line scans of an LMS 200 at 37.5 Hz, its 0.5 degree mode).
    pub fn real() -> People {
        People {
            count: 2,
            speed_m_s: 1.3,
            radius_m: 0.25,
            height_m: 1.75,
            scan_duration_s: 8.0,
            min_distance_m: 1.0,
            max_distance_m: 6.0,
        }
    }

    /// Checks the parameters.
    pub fn validate(&self) -> Result<(), cloud::InvalidParameter> {
        let p = |n: &'static str| format!("realism.people.{n}");
        check_range(p("count"), self.count as f64, 0.0, 50.0, "0..50 people")?;
        check_range(
            p("speed_m_s"),
            self.speed_m_s,
            0.0,
            10.0,
            "within 0..10 m/s",
        )?;
        check_range(p("radius_m"), self.radius_m, 0.05, 2.0, "within 0.05..2 m")?;
        check_range(p("height_m"), self.height_m, 0.1, 3.0, "within 0.1..3 m")?;
        check_range(
            p("scan_duration_s"),
            self.scan_duration_s,
            0.0,
            3600.0,
            "within 0..3600 s",
        )?;
        check_range(
            p("min_distance_m"),
            self.min_distance_m,
            0.0,
            1000.0,
            "within 0..1000 m",
        )?;
        check_range(
            p("max_distance_m"),
            self.max_distance_m,
            self.min_distance_m,
            1000.0,
            "within min_distance_m..1000 m",
        )?;
        Ok(())
    }

    /// Where the people are at every rotation step of one scan: `rows` lists of centres on
    /// the floor (world frame), one per person placed. People start around `sensor_xy`
    /// outside every solid of `geometry`, drawn from `rng`.
    pub(crate) fn walk(
        &self,
        geometry: &BuildingGeometry,
        sensor_xy: Vec2,
        rows: usize,
        rng: &mut Rng,
    ) -> Walkers {
        let mut tracks = Vec::new();
        for _ in 0..self.count {
            for _ in 0..PLACEMENT_TRIES {
                let r = rng.range(self.min_distance_m, self.max_distance_m) as f32;
                let a = rng.range(0.0, std::f64::consts::TAU) as f32;
                let heading = rng.range(0.0, std::f64::consts::TAU) as f32;
                let start = sensor_xy + Vec2::new(a.cos(), a.sin()) * r;
                let inside = |h: f32| geometry.entity_containing(start.extend(h)).is_some();
                if !inside(0.5 * self.height_m as f32) && !inside(0.9 * self.height_m as f32) {
                    tracks.push((start, Vec2::new(heading.cos(), heading.sin())));
                    break;
                }
            }
        }
        let dt = if rows > 1 {
            self.scan_duration_s / rows as f64
        } else {
            0.0
        };
        let at = (0..rows)
            .map(|j| {
                let walked = (self.speed_m_s * dt * j as f64) as f32;
                tracks.iter().map(|(s, d)| *s + *d * walked).collect()
            })
            .collect();
        Walkers {
            at,
            radius_m: self.radius_m as f32,
            height_m: self.height_m as f32,
        }
    }
}

/// The people of one scan, placed at every rotation step.
#[derive(Debug, Clone, Default)]
pub(crate) struct Walkers {
    /// Centres on the floor (world frame) per rotation step, one per person.
    pub(crate) at: Vec<Vec<Vec2>>,
    radius_m: f32,
    height_m: f32,
}

impl Walkers {
    /// The nearest person hit by the ray `origin + t * dir` (`dir` a unit vector, world
    /// frame) at rotation step `row`, within `max_t`: distance, outward unit normal and which
    /// person.
    pub(crate) fn cast(
        &self,
        row: usize,
        origin: Vec3,
        dir: Vec3,
        max_t: f32,
    ) -> Option<(f32, Vec3, usize)> {
        let people = self.at.get(row)?;
        let mut best: Option<(f32, Vec3, usize)> = None;
        for (q, c) in people.iter().enumerate() {
            if let Some((t, n)) = self.cast_one(*c, origin, dir) {
                if t < max_t && best.is_none_or(|b| t < b.0) {
                    best = Some((t, n, q));
                }
            }
        }
        best
    }

    /// A ray against one upright cylinder standing on the floor at `c`.
    fn cast_one(&self, c: Vec2, origin: Vec3, dir: Vec3) -> Option<(f32, Vec3)> {
        let (r, h) = (self.radius_m, self.height_m);
        let o = origin.truncate() - c;
        let d = dir.truncate();
        let mut best: Option<(f32, Vec3)> = None;
        // The side: |o + t d|^2 = r^2, entering (the smaller root), between floor and top.
        let a = d.length_squared();
        if a > 1e-12 {
            let b = o.dot(d);
            let disc = b * b - a * (o.length_squared() - r * r);
            if disc >= 0.0 {
                let t = (-b - disc.sqrt()) / a;
                let z = origin.z + t * dir.z;
                if t > 0.0 && (0.0..=h).contains(&z) {
                    best = Some((t, ((o + d * t) / r).extend(0.0)));
                }
            }
        }
        // The top, seen from above.
        if dir.z < 0.0 && origin.z > h {
            let t = (h - origin.z) / dir.z;
            let p = o + d * t;
            if p.length_squared() <= r * r && best.is_none_or(|b| t < b.0) {
                best = Some((t, Vec3::Z));
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ray_meets_the_cylinder_side_and_top_and_misses_above_it() {
        let w = Walkers {
            at: vec![vec![Vec2::new(3.0, 0.0)]],
            radius_m: 0.25,
            height_m: 1.75,
        };
        let (t, n, _) = w
            .cast(0, Vec3::new(0.0, 0.0, 0.5), Vec3::X, 10.0)
            .expect("side");
        assert!(
            (t - 2.75).abs() < 1e-5 && (n - Vec3::NEG_X).length() < 1e-5,
            "{t} {n}"
        );
        assert!(w.cast(0, Vec3::new(0.0, 0.0, 2.0), Vec3::X, 10.0).is_none());
        assert!(w.cast(0, Vec3::new(0.0, 0.0, 0.5), Vec3::X, 2.0).is_none());
        assert!(w.cast(1, Vec3::new(0.0, 0.0, 0.5), Vec3::X, 10.0).is_none());
        let (t, n, _) = w
            .cast(0, Vec3::new(3.0, 0.0, 3.0), Vec3::NEG_Z, 10.0)
            .expect("top");
        assert!((t - 1.25).abs() < 1e-5 && n == Vec3::Z, "{t} {n}");
    }
}
