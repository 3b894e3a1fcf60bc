//! A building under construction and the floor space its elements take: every wall piece,
//! staircase, ramp and thing on the floor has a footprint (an oriented rectangle), and a new
//! thing is placed only where its footprint overlaps none of them. Things under the ceiling
//! (beams, ducts) have footprints of their own, which staircases and ramps must avoid.

use crate::building::{Building, Ceiling, Door, Floor, Furniture, Material, Ramp, Staircase, Wall};

/// An oriented rectangle on the floor: centre, half sizes along its own axes, yaw.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Footprint {
    pub c: [f64; 2],
    pub half: [f64; 2],
    pub yaw: f64,
}

impl Footprint {
    /// An axis-aligned rectangle between two corners.
    #[cfg(test)]
    pub fn aabb(x0: f64, y0: f64, x1: f64, y1: f64) -> Footprint {
        Footprint {
            c: [(x0 + x1) / 2.0, (y0 + y1) / 2.0],
            half: [(x1 - x0).abs() / 2.0, (y1 - y0).abs() / 2.0],
            yaw: 0.0,
        }
    }

    /// The rectangle `along` x `across` centred on the segment from `a` to `b` (its length
    /// plus `along - |ab|`), e.g. a wall piece of thickness `across`.
    pub fn segment(a: [f64; 2], b: [f64; 2], across: f64) -> Footprint {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        Footprint {
            c: [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0],
            half: [dx.hypot(dy) / 2.0, across / 2.0],
            yaw: dy.atan2(dx),
        }
    }

    /// The same rectangle grown by `m` on every side.
    pub fn grown(&self, m: f64) -> Footprint {
        Footprint {
            half: [self.half[0] + m, self.half[1] + m],
            ..*self
        }
    }

    fn axes(&self) -> [[f64; 2]; 2] {
        let (s, c) = self.yaw.sin_cos();
        [[c, s], [-s, c]]
    }

    fn corners(&self) -> [[f64; 2]; 4] {
        let [u, v] = self.axes();
        let p = |a: f64, b: f64| {
            [
                self.c[0] + u[0] * a * self.half[0] + v[0] * b * self.half[1],
                self.c[1] + u[1] * a * self.half[0] + v[1] * b * self.half[1],
            ]
        };
        [p(-1.0, -1.0), p(1.0, -1.0), p(1.0, 1.0), p(-1.0, 1.0)]
    }

    /// True if the two rectangles' interiors overlap (separating axis test).
    pub fn overlaps(&self, o: &Footprint) -> bool {
        let (a, b) = (self.corners(), o.corners());
        for axis in self.axes().into_iter().chain(o.axes()) {
            let proj = |pts: &[[f64; 2]; 4]| {
                pts.iter()
                    .map(|p| p[0] * axis[0] + p[1] * axis[1])
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                        (lo.min(v), hi.max(v))
                    })
            };
            let ((a0, a1), (b0, b1)) = (proj(&a), proj(&b));
            if a1 <= b0 + 1e-9 || b1 <= a0 + 1e-9 {
                return false;
            }
        }
        true
    }

    /// True if every corner lies within the axis-aligned rectangle `[x0, y0, x1, y1]`.
    pub fn within(&self, rect: [f64; 4]) -> bool {
        self.corners()
            .iter()
            .all(|p| p[0] >= rect[0] && p[0] <= rect[2] && p[1] >= rect[1] && p[1] <= rect[3])
    }

    /// True if `p` lies inside.
    #[cfg(test)]
    pub fn contains(&self, p: [f64; 2]) -> bool {
        let [u, v] = self.axes();
        let d = [p[0] - self.c[0], p[1] - self.c[1]];
        (d[0] * u[0] + d[1] * u[1]).abs() <= self.half[0]
            && (d[0] * v[0] + d[1] * v[1]).abs() <= self.half[1]
    }
}

/// A building being generated, with the floor space and overhead space taken so far.
pub(super) struct Layout {
    pub b: Building,
    /// Footprints of everything standing on the floor, and of space kept free (door swings,
    /// passages).
    taken: Vec<Footprint>,
    /// Footprints of beams, ducts and pipes under the ceiling.
    overhead: Vec<Footprint>,
}

