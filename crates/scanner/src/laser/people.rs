//! People walking past during a stop-and-scan. The laser rotates its scan plane step by step,
//! so every rotation step sees them where they are at that moment: a walking person becomes a
//! smeared streak rather than a body. They are vertical cylinders walking in straight lines at
//! a steady pace, seeded per scan, and turning away from a solid where the next step would take
//! them into it (a wall, a parked car, a cabinet: nobody walks through one, and a streak inside a
//! car's body, where no other scan can see past it, is a thing no real survey shows); they are not
//! part of the building, so their returns carry the `unknown` label (entity 0), like every
//! return that no building entity explains.

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
                let heading = Vec2::new(heading.cos(), heading.sin());
                if self.stands_clear(geometry, start) {
                    tracks.push((start, heading));
                    break;
                }
            }
        }
        let dt = if rows > 1 {
            self.scan_duration_s / rows as f64
        } else {
            0.0
        };
        let step = (self.speed_m_s * dt) as f32;
        // Each person's place at every rotation step: a step on where that stands clear; where
        // it does not, they turn away from the solid, their heading mirrored across its face
        // (the building's axes stand for its faces': across a face along y first, then along
        // x; else back), and walk on that way; where none is clear, they stand. (Turning along
        // the solid instead keeps them brushing its face, which a person walking does not.)
        let mut walking = tracks;
        let mut at = Vec::with_capacity(rows);
        for j in 0..rows {
            if j > 0 {
                for (here, heading) in &mut walking {
                    (*here, *heading) = self.step_on(geometry, *here, *heading, step);
                }
            }
            at.push(walking.iter().map(|(here, _)| *here).collect());
        }
        Walkers {
            at,
            radius_m: self.radius_m as f32,
            height_m: self.height_m as f32,
        }
    }
}

impl People {
    /// Where a person at `here` walking along `heading` (a unit vector) is a step of `step`
    /// later, and their heading then (see [`People::walk`]).
    fn step_on(
        &self,
        geometry: &BuildingGeometry,
        here: Vec2,
        heading: Vec2,
        step: f32,
    ) -> (Vec2, Vec2) {
        let (x, y) = (heading.x, heading.y);
        let ways = [heading, Vec2::new(-x, y), Vec2::new(x, -y), -heading];
        ways.into_iter()
            .find(|w| self.stands_clear(geometry, here + *w * step))
            .map_or((here, heading), |way| (here + way * step, way))
    }

    /// True if a person standing at `c` is clear of every solid of `geometry`: their axis and
    /// eight points round their body, at their knees, waist and shoulders (a low crate, a car's
    /// body, a desk's top; the floor and a ceiling are out of reach).
    fn stands_clear(&self, geometry: &BuildingGeometry, c: Vec2) -> bool {
        let (h, r) = (self.height_m as f32, self.radius_m as f32);
        let round = (0..8).map(|k| {
            let a = k as f32 * std::f32::consts::FRAC_PI_4;
            c + Vec2::new(a.cos(), a.sin()) * r
        });
        std::iter::once(c).chain(round).all(|q| {
            BODY_HEIGHTS
                .iter()
                .all(|f| geometry.entity_containing(q.extend(f * h)).is_none())
        })
    }
}

/// Where a person's body is looked at for solids, as shares of their height: knees, waist,
/// shoulders.
const BODY_HEIGHTS: [f32; 3] = [0.25, 0.5, 0.85];

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

    /// A room 10 x 6 m with a parked car's body (4.6 x 1.8 m, 0.25-1.0 m up) at x = 4..8.6.
    fn room_with_a_car() -> BuildingGeometry {
        let toml = r#"
            [floor]
            min_m = [0.0, 0.0]
            max_m = [10.0, 6.0]
            [ceiling]
            height_m = 2.5
            [[walls]]
            start_m = [0.0, 6.0]
            end_m = [10.0, 6.0]
            thickness_m = 0.15
            [[boxes]]
            name = "car"
            center_m = [6.3, 3.0, 0.625]
            size_m = [4.6, 1.8, 0.75]
            "#;
        let b =
            crate::Building::from_toml_str(toml, std::path::Path::new("car.toml")).expect("valid");
        BuildingGeometry::new(&b)
    }

    #[test]
    fn a_person_walking_at_a_car_or_a_wall_turns_away_from_it() {
        // garage-495 of seeds 491-495: a person walked 1 m into a car's body, and their streak
        // over its bonnet and under its bumper read as a partial-height wall across the car.
        let g = room_with_a_car();
        let people = People {
            count: 1,
            min_distance_m: 1.0,
            max_distance_m: 3.0,
            ..People::real()
        };
        let (mut turned, mut straight) = (0, 0);
        for seed in 0..40 {
            let w = people.walk(&g, Vec2::new(2.0, 3.0), 301, &mut Rng::new(seed));
            let Some(track) =
                w.at.iter()
                    .map(|row| row.first().copied())
                    .collect::<Option<Vec<_>>>()
            else {
                continue;
            };
            let (first, last) = (track[0], track[track.len() - 1]);
            // Never inside the car or the wall, at any step: its axis clear at the waist.
            for q in &track {
                assert!(
                    g.entity_containing(q.extend(0.875)).is_none(),
                    "seed {seed}: {q} inside"
                );
            }
            // Turned where a solid stood in the way (ending nearer their start than the 10.4 m
            // of an 8 s scan at 1.3 m/s), straight on where none did, a step at every rotation
            // step.
            if (last - first).length() < 10.0 {
                turned += 1;
            } else {
                straight += 1;
            }
            let walked: f32 = track.windows(2).map(|w| (w[1] - w[0]).length()).sum();
            assert!(
                (walked - 10.4 * 300.0 / 301.0).abs() < 0.01,
                "seed {seed}: {walked}"
            );
        }
        assert!(turned > 0 && straight > 0, "{turned} {straight}");
    }

    #[test]
    fn a_person_meeting_a_car_head_on_walks_away_from_it() {
        // 5 degrees off square to the car's west face (x = 4): mirrored, they leave it as they
        // came; a quarter turn along the face instead would keep them brushing it (office-493
        // of seeds 491-495, walkers turning so: a person read along a glass partition by two
        // scans, the partition lost).
        let g = room_with_a_car();
        let people = People::real();
        let step = 1.3 * 8.0 / 301.0;
        let a = 5f32.to_radians();
        let (mut here, mut heading) = (Vec2::new(3.0, 3.0), Vec2::new(a.cos(), a.sin()));
        let (mut met, mut brushing) = (false, 0);
        for _ in 0..100 {
            (here, heading) = people.step_on(&g, here, heading, step);
            let gap = 4.0 - here.x - 0.25;
            assert!(gap >= 0.0, "{here} in the car");
            met |= heading.x < 0.0;
            brushing += usize::from(gap < 0.05);
        }
        assert!(brushing <= 3, "{brushing} steps within 5 cm of the car");
        assert!(met && heading.y > 0.0, "{heading}");
        assert!(here.x < 2.0, "{here}");
    }

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
