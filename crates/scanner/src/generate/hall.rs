//! The `hall` style: a wide open hall (16-24 x 12-18 m) whose east and north walls are not
//! at right angles to the others (the west wall too, often), a side room behind a partition
//! with an open doorway, a row of two to four pillars, tables with chairs, shelves against
//! the south wall, clutter along the walls and a straight staircase.

use super::furniture::{cabinet, chair, clutter, pillar, table, Place};
use super::layout::{wall, Layout};
use super::stairs::{flight, two_flights};
use crate::building::{Building, Door, Hinge, Leaf, Material, Swing};
use cloud::Rng;

/// Generates a hall from `seed`.
pub(super) fn generate(seed: u64) -> Building {
    let mut r = Rng::stream(seed, 0x4a11);
    let (w, d) = (r.range(16.0, 24.0), r.range(12.0, 18.0));
    let height = r.range(3.0, 4.0);
    let t = 0.2;
    // 1. The outline: p0 p1 on the x axis, p2 and p3 pushed off the rectangle's corners, so
    //    that the east and north walls lean by 5-17 degrees.
    let a = r.range(1.0, 3.0) * if r.chance(0.5) { 1.0 } else { -1.0 };
    let b = r.range(-1.5, 1.5);
    let c = r.range(-1.5, 1.5);
    let corners = [[0.0, 0.0], [w, 0.0], [w + a, d + b], [c, d]];
    let (xs, ys): (Vec<f64>, Vec<f64>) = corners.iter().map(|p| (p[0], p[1])).unzip();
    let lo = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = |v: &[f64]| v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let m = t + 0.1;
    let mut l = Layout::new(
        format!("generated hall, seed {seed}"),
        [lo(&xs) - m, lo(&ys) - m],
        [hi(&xs) + m, hi(&ys) + m],
        height,
    );
    let names = ["south", "east", "north", "west"];
    for k in 0..4 {
        let (p, q) = (corners[k], corners[(k + 1) % 4]);
        // Each wall reaches half a thickness past its corners, closing the joint.
        let len = (q[0] - p[0]).hypot(q[1] - p[1]);
        let u = [(q[0] - p[0]) / len, (q[1] - p[1]) / len];
        let e = t / 2.0;
        let start = [p[0] - u[0] * e, p[1] - u[1] * e];
        let end = [q[0] + u[0] * e, q[1] + u[1] * e];
        l.wall(wall(names[k], start, end, t), 0.0);
    }
    // 2. The side room's partition, from the south wall to the north wall, with a doorway.
    let x_part = c.max(0.0) + r.range(4.0, 5.0);
    let y_north = d + b * (x_part - c) / (w + a - c);
    let mut part = wall("partition", [x_part, t / 2.0], [x_part, y_north], 0.12);
    let door_w = r.range(0.9, 1.2);
    let leaf = r.chance(0.6).then(|| Leaf {
        hinge: Hinge::End,
        swing: Swing::Right,
        open_deg: r.range(85.0, 100.0),
        thickness_m: 0.04,
        material: if r.chance(0.3) {
            Material::Glass
        } else {
            Material::Matte
        },
    });
    part.doors.push(Door {
        offset_m: r.range(1.5, (y_north - t / 2.0 - door_w - 1.5).max(1.6)),
        width_m: door_w,
        height_m: r.range(2.0, 2.3),
        leaf,
    });
    l.wall(part, 1.3);
    // The hall's and the side room's inner rectangles (clear of the leaning walls).
    let top = d.min(d + b) - 0.6;
    let hall = [x_part + 0.3, 0.3, w.min(w + a) - 0.6, top];
    let room = [c.max(0.0) + 0.6, 0.3, x_part - 0.3, top];
    // 3. A row of pillars across the middle of the hall.
    let n = r.int(2, 4);
    let (x0, x1) = (hall[0] + 3.0, hall[2] - 3.0);
    let y_row = d / 2.0 + r.range(-1.0, 1.0);
    let side = r.range(0.35, 0.6);
    for k in 0..n {
        let x = x0 + (x1 - x0) * (k as f64 + 0.5) / n as f64;
        let (boxes, fp) = pillar(x, y_row, side, height, &format!("pillar {k}"));
        l.thing(fp, boxes);
    }
    // 4. A staircase against the south wall.
    let east = r.chance(0.5);
    let (x, dir) = if east {
        (hall[0] + 1.0, 0.0)
    } else {
        (hall[2] - 1.0, 180.0)
    };
    //    Every other hall's has a landing half-way (where two flights fit under the ceiling).
    let mut placed = false;
    if r.chance(0.5) {
        if let Some(mut f) = two_flights(&mut r, [x, 0.0], dir, 5.0, height, "stairs") {
            for s in &mut f {
                s.start_m[1] = t / 2.0 + 0.35 + s.width_m / 2.0;
            }
            placed = l.flights(f.to_vec());
        }
    }
    if !placed {
        if let Some(mut s) = flight(&mut r, [x, 0.0], dir, 5.0, height, "stairs") {
            s.start_m[1] = t / 2.0 + 0.35 + s.width_m / 2.0;
            l.stairs(s);
        }
    }
    // 5. Shelves against the south wall, tables with chairs, clutter along the walls.
    for k in 0..r.int(1, 3) {
        let p = Place {
            x: r.range(hall[0] + 1.0, hall[2] - 1.0),
            y: 0.35,
            yaw_deg: 0.0,
        };
        let (boxes, fp) = cabinet(&mut r, &p, &format!("shelf {k}"));
        let fp_in = fp.within([hall[0], 0.1, hall[2], hall[3]]);
        if fp_in {
            l.thing(fp, boxes);
        }
    }
    let mut tables = 0;
    for k in 0..40 {
        if tables >= 3 {
            break;
        }
        let in_room = k % 4 == 3;
        let rect = if in_room { room } else { hall };
        let p = Place {
            x: r.range(rect[0] + 1.0, rect[2] - 1.0),
            y: r.range(rect[1] + 1.0, rect[3] - 1.0),
            yaw_deg: r.range(0.0, 180.0),
        };
        let (boxes, fp) = table(&mut r, &p, &format!("table {tables}"));
        if !fp.grown(0.6).within(rect) || !l.is_free(&fp.grown(0.6)) {
            continue;
        }
        l.thing(fp.grown(0.05), boxes);
        let (s, c) = p.yaw_deg.to_radians().sin_cos();
        let off = fp.half[1] + 0.3;
        let cp = Place {
            x: p.x - s * off,
            y: p.y + c * off,
            yaw_deg: p.yaw_deg + 90.0,
        };
        let (boxes, cfp) = chair(&cp, &format!("chair {tables}"));
        l.thing(cfp, boxes);
        tables += 1;
    }
    for k in 0..r.int(2, 5) {
        let size = [r.range(0.4, 1.0), r.range(0.4, 0.8), r.range(0.4, 1.2)];
        let p = Place {
            x: r.range(hall[0] + 0.6, hall[2] - 0.6),
            y: hall[3] - size[1] / 2.0 - 0.05,
            yaw_deg: 0.0,
        };
        let (boxes, fp) = clutter(&p, size, &format!("crate {k}"));
        if fp.within(hall) {
            l.thing(fp, boxes);
        }
    }
    l.b
}