impl Layout {
    /// An empty building with the floor rectangle and ceiling.
    pub fn new(name: String, min_m: [f64; 2], max_m: [f64; 2], height_m: f64) -> Layout {
        Layout {
            b: Building {
                name,
                floor: Floor {
                    min_m,
                    max_m,
                    thickness_m: 0.2,
                },
                ceiling: Ceiling {
                    height_m,
                    thickness_m: 0.2,
                },
                walls: Vec::new(),
                stairs: Vec::new(),
                boxes: Vec::new(),
                ramps: Vec::new(),
            },
            taken: Vec::new(),
            overhead: Vec::new(),
        }
    }

    /// True if `fp` overlaps nothing on the floor (or kept free).
    pub fn is_free(&self, fp: &Footprint) -> bool {
        !self.taken.iter().any(|t| t.overlaps(fp))
    }

    /// True if `fp` lies under no beam, duct or pipe.
    pub fn is_open_above(&self, fp: &Footprint) -> bool {
        !self.overhead.iter().any(|t| t.overlaps(fp))
    }

    /// Keeps `fp` free of later things (a door's swing, a passage).
    pub fn keep_free(&mut self, fp: Footprint) {
        self.taken.push(fp);
    }

    /// Adds a wall; each solid piece beside its door openings takes floor space, and each
    /// opening keeps `clear_m` free on both sides (the leaf's swing and the way through).
    pub fn wall(&mut self, w: Wall, clear_m: f64) {
        let len = w.length_m();
        let u = [
            (w.end_m[0] - w.start_m[0]) / len,
            (w.end_m[1] - w.start_m[1]) / len,
        ];
        let at = |s: f64| [w.start_m[0] + u[0] * s, w.start_m[1] + u[1] * s];
        let mut doors: Vec<&Door> = w.doors.iter().collect();
        doors.sort_by(|a, b| a.offset_m.total_cmp(&b.offset_m));
        let mut s = 0.0;
        for d in &doors {
            if d.offset_m > s {
                self.taken
                    .push(Footprint::segment(at(s), at(d.offset_m), w.thickness_m));
            }
            let opening = Footprint::segment(at(d.offset_m), at(d.offset_m + d.width_m), 0.0);
            self.taken.push(Footprint {
                half: [opening.half[0], w.thickness_m / 2.0 + clear_m],
                ..opening
            });
            s = d.offset_m + d.width_m;
        }
        if len > s {
            self.taken
                .push(Footprint::segment(at(s), at(len), w.thickness_m));
        }
        self.b.walls.push(w);
    }

    /// Places a thing of several boxes if its footprint is free; true if placed.
    pub fn thing(&mut self, fp: Footprint, boxes: Vec<Furniture>) -> bool {
        if !self.is_free(&fp) {
            return false;
        }
        self.taken.push(fp);
        self.b.boxes.extend(boxes);
        true
    }

    /// Adds boxes under the ceiling (beams, ducts) with their footprint.
    pub fn overhead(&mut self, fp: Footprint, boxes: Vec<Furniture>) {
        self.overhead.push(fp);
        self.b.boxes.extend(boxes);
    }

    /// Places a staircase if its footprint (grown by a 0.3 m margin to walk round it) is free
    /// on the floor and open above; true if placed.
    /// The landing at its foot ([`FOOT_LANDING_M`] deep, as wide as the flight) is kept free
    /// too: a flight is climbed from the front.
    pub fn stairs(&mut self, s: Staircase) -> bool {
        let fp = stairs_footprint(&s);
        let foot = foot_landing(&s);
        if !self.is_free(&fp.grown(0.3)) || !self.is_free(&foot) || !self.is_open_above(&fp) {
            return false;
        }
        self.taken.push(fp.grown(0.3));
        self.taken.push(foot);
        self.b.stairs.push(s);
        true
    }

