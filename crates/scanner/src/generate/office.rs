//! The `office` style: a corridor with rooms on both sides; desks and chairs on legs, cabinets
//! and shelves against the walls, one glass partition between rooms and one glass door, a
//! partial-height partition (1.2-1.5 m) in a room, a crate against a doorway's jamb (the way
//! through stays at least 0.6 m wide), and one or two straight staircases.
//! Ranges: corridor 16-26 m long and 1.8-2.6 m wide, rooms 4-6 m deep and 4-6.5 m wide,
//! ceilings 2.6-3.1 m: ordinary office floors.

use super::furniture::{cabinet, chair, clutter, table, Place};
use super::layout::{wall, Footprint, Layout, FOOT_LANDING_M};
use super::stairs::{flight, two_flights};
use crate::building::{Building, Door, Hinge, Leaf, Material, Swing, Wall};
use cloud::Rng;

/// A room: its inner rectangle and its side of the corridor.
struct Room {
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    north: bool,
}

/// Generates an office floor from `seed`.
pub(super) fn generate(seed: u64) -> Building {
    let mut r = Rng::stream(seed, 0x0ff1ce);
    let len = r.range(16.0, 26.0);
    let half_w = r.range(0.9, 1.3);
    let height = r.range(2.6, 3.1);
    let t = 0.15;
    let (depth_n, depth_s) = (r.range(4.0, 6.0), r.range(4.0, 6.0));
    let (yn, ys) = (half_w + t / 2.0, -half_w - t / 2.0);
    let (yn_out, ys_out) = (yn + depth_n, ys - depth_s);
    let mut l = Layout::new(
        format!("generated office, seed {seed}"),
        [-t - 0.1, ys_out - t - 0.1],
        [len + t + 0.1, yn_out + t + 0.1],
        height,
    );
    // 1. The outer walls.
    for (name, a, b) in [
        ("south outer", [-t / 2.0, ys_out], [len + t / 2.0, ys_out]),
        ("north outer", [-t / 2.0, yn_out], [len + t / 2.0, yn_out]),
        ("west outer", [0.0, ys_out], [0.0, yn_out]),
        ("east outer", [len, ys_out], [len, yn_out]),
    ] {
        l.wall(wall(name, a, b, t), 0.0);
    }
    // 2. Rooms along both sides, separated by partitions (one of glass).
    let mut rooms = Vec::new();
    let mut partitions = Vec::new();
    for north in [true, false] {
        let (a, b) = if north {
            (yn + t / 2.0, yn_out - t / 2.0)
        } else {
            (ys_out + t / 2.0, ys - t / 2.0)
        };
        let mut x0 = 0.0;
        while len - x0 > 4.0 {
            let w = r.range(4.0, 6.5);
            let x1 = if len - (x0 + w) < 4.0 { len } else { x0 + w };
            if x1 < len {
                partitions.push(wall("partition", [x1, a], [x1, b], t));
            }
            rooms.push(Room {
                x0: x0 + t / 2.0,
                x1: x1 - t / 2.0,
                y0: a,
                y1: b,
                north,
            });
            x0 = x1;
        }
    }
    if !partitions.is_empty() {
        let k = r.int(0, partitions.len() as i64 - 1) as usize;
        partitions[k].material = Material::Glass;
        partitions[k].name = "glass partition".into();
    }
    for p in partitions {
        l.wall(p, 0.0);
    }
    // 3. One door per room in the corridor walls: mostly open (a surveyor enters), one
    //    half-open, one closed, one without a leaf; one leaf of glass.
    let glass_door = r.int(0, rooms.len() as i64 - 1) as usize;
    let mut doors = [Vec::new(), Vec::new()];
    let mut openings = Vec::new();
    for (i, room) in rooms.iter().enumerate() {
        let width = r.range(0.9, 1.2);
        let centre = r.range(room.x0 + 0.5 + width / 2.0, room.x1 - 0.5 - width / 2.0);
        let open_deg = match i % 5 {
            1 => Some(r.range(35.0, 60.0)),
            3 => Some(0.0),
            4 => None,
            _ => Some(r.range(85.0, 100.0)),
        };
        let leaf = open_deg.map(|open_deg| Leaf {
            hinge: if r.chance(0.5) {
                Hinge::Start
            } else {
                Hinge::End
            },
            swing: if room.north {
                Swing::Left
            } else {
                Swing::Right
            },
            open_deg,
            thickness_m: 0.04,
            material: if i == glass_door {
                Material::Glass
            } else {
                Material::Matte
            },
        });
        openings.push((centre, width, leaf.as_ref().map_or(90.0, |l| l.open_deg)));
        doors[usize::from(!room.north)].push(Door {
            offset_m: centre - width / 2.0 - t / 2.0,
            width_m: width,
            height_m: r.range(2.0, 2.2).min(height - 0.2),
            leaf,
        });
    }
    for (k, (name, y)) in [("corridor north", yn), ("corridor south", ys)]
        .into_iter()
        .enumerate()
    {
        let mut w: Wall = wall(name, [t / 2.0, y], [len - t / 2.0, y], t);
        w.doors = std::mem::take(&mut doors[k]);
        // Keep the leaf's swing and the way through free: a leaf is at most 1.2 m wide.
        l.wall(w, 1.3);
    }
    // 4. Staircases along the far wall of the two largest rooms (the second if it fits).
    let mut by_size: Vec<usize> = (0..rooms.len()).collect();
    by_size.sort_by(|&a, &b| {
        let area = |r: &Room| (r.x1 - r.x0) * (r.y1 - r.y0);
        area(&rooms[b]).total_cmp(&area(&rooms[a]))
    });
    for (n, &i) in by_size.iter().take(2).enumerate() {
        let room = &rooms[i];
        let east = r.chance(0.5);
        // The first riser stands a foot landing away from the side wall (a flight is climbed
        // from the front); the top landing keeps 0.35 m from the far wall.
        let foot = 0.05 + FOOT_LANDING_M;
        let (x, dir) = if east {
            (room.x0 + foot, 0.0)
        } else {
            (room.x1 - foot, 180.0)
        };
        let max_len = room.x1 - room.x0 - foot - 0.35;
        // The largest room's staircase has a landing half-way where it fits.
        let y_for = |width: f64| {
            if room.north {
                room.y1 - 0.35 - width / 2.0
            } else {
                room.y0 + 0.35 + width / 2.0
            }
        };
        if n == 0 {
            if let Some(mut f) = two_flights(&mut r, [x, 0.0], dir, max_len, height, "stairs 0") {
                let y = y_for(f[0].width_m);
                for s in &mut f {
                    s.start_m[1] = y;
                }
                if l.flights(f.to_vec()) {
                    continue;
                }
            }
        }
        if let Some(mut s) = flight(
            &mut r,
            [x, 0.0],
            dir,
            max_len,
            height,
            &format!("stairs {n}"),
        ) {
            s.start_m[1] = if room.north {
                room.y1 - 0.35 - s.width_m / 2.0
            } else {
                room.y0 + 0.35 + s.width_m / 2.0
            };
            l.stairs(s);
        }
    }
    // 5. Furniture, a partial-height partition from a far wall, clutter.
    furnish(&mut r, &mut l, &rooms);
    // 6. A crate against the jamb of a wide open doorway, on the corridor side.
    if let Some((i, &(centre, width, _))) = openings
        .iter()
        .enumerate()
        .find(|(_, o)| o.1 >= 1.0 && o.2 >= 80.0)
    {
        let side = r.range(0.3, 0.35);
        let sign = if rooms[i].north { 1.0 } else { -1.0 };
        let y_wall = if rooms[i].north { yn } else { ys };
        let p = Place {
            x: centre - width / 2.0 + 0.02 + side / 2.0,
            y: y_wall - sign * (t / 2.0 + 0.02 + side / 2.0),
            yaw_deg: 0.0,
        };
        let (boxes, fp) = clutter(&p, [side, side, r.range(0.4, 0.7)], "doorway crate");
        l.keep_free(fp);
        l.b.boxes.extend(boxes);
    }
    l.b
}

