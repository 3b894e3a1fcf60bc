//! Things made of boxes, each with its footprint: tables and chairs on legs, cabinets and
//! shelves, parked cars, pillars, and beams, ducts and pipes under the ceiling. Every box of
//! one thing carries the thing's name (e.g. `table 3`), so that a thing is its boxes.
//! Sizes are human scale: desks 0.72-0.76 m high, chairs' seats 0.45 m, cabinets 1.8-2.1 m,
//! cars 4.2-4.7 x 1.75-1.85 m.

use super::layout::Footprint;
use crate::building::{Furniture, Material};
use cloud::{EntityClass, Rng};

/// Where a thing stands: centre on the floor and yaw (degrees).
#[derive(Debug, Clone, Copy)]
pub(super) struct Place {
    pub x: f64,
    pub y: f64,
    pub yaw_deg: f64,
}

impl Place {
    /// The point `along`, `across` in the thing's own frame, in the world.
    fn at(&self, along: f64, across: f64) -> [f64; 2] {
        let (s, c) = self.yaw_deg.to_radians().sin_cos();
        [
            self.x + c * along - s * across,
            self.y + s * along + c * across,
        ]
    }

    /// The footprint `length` x `width` around it.
    pub fn footprint(&self, length: f64, width: f64) -> Footprint {
        Footprint {
            c: [self.x, self.y],
            half: [length / 2.0, width / 2.0],
            yaw: self.yaw_deg.to_radians(),
        }
    }
}

/// One box of a thing: offset in the thing's frame (along, across, z of its centre), size.
fn part(
    p: &Place,
    name: &str,
    class: EntityClass,
    material: Material,
    off: [f64; 3],
    size: [f64; 3],
) -> Furniture {
    let xy = p.at(off[0], off[1]);
    Furniture {
        name: name.into(),
        class,
        material,
        center_m: [xy[0], xy[1], off[2]],
        size_m: size,
        yaw_deg: p.yaw_deg,
    }
}

/// A table (or desk): a top on four legs. Returns its boxes and footprint.
pub(super) fn table(r: &mut Rng, p: &Place, name: &str) -> (Vec<Furniture>, Footprint) {
    let (len, wid, h) = (r.range(1.2, 1.8), r.range(0.7, 0.9), r.range(0.72, 0.76));
    let (top, leg) = (0.04, 0.05);
    let f = EntityClass::Furniture;
    let m = Material::Matte;
    let mut boxes = vec![part(
        p,
        name,
        f,
        m,
        [0.0, 0.0, h - top / 2.0],
        [len, wid, top],
    )];
    for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
        let off = [
            a * (len / 2.0 - leg),
            b * (wid / 2.0 - leg),
            (h - top) / 2.0,
        ];
        boxes.push(part(p, name, f, m, off, [leg, leg, h - top]));
    }
    (boxes, p.footprint(len, wid))
}

/// A chair: seat on four legs and a backrest on the `-along` side.
pub(super) fn chair(p: &Place, name: &str) -> (Vec<Furniture>, Footprint) {
    let (w, seat_h, leg) = (0.45, 0.45, 0.04);
    let f = EntityClass::Furniture;
    let m = Material::Matte;
    let mut boxes = vec![
        part(p, name, f, m, [0.0, 0.0, seat_h - 0.02], [w, w, 0.04]),
        part(
            p,
            name,
            f,
            m,
            [-w / 2.0 + 0.02, 0.0, seat_h + 0.22],
            [0.04, w, 0.4],
        ),
    ];
    for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
        let off = [
            a * (w / 2.0 - leg),
            b * (w / 2.0 - leg),
            (seat_h - 0.04) / 2.0,
        ];
        boxes.push(part(p, name, f, m, off, [leg, leg, seat_h - 0.04]));
    }
    (boxes, p.footprint(w, w))
}

/// A cabinet or shelf: one tall box (an obstacle), `length` along the wall it stands against.
pub(super) fn cabinet(r: &mut Rng, p: &Place, name: &str) -> (Vec<Furniture>, Footprint) {
    let (len, depth, h) = (r.range(0.8, 2.0), r.range(0.35, 0.6), r.range(1.8, 2.1));
    let material = if r.chance(0.3) {
        Material::Dark
    } else {
        Material::Matte
    };
    let b = part(
        p,
        name,
        EntityClass::Obstacle,
        material,
        [0.0, 0.0, h / 2.0],
        [len, depth, h],
    );
    (vec![b], p.footprint(len, depth))
}

/// Size of a parked car's footprint (length, width), metres.
pub(super) const CAR_M: [f64; 2] = [4.7, 1.85];

/// A parked car (an obstacle): body, cabin and four dark tyres, pointing along `+along`.
pub(super) fn car(r: &mut Rng, p: &Place, name: &str) -> (Vec<Furniture>, Footprint) {
    let (len, wid) = (r.range(4.2, CAR_M[0]), r.range(1.75, CAR_M[1]));
    let body_m = if r.chance(0.4) {
        Material::Dark
    } else {
        Material::Matte
    };
    let o = EntityClass::Obstacle;
    let (tyre_d, tyre_w) = (0.62, 0.22);
    let mut boxes = vec![
        part(
            p,
            name,
            o,
            body_m,
            [0.0, 0.0, 0.25 + 0.375],
            [len, wid, 0.75],
        ),
        part(
            p,
            name,
            o,
            body_m,
            [-0.2, 0.0, 1.0 + 0.22],
            [len * 0.5, wid - 0.15, 0.44],
        ),
    ];
    for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
        let off = [
            a * (len / 2.0 - 0.8),
            b * (wid / 2.0 - tyre_w / 2.0),
            tyre_d / 2.0,
        ];
        boxes.push(part(
            p,
            name,
            o,
            Material::Dark,
            off,
            [tyre_d, tyre_w, tyre_d],
        ));
    }
    (boxes, p.footprint(len, wid))
}

/// A pillar (a column) of `side` x `side` from the floor to the ceiling.
pub(super) fn pillar(
    x: f64,
    y: f64,
    side: f64,
    height: f64,
    name: &str,
) -> (Vec<Furniture>, Footprint) {
    let p = Place { x, y, yaw_deg: 0.0 };
    let b = part(
        &p,
        name,
        EntityClass::Column,
        Material::Matte,
        [0.0, 0.0, height / 2.0],
        [side, side, height],
    );
    (vec![b], p.footprint(side, side))
}

/// A beam, duct or pipe (class beam) from `a` to `b` (XY), `width` wide, hanging with its top
/// `gap` below the ceiling at `height` and `depth` deep.
pub(super) fn overhead(
    a: [f64; 2],
    b: [f64; 2],
    width: f64,
    depth: f64,
    height: f64,
    gap: f64,
    name: &str,
) -> (Vec<Furniture>, Footprint) {
    let fp = Footprint::segment(a, b, width);
    let f = Furniture {
        name: name.into(),
        class: EntityClass::Beam,
        material: Material::Matte,
        center_m: [fp.c[0], fp.c[1], height - gap - depth / 2.0],
        size_m: [2.0 * fp.half[0], width, depth],
        yaw_deg: fp.yaw.to_degrees(),
    };
    (vec![f], fp)
}

/// A small clutter box (a crate, a bin) of class furniture, `size` (x, y, z).
pub(super) fn clutter(p: &Place, size: [f64; 3], name: &str) -> (Vec<Furniture>, Footprint) {
    let b = part(
        p,
        name,
        EntityClass::Furniture,
        Material::Matte,
        [0.0, 0.0, size[2] / 2.0],
        size,
    );
    (vec![b], p.footprint(size[0], size[1]))
}