    /// Places the flights of one staircase (a flight and the one starting on its landing) if
    /// all their footprints (grown by 0.3 m) and the first flight's foot landing are free and
    /// open above; true if placed.
    pub fn flights(&mut self, flights: Vec<Staircase>) -> bool {
        let fps: Vec<Footprint> = flights.iter().map(stairs_footprint).collect();
        let feet: Vec<Footprint> = flights
            .iter()
            .filter(|s| s.base_m == 0.0)
            .map(foot_landing)
            .collect();
        if !fps
            .iter()
            .all(|fp| self.is_free(&fp.grown(0.3)) && self.is_open_above(fp))
            || !feet.iter().all(|f| self.is_free(f))
        {
            return false;
        }
        self.taken.extend(fps.iter().map(|fp| fp.grown(0.3)));
        self.taken.extend(feet);
        self.b.stairs.extend(flights);
        true
    }

    /// Places a ramp if its footprint (grown by 0.3 m) is free and open above; true if placed.
    pub fn ramp(&mut self, r: Ramp) -> bool {
        let fp = ramp_footprint(&r);
        if !self.is_free(&fp.grown(0.3)) || !self.is_open_above(&fp) {
            return false;
        }
        self.taken.push(fp.grown(0.3));
        self.b.ramps.push(r);
        true
    }
}

/// The floor rectangle a staircase covers (steps and landing).
fn stairs_footprint(s: &Staircase) -> Footprint {
    let a = s.direction_deg.to_radians();
    let len = s.steps as f64 * s.run_m + s.landing_m;
    Footprint {
        c: [
            s.start_m[0] + a.cos() * len / 2.0,
            s.start_m[1] + a.sin() * len / 2.0,
        ],
        half: [len / 2.0, s.width_m / 2.0],
        yaw: a,
    }
}

/// How deep the clear landing at a flight's foot is (m): building codes ask at least the
/// stair's width or about 0.9 m; the generated flights are 0.9-1.3 m wide.
pub const FOOT_LANDING_M: f64 = 0.9;

/// The floor in front of a flight's first riser kept clear to walk onto it
/// ([`FOOT_LANDING_M`] deep, as wide as the flight).
fn foot_landing(s: &Staircase) -> Footprint {
    let a = s.direction_deg.to_radians();
    let back = FOOT_LANDING_M / 2.0;
    Footprint {
        c: [s.start_m[0] - a.cos() * back, s.start_m[1] - a.sin() * back],
        half: [back, s.width_m / 2.0],
        yaw: a,
    }
}

/// The floor rectangle a ramp covers.
fn ramp_footprint(r: &Ramp) -> Footprint {
    let d = r.direction();
    Footprint {
        c: [
            r.start_m[0] + d[0] * r.length_m / 2.0,
            r.start_m[1] + d[1] * r.length_m / 2.0,
        ],
        half: [r.length_m / 2.0, r.width_m / 2.0],
        yaw: r.direction_deg.to_radians(),
    }
}

/// A full-height wall without doors.
pub(super) fn wall(name: &str, start_m: [f64; 2], end_m: [f64; 2], thickness_m: f64) -> Wall {
    Wall {
        name: name.into(),
        start_m,
        end_m,
        thickness_m,
        height_m: None,
        doors: Vec::new(),
        material: Material::Matte,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotated_rectangles_overlap_only_when_they_do() {
        let a = Footprint::aabb(0.0, 0.0, 2.0, 1.0);
        assert!(a.overlaps(&Footprint::aabb(1.9, 0.5, 3.0, 2.0)));
        assert!(
            !a.overlaps(&Footprint::aabb(2.0, 0.0, 3.0, 1.0)),
            "touching"
        );
        // A diamond whose corner points at a's corner from outside: no overlap, though the
        // axis-aligned boxes would.
        let diamond = Footprint {
            c: [2.6, 1.6],
            half: [0.5, 0.5],
            yaw: std::f64::consts::FRAC_PI_4,
        };
        assert!(!a.overlaps(&diamond));
        assert!(a.overlaps(&Footprint {
            c: [2.3, 1.3],
            ..diamond
        }));
        assert!(diamond.contains([2.3, 1.3]) && !diamond.contains([2.0, 1.0]));
    }
}