/// Desks with chairs, cabinets, a partial partition and clutter in each room.
fn furnish(r: &mut Rng, l: &mut Layout, rooms: &[Room]) {
    // A partial-height partition from the far wall, in the first room with space for it
    // (clear of stairs and door swings, 0.3 m to walk round its free end).
    for room in rooms.iter().filter(|r| r.x1 - r.x0 > 4.5) {
        let x = (room.x0 + room.x1) / 2.0 + r.range(-0.5, 0.5);
        let length = r.range(1.5, 2.0);
        let sign = if room.north { -1.0 } else { 1.0 };
        let far = if room.north { room.y1 } else { room.y0 };
        let (a, b) = ([x, far], [x, far + sign * length]);
        // Its footprint, pulled 0.35 m off the far wall (which it touches) and grown 0.3 m.
        let probe = Footprint::segment([x, far + sign * 0.35], b, 0.08).grown(0.3);
        if l.is_free(&probe) {
            let mut w = wall("partial partition", a, b, 0.08);
            w.height_m = Some(r.range(1.2, 1.5));
            l.wall(w, 0.0);
            break;
        }
    }
    for (i, room) in rooms.iter().enumerate() {
        let name = |what: &str| format!("{what} {i}");
        // A cabinet or shelf against the far wall, then a desk with one or two chairs.
        for k in 0..2 {
            let (boxes, fp) = {
                let x = r.range(room.x0 + 1.0, room.x1 - 1.0);
                let y_depth = r.range(0.35, 0.6);
                let y = if room.north {
                    room.y1 - 0.03 - y_depth / 2.0
                } else {
                    room.y0 + 0.03 + y_depth / 2.0
                };
                let p = Place { x, y, yaw_deg: 0.0 };
                cabinet(r, &p, &name(&format!("cabinet {k}")))
            };
            if inside(room, &fp) {
                l.thing(fp, boxes);
            }
        }
        for _ in 0..20 {
            let p = Place {
                x: r.range(room.x0 + 1.2, room.x1 - 1.2),
                y: r.range(room.y0 + 1.2, room.y1 - 1.2),
                yaw_deg: if r.chance(0.5) { 0.0 } else { 90.0 },
            };
            let (boxes, fp) = table(r, &p, &name("desk"));
            // The desk and a chair on each long side need room round them.
            if inside(room, &fp.grown(0.6)) && l.thing(fp.grown(0.05), boxes) {
                let (s, c) = p.yaw_deg.to_radians().sin_cos();
                for (k, side) in [1.0, -1.0]
                    .into_iter()
                    .enumerate()
                    .take(r.int(1, 2) as usize)
                {
                    let off = fp.half[1] + 0.3;
                    let cp = Place {
                        x: p.x - s * side * off,
                        y: p.y + c * side * off,
                        yaw_deg: p.yaw_deg + if side > 0.0 { 90.0 } else { -90.0 },
                    };
                    let (boxes, cfp) = chair(&cp, &name(&format!("chair {k}")));
                    if inside(room, &cfp) {
                        l.thing(cfp, boxes);
                    }
                }
                break;
            }
        }
        // Clutter boxes.
        for k in 0..r.int(0, 2) {
            let size = [r.range(0.3, 0.8), r.range(0.3, 0.6), r.range(0.3, 0.9)];
            let p = Place {
                x: r.range(room.x0 + 0.5, room.x1 - 0.5),
                y: r.range(room.y0 + 0.5, room.y1 - 0.5),
                yaw_deg: r.range(-45.0, 45.0),
            };
            let (boxes, fp) = clutter(&p, size, &name(&format!("box {k}")));
            if inside(room, &fp) {
                l.thing(fp, boxes);
            }
        }
    }
}

/// True if `fp` lies in the room, 5 cm clear of its walls.
fn inside(room: &Room, fp: &Footprint) -> bool {
    fp.within([
        room.x0 + 0.05,
        room.y0 + 0.05,
        room.x1 - 0.05,
        room.y1 - 0.05,
    ])
}
